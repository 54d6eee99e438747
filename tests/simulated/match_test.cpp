// A whole unattended match, start to finish, as `./ssl up` plays it: the Bullet simulator with realistic
// vision and robots answering late (the harness's `realistic` conditions), both teams' world models and
// planners, and the built-in referee with the `simulation` profile (goals with the ball placed back on the
// centre mark by the simulator, balls out of the field, keep-out, no progress, half time with the side swap,
// the final whistle), all in lockstep in one process (planner::testing::PlannedMatch). The halves are shortened to 2 x 120 s of playing time and the half-time
// break to 10 s so that the whole match runs in CI; everything else is the profile as shipped.
//
// The match is played once (the suite's set-up) and each test reads one property of it:
//  * every goal is followed by its kickoff being taken (the ball in play) within 15 s of simulated time
//    (when nobody scored in the first 60 s of the match, one goal is scripted: the ball put rolling over a
//    goal line, so that this is always exercised);
//  * the side swap: blue defends the other goal in the second half, each world model's team frame follows
//    the referee's side, each keeper stands in front of the goal its team defends, and both teams stand in
//    their new halves for the second half's kickoff (its NORMAL_START came because they were in position);
//  * at most 2 no-progress restarts per half;
//  * the match ends with the final whistle (POST_GAME).
// MATCH_TEST_SEED=n plays another seed; MATCH_TEST_VERBOSE=1 prints every referee command as it comes;
// MATCH_TEST_MOTION=simple|trajectory picks both teams' skill layer (default: the planner config's).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "services/planner/testing/planned_match.h"
#include "tests/support/validation.h"
#include "tools/sslctl/match_report.h"

