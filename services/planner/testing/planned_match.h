// PlannedMatch: THE lockstep match harness. A whole simulated match in one process and in LOCKSTEP on the
// simulated clock: the Bullet simulator (realistic vision), and for each team a WorldModel fed with every
// camera frame, its dribbler feedback and its own commands, and a Planner ticking every 10 ms on its world
// model's state. The referee both teams see is either a script of commands or the built-in referee
// (services/referee_gateway/builtin) with a profile, stepped every 10 ms on the true world, its ball
// placements done by the simulator as `./ssl up` has them done (builtin.teleport_placement). No threads, no
// sleeps, no DDS: the same seed gives the same match. Used by the referee and skill scenarios, the
// whole-match tests, the world model's accuracy checks against the ground truth, bench/match_series and the
// full-match benchmark (real-time factor).
//
//   testing::PlannedMatch match({.field = sim::FieldGeometry::division_b(), .robots = 6, .seed = 7});
//   match.script({{0.0, wm::RefereeCommand::kStop}, {2.0, wm::RefereeCommand::kForceStart}});
//   match.run(30s, [&](const sim::DetectionFrame& frame, const sim::WorldSnapshot& truth) { ... });
//
//   PlannedMatch refereed({.robots = 6, .referee = *referee::load_referee_profile("simulation")});
//   refereed.start_match();                          // the operator's first STOP
//   refereed.run_until_final_whistle(20min, nullptr);
//
// Scenarios set the stage with apply() (teleports, robots taken off), drive single skills through
// planner(team).override_skill(...) and advance one planner period at a time with step().
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

#include "libs/common/team.h"
#include "services/planner/core/planner.h"
#include "services/referee_gateway/adapter/builtin_input.h"
#include "services/referee_gateway/builtin/builtin_referee.h"
#include "services/simulator/core/simulator.h"
#include "services/world_model/core/sim_harness.h"
#include "services/world_model/core/world_model.h"

namespace ssl::planner::testing {

/// What the match is played under, beyond the rules: how far the lab is from a field.
///   kIdeal      realistic vision; commands act at once and exactly, the planners expect no latency and
///               measure none; the referee sees the true world (the lockstep harness before 2026-11-28)
///   kRealistic  realistic vision; the robots answer as sim::RobotResponse::realistic() has them (25 ms radio
///               and firmware, 1 % of commands lost, 50 ms velocity lag, limits +-10 % per robot): about 40 ms
///               from camera to wheels with the vision delay; the planners plan with the delay their world
///               models measure; the referee sees the vision the teams see
///   kHarsh      competition vision; RobotResponse::harsh() (50 ms, 5 %, 100 ms, +-20 %): about 80 ms; the
///               referee sees vision
/// The planners command at 100 Hz (the radio's rate) under each.
enum class Conditions { kIdeal, kRealistic, kHarsh };

/// The conditions of that name (ideal, realistic, harsh), or nullopt.
std::optional<Conditions> conditions_named(std::string_view name);
const char* to_string(Conditions conditions);

struct PlannedMatchOptions {
  // The scenario and whole-match tests, bench/match_series and the lockstep benches play under kRealistic;
  // the scenarios that do not hold there yet ask for kIdeal and say why (planner_referee_sim_test's
  // kNotYetRealistic, the world model's match accuracy).
  Conditions conditions = Conditions::kRealistic;
  sim::FieldGeometry field = sim::FieldGeometry::division_b();
  std::uint32_t robots = 6;  // per team
  std::uint64_t seed = 1;
  bool blue_on_positive_half = kBlueOnPositiveHalfAtStart;  // at the start (the built-in referee swaps it)
  /// With a profile, the built-in referee runs the match and script() is not used.
  std::optional<referee::RefereeProfile> referee;
  MotionControl motion = PlannerConfig().motion;  // both teams' skill layer
  /// s both planners expect until a command acts; nullopt: by the conditions (ideal: 0, commands act at
  /// once; otherwise the deployed value, PlannerConfig's, as the robots on a real field need it).
  std::optional<double> actuation_latency;
  Strategy blue_strategy = Strategy::kBase;       // each team's strategy in normal play
  Strategy yellow_strategy = Strategy::kBase;
  FreeKickPlay blue_free_kick = FreeKickPlay::kShot;  // each team's own free kicks (the base strategy's)
  FreeKickPlay yellow_free_kick = FreeKickPlay::kShot;
  KickoffPlay blue_kickoff = PlannerConfig().kickoff;  // each team's own kickoffs (the base strategy's)
  KickoffPlay yellow_kickoff = PlannerConfig().kickoff;
  PenaltyPlay blue_penalty = PlannerConfig().penalty;  // each team's own penalties (the base strategy's)
  PenaltyPlay yellow_penalty = PlannerConfig().penalty;
};

/// The `strict_ai` profile's rules (every foul refereed, cards, defense areas, no progress) for matches that
/// run unattended and comparably: restarts continue without an operator, halves of `half_duration` s of
/// playing time, a 10 s half-time break, no early end and no extra time (always two full halves). Used by
/// bench/match_series and the strategy tests.
Result<referee::RefereeProfile> unattended_strict_ai(double half_duration);

/// A referee command issued `at` seconds after the start, with what the referee announces with it.
struct ScriptedCommand {
  double at = 0;
  wm::RefereeCommand command = wm::RefereeCommand::kHalt;
  std::optional<wm::RefereeCommand> next;
  std::optional<Vec2> designated;  // m, VISION frame (ball placement target)
};

class PlannedMatch {
 public:
  static constexpr auto kPlannerPeriod = std::chrono::milliseconds(10);

