// Full-match benchmark (./ssl bench): a whole simulated match in one process, in lockstep
// (planner::testing::PlannedMatch: the Bullet simulator with realistic vision, both teams' world models and
// planners ticking at 100 Hz, the built-in referee with the `simulation` profile as `./ssl up` runs it:
// two halves of 300 s of playing time, half time, placements by the simulator), timed on the host's steady
// clock: the real-time factor is simulated seconds per wall-clock second (budgets: bench/budget_table.cpp).
// Prints the match report (sslctl match report's) of each match, and the 11 v 11 (division A) figure.
//
//   build/bench/match_lockstep [--half S] [--seed N] [--robots 6|11|both]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "services/planner/testing/planned_match.h"
#include "tools/sslctl/match_report.h"

namespace {

using namespace std::chrono_literals;
using ssl::planner::testing::PlannedMatch;

struct Figures {
  double realtime_factor = 0;
  double simulated = 0;  // s
  bool final_whistle = false;
  ssl::planner::MotionControl motion = ssl::planner::MotionControl::kTrajectory;
  double closest_robots = 1e9;  // m, the smallest centre distance of two robots in any frame
  std::uint64_t close_frames = 0;  // frames with two robots closer than 2 radii + 1 cm
  ssl::sslctl::MatchReport report;
};

Figures play(const ssl::sim::FieldGeometry& field, std::uint32_t robots, double half, std::uint64_t seed,
             ssl::planner::MotionControl motion) {
  auto profile = ssl::referee::load_referee_profile("simulation");
  if (!profile) {
    std::fprintf(stderr, "match_lockstep: %s\n", profile.error().message.c_str());
    std::exit(1);
  }
  profile->game.half_duration = half;
  PlannedMatch match({.field = field, .robots = robots, .seed = seed, .referee = *profile, .motion = motion});
  ssl::sslctl::MatchReportBuilder report;
  match.start_match();
  const auto start = std::chrono::steady_clock::now();
  Figures out;
  out.motion = motion;
  out.final_whistle = match.run_until_final_whistle(
      std::chrono::hours(1), [&](const ssl::sim::DetectionFrame&, const ssl::sim::WorldSnapshot& truth) {
        report.on_referee(match.builtin_referee()->state(), truth.time);
        report.on_ball(truth.ball.position.head<2>(), truth.time);
        double closest = 1e9;
        for (std::size_t i = 0; i < truth.robots.size(); ++i) {
          for (std::size_t j = i + 1; j < truth.robots.size(); ++j) {
            closest = std::min(closest, (truth.robots[i].position - truth.robots[j].position).norm());
          }
        }
        out.closest_robots = std::min(out.closest_robots, closest);
        if (closest < 2 * field.max_robot_radius + 0.01) ++out.close_frames;
      });
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.simulated = ssl::time::to_seconds(match.sim().time() - match.start());
  out.realtime_factor = out.simulated / wall;
  out.report = report.report();
  return out;
}

/// `budget_key`: the key of the BUDGET line of the real-time factor (bench/budget_table.cpp).
void print(const char* name, const Figures& f, const char* budget_key) {
  std::printf("%s: %.0f s simulated (final whistle: %s), %.1fx real time\n", name, f.simulated,
              f.final_whistle ? "yes" : "NO", f.realtime_factor);
  std::printf("closest two robots: %.3f m apart; frames with two closer than 2 radii + 1 cm: %llu\n",
              f.closest_robots, static_cast<unsigned long long>(f.close_frames));
  std::printf("%s\n", ssl::sslctl::to_text(f.report).c_str());
  // The budget is for a whole match with the planner's own motion control.
  if (f.final_whistle && f.motion == ssl::planner::MotionControl::kTrajectory) {
    std::printf("BUDGET %s %.1f\n", budget_key, f.realtime_factor);
  }
}

}  // namespace

int main(int argc, char** argv) {
  double half = 300;
  std::uint64_t seed = 42;
  std::string robots = "both";
  ssl::planner::MotionControl motion = ssl::planner::PlannerConfig().motion;
  for (int i = 1; i < argc; ++i) {
    const auto value = [&](const char* flag) -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "match_lockstep: %s needs a value\n", flag);
        std::exit(2);
      }
      return argv[++i];
    };
    if (std::strcmp(argv[i], "--help") == 0) {
      std::printf("usage: match_lockstep [--half S] [--seed N] [--robots 6|11|both] [--motion simple|trajectory]\n"
                  "  plays whole matches (two halves of S s of playing time, default 300, the built-in referee's\n"
                  "  simulation profile) of 6 v 6 (division B) and 11 v 11 (division A) in lockstep and prints the\n"
                  "  real-time factors, the closest two robots came and each match's report; --motion: both\n"
                  "  teams' skill layer (default trajectory, as the planner's)\n");
      return 0;
    }
    if (std::strcmp(argv[i], "--half") == 0) {
      char* end = nullptr;
      half = std::strtod(value("--half"), &end);
      if (!end || *end != '\0' || !(half >= 1 && half <= 3600)) {
        std::fprintf(stderr, "match_lockstep: --half needs a number of seconds in [1, 3600]\n");
        return 2;
      }
      continue;
    }
    if (std::strcmp(argv[i], "--seed") == 0) {
      char* end = nullptr;
      seed = std::strtoull(value("--seed"), &end, 10);
      if (!end || *end != '\0') {
        std::fprintf(stderr, "match_lockstep: --seed needs a whole number\n");
        return 2;
      }
      continue;
    }
    if (std::strcmp(argv[i], "--robots") == 0) {
      robots = value("--robots");
      if (robots != "6" && robots != "11" && robots != "both") {
        std::fprintf(stderr, "match_lockstep: --robots takes 6, 11 or both\n");
        return 2;
      }
      continue;
    }
    if (std::strcmp(argv[i], "--motion") == 0) {
      const std::string name = value("--motion");
      if (name != "simple" && name != "trajectory") {
        std::fprintf(stderr, "match_lockstep: --motion takes simple or trajectory\n");
        return 2;
      }
      motion = name == "simple" ? ssl::planner::MotionControl::kSimple : ssl::planner::MotionControl::kTrajectory;
      continue;
    }
    std::fprintf(stderr, "match_lockstep: unknown argument '%s' (see --help)\n", argv[i]);
    return 2;
  }
  std::printf("whole matches in lockstep, one process (simulator + 2 x (world model + planner) + built-in referee "
              "'simulation'), halves of %.0f s, seed %llu, %s motion\n\n", half, static_cast<unsigned long long>(seed),
              motion == ssl::planner::MotionControl::kSimple ? "simple" : "trajectory");
  if (robots != "11") {
    print("6 v 6 division B", play(ssl::sim::FieldGeometry::division_b(), 6, half, seed, motion),
          "lockstep_6v6_realtime_factor");
  }
  if (robots != "6") {
    print("11 v 11 division A", play(ssl::sim::FieldGeometry::division_a(), 11, half, seed, motion),
          "lockstep_11v11_realtime_factor");
  }
  return 0;
}