namespace ssl {
namespace {

using namespace std::chrono_literals;
using geom::Vec2;
using referee::Command;
using referee::GameEventType;
using referee::RefereeState;
using referee::Stage;

constexpr std::uint64_t kDefaultSeed = 20261125;
std::uint64_t seed() {
  const char* env = std::getenv("MATCH_TEST_SEED");
  return env && *env ? std::strtoull(env, nullptr, 10) : kDefaultSeed;
}
planner::MotionControl motion() {
  const char* env = std::getenv("MATCH_TEST_MOTION");
  if (env && std::string(env) == "simple") return planner::MotionControl::kSimple;
  if (env && std::string(env) == "trajectory") return planner::MotionControl::kTrajectory;
  return planner::PlannerConfig().motion;
}
bool verbose() {
  const char* env = std::getenv("MATCH_TEST_VERBOSE");
  return env && *env && *env != '0';
}

constexpr double kHalfDuration = 120;  // s of playing time
constexpr double kHalfTime = 10;       // s
constexpr double kKickoffWithin = 15;  // s from a goal to its kickoff in play
constexpr double kScriptedGoalAfter = 60;  // s of the match without a goal: one is scripted
constexpr std::uint32_t kKeeper = 0;   // both teams' goalkeeper id (the referee's default)

bool is_first_half(Stage stage) { return stage == Stage::kNormalFirstHalfPre || stage == Stage::kNormalFirstHalf; }
bool is_second_half(Stage stage) {
  return stage == Stage::kNormalSecondHalfPre || stage == Stage::kNormalSecondHalf;
}

/// What the match showed, gathered at every camera frame.
struct MatchRecord {
  struct Goal {
    double at = 0;  // s of simulated time since the start
    referee::Team scorer = referee::Team::kUnknown;
    Stage stage = Stage::kNormalFirstHalf;
    std::optional<double> kickoff_in_play_after;  // s from the goal
    bool half_ended_first = false;                // the half ended before its kickoff was taken
  };
  std::vector<Goal> goals;
  std::map<Stage, int> no_progress;  // kNoProgressInGame events by stage
  std::set<std::string> seen_events;
  bool final_whistle = false;
  double duration = 0;  // s simulated
  // Side: blue on the positive half per half, and whether each world model's frame always agreed.
  std::optional<bool> blue_positive_first, blue_positive_second;
  testing::Always frames{"each world model's team frame follows the referee's side"};  // once a second
  // Keepers: mean x (vision frame) per team and half.
  std::map<std::pair<TeamColor, bool>, std::pair<double, int>> keeper_x;  // (team, second half) -> sum, n
  // The second half's kickoff: how its NORMAL_START came.
  std::string second_half_kickoff_start;
  std::optional<double> scripted_goal;  // s: when the ball was put over a goal line (nobody had scored)
  std::uint64_t placements = 0;
};

const MatchRecord& played_match() {
  static const MatchRecord record = [] {
    MatchRecord out;
    auto profile = referee::load_referee_profile("simulation");
    EXPECT_TRUE(profile) << profile.error().message;
    profile->game.half_duration = kHalfDuration;
    profile->game.half_time = kHalfTime;
    planner::testing::PlannedMatch match(
        {.field = sim::FieldGeometry::division_b(), .robots = 6, .seed = seed(), .referee = *profile,
         .motion = motion()});
    match.start_match();
    const time::Timestamp start = match.start();
    std::uint32_t last_counter = 0;
    sslctl::MatchReportBuilder report;
    double next_frame_check = 0;
    out.final_whistle = match.run_until_final_whistle(
        std::chrono::minutes(15), [&](const sim::DetectionFrame&, const sim::WorldSnapshot& truth) {
          const referee::BuiltinReferee& referee = *match.builtin_referee();
          const RefereeState& state = referee.state();
          const double t = time::to_seconds(truth.time - start);
          report.on_referee(state, truth.time);
          report.on_ball(truth.ball.position.head<2>(), truth.time);
          for (const referee::GameEvent& event : state.game_events) {
            if (!out.seen_events.insert(event.id).second) continue;
            if (event.type == GameEventType::kGoal) {
              out.goals.push_back({.at = t, .scorer = event.by_team, .stage = state.stage});
            }
            if (event.type == GameEventType::kNoProgressInGame) ++out.no_progress[state.stage];
          }
          if (!out.goals.empty() && !out.goals.back().kickoff_in_play_after && !out.goals.back().half_ended_first &&
              state.command == Command::kNormalStart && referee.game_running()) {
            out.goals.back().kickoff_in_play_after = t - out.goals.back().at;
          }
          // Keepers save most shots: when nobody scored after kScriptedGoalAfter s, the ball is put rolling
          // over a goal line in the middle of the mouth, so that a goal and its kickoff are always exercised.
          if (out.goals.empty() && !out.scripted_goal && t > kScriptedGoalAfter && referee.game_running() &&
              state.stage == Stage::kNormalFirstHalf) {
            const double line = 0.5 * sim::FieldGeometry::division_b().field_length;
            out.scripted_goal = t;
            EXPECT_TRUE(match.apply({.ball = sim::BallTeleport{
                                         .x = line - 0.03, .y = 0.0, .z = 0.0215, .vx = 1.0, .vy = 0.0,
                                         .teleport_safely = true, .roll = true}}))
                << "scripted goal";
          }
          if (!out.goals.empty() && !out.goals.back().kickoff_in_play_after && out.goals.back().stage != state.stage) {
            out.goals.back().half_ended_first = true;
          }
          const bool blue_positive = state.blue_team_on_positive_half.value_or(kBlueOnPositiveHalfAtStart);
          const bool first = is_first_half(state.stage);
          const bool second = is_second_half(state.stage);
          if (first && !out.blue_positive_first) out.blue_positive_first = blue_positive;
          if (second && !out.blue_positive_second) out.blue_positive_second = blue_positive;
          if (state.command_counter != last_counter) {
            last_counter = state.command_counter;
            if (verbose()) {
              std::printf("%7.2f s  %-22s %-26s ball (%5.2f, %5.2f)  %s\n", t,
                          std::string(to_string(state.command)).c_str(), std::string(to_string(state.stage)).c_str(),
                          truth.ball.position.x(), truth.ball.position.y(), state.status_message.c_str());
            }
            if (state.stage == Stage::kNormalSecondHalf && state.command == Command::kNormalStart &&
                out.second_half_kickoff_start.empty()) {
              out.second_half_kickoff_start = state.status_message;
            }
          }
          // During play, keepers and frames.
          if ((first || second) && state.command != Command::kHalt) {
            for (const sim::RobotState& robot : truth.robots) {
              if (robot.key.id != kKeeper) continue;
              auto& [sum, n] = out.keeper_x[{robot.key.team, second}];
              sum += robot.position.x();
              ++n;
            }
            if (t >= next_frame_check) {
              next_frame_check = t + 1.0;
              for (const TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
                // We defend +x (the frame is turned) when our colour is on the positive half.
                const bool defends_positive = (team == TeamColor::kBlue) == blue_positive;
                out.frames.require(match.model(team).state(truth.time).flipped == defends_positive, t, [&] {
                  return std::string(to_string(team)) + "'s frame is " +
                         (defends_positive ? "not turned" : "turned") + " while it defends the " +
                         (defends_positive ? "positive" : "negative") + " half";
                });
              }
            }
          }
          out.duration = t;
        });
    out.placements = match.placements_teleported();
    const RefereeState& final_state = match.builtin_referee()->state();
    std::printf("match (seed %llu): yellow %u : %u blue after %.0f s simulated, %zu goals, %llu placements by "
                "the simulator, no-progress restarts: first half %d, second half %d, final stage %s\n",
                static_cast<unsigned long long>(seed()), final_state.yellow.score, final_state.blue.score,
                out.duration, out.goals.size(), static_cast<unsigned long long>(out.placements),
                out.no_progress[Stage::kNormalFirstHalf], out.no_progress[Stage::kNormalSecondHalf],
                std::string(to_string(final_state.stage)).c_str());
    if (out.scripted_goal) std::printf("nobody had scored: a goal was scripted at %.1f s\n", *out.scripted_goal);
    std::printf("%s", sslctl::to_text(report.report()).c_str());
    for (const MatchRecord::Goal& goal : out.goals) {
      std::printf("  goal at %6.1f s for %s, kickoff in play %s\n", goal.at,
                  goal.scorer == referee::Team::kYellow ? "yellow" : "blue",
                  goal.kickoff_in_play_after ? (std::to_string(*goal.kickoff_in_play_after) + " s later").c_str()
                                             : "never");
    }
    return out;
  }();
  return record;
}

TEST(WholeMatch, EndsWithTheFinalWhistle) {
  const MatchRecord& match = played_match();
  EXPECT_TRUE(match.final_whistle) << "still playing after " << match.duration << " s";
}

TEST(WholeMatch, EveryGoalIsFollowedByItsKickoffWithinFifteenSeconds) {
  const MatchRecord& match = played_match();
  EXPECT_FALSE(match.goals.empty()) << "nobody scored: the kickoff after a goal was never exercised";
  for (const MatchRecord::Goal& goal : match.goals) {
    if (goal.half_ended_first) continue;  // half time or the final whistle came before the kickoff
    ASSERT_TRUE(goal.kickoff_in_play_after) << "goal at " << goal.at << " s: its kickoff never came";
    EXPECT_LE(*goal.kickoff_in_play_after, kKickoffWithin) << "goal at " << goal.at << " s";
  }
}

TEST(WholeMatch, TheTeamsChangeSidesAtHalfTimeAndPlayTheirNewSides) {
  const MatchRecord& match = played_match();
  ASSERT_TRUE(match.blue_positive_first && match.blue_positive_second);
  EXPECT_EQ(*match.blue_positive_first, kBlueOnPositiveHalfAtStart);
  EXPECT_NE(*match.blue_positive_second, *match.blue_positive_first) << "the referee swapped the sides";
  EXPECT_GT(match.frames.evaluated(), 200);
  match.frames.report();
  for (const bool second : {false, true}) {
    const bool blue_positive = second ? *match.blue_positive_second : *match.blue_positive_first;
    for (const TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
      const auto it = match.keeper_x.find({team, second});
      ASSERT_NE(it, match.keeper_x.end());
      const double mean_x = it->second.first / it->second.second;
      const double own_goal_x = ((team == TeamColor::kBlue) == blue_positive ? 1.0 : -1.0) * 4.5;
      EXPECT_LT(std::abs(mean_x - own_goal_x), 1.5)
          << to_string(team) << " keeper, " << (second ? "second" : "first") << " half: mean x " << mean_x
          << ", own goal at " << own_goal_x;
    }
  }
  EXPECT_EQ(match.second_half_kickoff_start, "automatic: NORMAL_START")
      << "both teams in their new halves for the second half's kickoff";
}

TEST(WholeMatch, AtMostTwoNoProgressRestartsPerHalf) {
  const MatchRecord& match = played_match();
  EXPECT_LE(match.no_progress.count(Stage::kNormalFirstHalf) ? match.no_progress.at(Stage::kNormalFirstHalf) : 0, 2);
  EXPECT_LE(match.no_progress.count(Stage::kNormalSecondHalf) ? match.no_progress.at(Stage::kNormalSecondHalf) : 0, 2);
}

}  // namespace
}  // namespace ssl