  explicit PlannedMatch(const PlannedMatchOptions& options);

  /// The referee commands of the match (both teams see them); HALT until the first one.
  void script(std::vector<ScriptedCommand> commands) { script_ = std::move(commands); }

  /// With the built-in referee: the operator's STOP that starts the match (it starts in HALT).
  void start_match();
  /// With the built-in referee: plays until POST_GAME or until `limit` of simulated time passed; true
  /// when the final whistle came.
  bool run_until_final_whistle(time::Duration limit,
                               const std::function<void(const sim::DetectionFrame&, const sim::WorldSnapshot&)>& after_frame);
  /// The built-in referee (nullptr with a script).
  const referee::BuiltinReferee* builtin_referee() const { return builtin_ ? &*builtin_ : nullptr; }
  /// What `team`'s planner decided on its last tick (roles, play, commands).
  const PlannerOutput& output(TeamColor team) const;
  /// Ball placements the simulator did for the referee.
  std::uint64_t placements_teleported() const { return placements_teleported_; }

  /// Plays one planner period (10 ms) of simulated time.
  void step() { run(kPlannerPeriod, nullptr); }
  /// Seconds of simulated time since the start.
  double elapsed() const { return time::to_seconds(harness_.now() - start_); }
  /// Applies a simulator control request (teleports, robots taken off or put back); true when it was
  /// accepted whole. Robots off the field get no command.
  bool apply(const sim::ControlRequest& request) { return harness_.sim().apply(request).empty(); }
  /// A team's planner (to run single skills: Planner::override_skill).
  Planner& planner(TeamColor team);

  /// Plays `duration` of simulated time; after each camera frame was given to both world models calls
  /// `after_frame(frame, truth)` with the true world at the frame's capture instant.
  void run(time::Duration duration,
           const std::function<void(const sim::DetectionFrame&, const sim::WorldSnapshot&)>& after_frame);

  /// The world model of `team` (its team frame: our goal at negative x).
  const wm::WorldModel& model(TeamColor team) const;
  const sim::Simulator& sim() const { return harness_.sim(); }
  time::Timestamp start() const { return start_; }
  /// Distance the ball travelled on the field so far (m, ground truth at the camera frames).
  double ball_travel() const { return ball_travel_; }

 private:
  struct Team {
    TeamColor color;
    Planner planner;
    PlannerOutput out;
  };

  void tick(wm::testing::SimHarness& harness);
  void step_referee(wm::testing::SimHarness& harness, const sim::WorldSnapshot& truth, time::Timestamp now);
  wm::RefereeInfo referee_info() const;
  wm::WorldModel& model_of(TeamColor team);

  wm::testing::SimHarness harness_;  // holds the simulator and BLUE's world model
  wm::WorldModel yellow_model_;
  std::vector<Team> teams_;
  std::uint32_t robots_;
  wm::RefereeInfo scripted_;  // the scripted referee
  std::optional<referee::BuiltinReferee> builtin_;
  bool referee_sees_vision_ = false;
  referee::VisionObservation referee_vision_;  // the camera frames the referee sees (when it sees vision)
  std::optional<std::uint32_t> teleported_for_;  // command counter of the last placement the simulator did
  std::uint64_t placements_teleported_ = 0;
  std::vector<ScriptedCommand> script_;
  std::size_t next_command_ = 0;
  time::Timestamp start_;
  time::Timestamp next_tick_;
  double ball_travel_ = 0;
};

}  // namespace ssl::planner::testing
