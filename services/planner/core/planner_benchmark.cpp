// Planner tick, 11 v 11, under several referee commands; the budget is on the match cycle with trajectories
// (BM_PlannerTickMatchCycleTrajectoriesP99's p99_us, in ./ssl bench's table: bench/budget_table.cpp).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "services/planner/core/planner.h"
#include "services/planner/core/planner_test_util.h"
#include "services/planner/core/team_play.h"

namespace ssl::planner {
namespace {

using testing::Restart;
using testing::Script;
using testing::Side;
using wm::RefereeCommand;

void run(benchmark::State& state, RefereeCommand command, std::optional<RefereeCommand> next = std::nullopt,
         std::optional<Vec2> designated = std::nullopt) {
  Script script(Side{TeamColor::kBlue, true});
  script.default_teams();
  script.set_ball({1.2, -0.7});
  script.command(command, next, designated);
  Planner planner(testing::config_for(script.side()));
  const PlannerInputs inputs = script.inputs();
  PlannerOutput out;
  int tick = 0;
  for (auto _ : state) {
    planner.step(inputs, testing::at_tick(tick++), out);
    benchmark::DoNotOptimize(out.commands.data());
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_PlannerTickHalt(benchmark::State& s) { run(s, RefereeCommand::kHalt); }
void BM_PlannerTickStop(benchmark::State& s) {
  run(s, RefereeCommand::kStop, RefereeCommand::kDirectFreeBlue);
}
void BM_PlannerTickOurKickoff(benchmark::State& s) { run(s, RefereeCommand::kPrepareKickoffBlue); }
void BM_PlannerTickTheirFreeKick(benchmark::State& s) { run(s, RefereeCommand::kDirectFreeYellow); }
void BM_PlannerTickOurPlacement(benchmark::State& s) {
  run(s, RefereeCommand::kBallPlacementBlue, RefereeCommand::kDirectFreeBlue, Vec2(-2.0, 1.0));
}
void BM_PlannerTickNormalPlay(benchmark::State& s) { run(s, RefereeCommand::kForceStart); }

/// Cycles through the referee commands of a match (a command change every 50 ticks) and reports the
/// tick-time percentiles as counters (p50_us, p99_us, max_us).
void match_cycle(benchmark::State& state, MotionControl motion) {
  Script script(Side{TeamColor::kYellow, false});
  script.default_teams();
  script.set_ball({-0.8, 1.1});
  PlannerConfig config = testing::config_for(script.side());
  config.motion = motion;
  Planner planner(config);
  const RefereeCommand cycle[] = {RefereeCommand::kStop,
                                  RefereeCommand::kBallPlacementYellow,
                                  RefereeCommand::kDirectFreeYellow,
                                  RefereeCommand::kForceStart,
                                  RefereeCommand::kStop,
                                  RefereeCommand::kPrepareKickoffBlue,
                                  RefereeCommand::kNormalStart,
                                  RefereeCommand::kDirectFreeBlue,
                                  RefereeCommand::kPreparePenaltyYellow,
                                  RefereeCommand::kHalt};
  std::vector<double> micros;
  micros.reserve(1 << 20);
  PlannerOutput out;
  int tick = 0;
  for (auto _ : state) {
    if (tick % 50 == 0)
      script.command(cycle[(tick / 50) % 10], RefereeCommand::kDirectFreeYellow, Vec2(1.0, -2.0));
    const PlannerInputs inputs = script.inputs();
    const auto start = std::chrono::steady_clock::now();
    planner.step(inputs, testing::at_tick(tick++), out);
    const auto stop = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(out.commands.data());
    if (micros.size() < micros.capacity())
      micros.push_back(std::chrono::duration<double, std::micro>(stop - start).count());
  }
  std::sort(micros.begin(), micros.end());
  const auto at = [&](double q) {
    return micros.empty() ? 0.0 : micros[static_cast<std::size_t>(q * (micros.size() - 1))];
  };
  state.counters["p50_us"] = at(0.5);
  state.counters["p99_us"] = at(0.99);
  state.counters["max_us"] = at(1.0);
}
void BM_PlannerTickMatchCycleP99(benchmark::State& state) { match_cycle(state, MotionControl::kSimple); }
/// The same with planner II's trajectories and path search (the budgeted figure).
void BM_PlannerTickMatchCycleTrajectoriesP99(benchmark::State& state) {
  match_cycle(state, MotionControl::kTrajectory);
}
/// The free-kick set play's choice (planner.free_kick=redirect), made once on a restart's first tick: our free
/// kick 1 m in front of their division A defense area, 11 v 11 (a wall of two in front of the ball), every
/// point of the grid rated for every field player.
void BM_FreeKickSetPlayChoiceDivisionA11v11(benchmark::State& state) {
  const PlannerConfig config;
  std::vector<wm::RobotState> ours;
  std::vector<wm::RobotState> theirs;
  const Vec2 spread[] = {{-5.8, 0},  {-3.5, 1.0}, {-3.5, -1.0}, {-2.0, 2.5}, {-2.0, -2.5}, {-1.0, 0.5},
                         {0.5, 1.5}, {2.0, -1.8}, {3.0, 3.0},   {3.08, 0.0}, {3.5, 1.8}};
  for (std::uint32_t id = 0; id < 11; ++id) ours.push_back(testing::robot_at(spread[id], 0.0, id));
  for (std::uint32_t id = 0; id < 11; ++id) theirs.push_back(testing::robot_at(-spread[id] + Vec2(0, 0.3), M_PI, id));
  theirs[0].position = {5.85, 0.25};  // their keeper
  theirs[1].position = {3.8, -0.1};   // the wall
  theirs[2].position = {3.8, 0.1};
  Situation s;
  s.config = &config;
  s.field = wm::Field(config.default_field);
  s.ball_known = true;
  s.ball = {3.2, 0.0};
  s.robots = ours;
  s.enemies = theirs;
  s.keeper = 0;
  bool found = false;
  for (auto _ : state) {
    std::optional<PassOption> option = rate_redirect(s, 9);
    found = option.has_value();
    benchmark::DoNotOptimize(option);
  }
  state.counters["set_play_found"] = found ? 1 : 0;
}
BENCHMARK(BM_FreeKickSetPlayChoiceDivisionA11v11)->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_PlannerTickMatchCycleP99);
BENCHMARK(BM_PlannerTickMatchCycleTrajectoriesP99);

BENCHMARK(BM_PlannerTickHalt);
BENCHMARK(BM_PlannerTickStop);
BENCHMARK(BM_PlannerTickOurKickoff);
BENCHMARK(BM_PlannerTickTheirFreeKick);
BENCHMARK(BM_PlannerTickOurPlacement);
BENCHMARK(BM_PlannerTickNormalPlay);

}  // namespace
}  // namespace ssl::planner

BENCHMARK_MAIN();
