// Planner II in a whole match: both teams drive with `motion: trajectory` (time-optimal trajectories along
// a searched path, then the contact guard) through a 6 v 6 lockstep match with the built-in referee's
// `simulation` profile under the harness's `realistic` conditions, halves shortened to 2 x 60 s of playing
// time. Checked against the simulator's ground truth at every camera frame: no two robots ever closer than
// two radii + 1 cm (the bar; planner I's controller drives robots 2.4 cm into each other), and the
// referee raises no bot crash.
// TRAJECTORY_MATCH_SEED=n plays another seed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <set>
#include <string>

#include "services/planner/testing/planned_match.h"
#include "tests/support/validation.h"

namespace ssl {
namespace {

using referee::GameEventType;

constexpr std::uint64_t kDefaultSeed = 1;
constexpr double kHalfDuration = 60;  // s of playing time
constexpr double kHalfTime = 10;      // s
constexpr double kRobotRadius = 0.09;
constexpr double kClearance = 0.01;  // m between two robots' edges, at the closest

std::uint64_t seed() {
  const char* env = std::getenv("TRAJECTORY_MATCH_SEED");
  return env && *env ? std::strtoull(env, nullptr, 10) : kDefaultSeed;
}

using ssl::testing::Always;

struct Record {
  bool final_whistle = false;
  Always apart{"no two robots closer than two radii + 1 cm"};  // at every camera frame
  double closest = std::numeric_limits<double>::infinity();  // m between two robots' centres
  double closest_at = 0;                                     // s simulated
  int crashes = 0;
  int goals = 0;
};

const Record& played() {
  static const Record record = [] {
    Record out;
    auto profile = referee::load_referee_profile("simulation");
    EXPECT_TRUE(profile) << profile.error().message;
    profile->game.half_duration = kHalfDuration;
    profile->game.half_time = kHalfTime;
    planner::testing::PlannedMatch match({.field = sim::FieldGeometry::division_b(),
                                          .robots = 6,
                                          .seed = seed(),
                                          .referee = *profile,
                                          .motion = planner::MotionControl::kTrajectory});
    match.start_match();
    std::set<std::string> seen;
    out.final_whistle = match.run_until_final_whistle(
        std::chrono::minutes(10), [&](const sim::DetectionFrame&, const sim::WorldSnapshot& truth) {
          const double t = time::to_seconds(truth.time - match.start());
          for (std::size_t i = 0; i < truth.robots.size(); ++i) {
            for (std::size_t j = i + 1; j < truth.robots.size(); ++j) {
              const double d = (truth.robots[i].position - truth.robots[j].position).norm();
              if (d < out.closest) {
                out.closest = d;
                out.closest_at = t;
              }
              out.apart.require(d >= 2 * kRobotRadius + kClearance, t, [&] {
                return std::string(to_string(truth.robots[i].key.team)) + " " + std::to_string(truth.robots[i].key.id) +
                       " and " + std::string(to_string(truth.robots[j].key.team)) + " " +
                       std::to_string(truth.robots[j].key.id) + " " + Always::fmt(d) + " m apart";
              });
            }
          }
          for (const referee::GameEvent& event : match.builtin_referee()->state().game_events) {
            if (!seen.insert(event.id).second) continue;
            if (event.type == GameEventType::kBotCrashUnique || event.type == GameEventType::kBotCrashDrawn) {
              ++out.crashes;
            }
            if (event.type == GameEventType::kGoal) ++out.goals;
          }
        });
    std::printf("trajectory match (seed %llu): closest two robots %.3f m at %.1f s, %d crashes, %d goals\n",
                static_cast<unsigned long long>(seed()), out.closest, out.closest_at, out.crashes, out.goals);
    return out;
  }();
  return record;
}

TEST(TrajectoryMatch, EndsWithTheFinalWhistle) { EXPECT_TRUE(played().final_whistle); }

TEST(TrajectoryMatch, NoTwoRobotsEverCloserThanTwoRadiiAndOneCentimetre) { played().apart.report(); }

TEST(TrajectoryMatch, TheRefereeRaisesNoBotCrash) { EXPECT_EQ(played().crashes, 0); }

}  // namespace
}  // namespace ssl
