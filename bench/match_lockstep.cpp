// Full-match benchmark (./ssl bench): a whole simulated match in one process, in lockstep
// (planner::testing::PlannedMatch: the Bullet simulator with realistic vision, both teams' world models and
// planners ticking at 100 Hz, a scripted referee), timed on the host's steady clock: the real-time factor
// is simulated seconds per wall-clock second. Design budget: a 6 v 6 match >= 20x real time. Also prints
// the 11 v 11 (division A) figure and the per-component cost is left to the component benchmarks.
//
//   build/bench/match_lockstep [--seconds S]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "services/planner/testing/planned_match.h"

namespace {

using namespace std::chrono_literals;
using ssl::planner::testing::PlannedMatch;
using ssl::wm::RefereeCommand;

struct Figures {
  double realtime_factor = 0;
  std::size_t frames = 0;
  double ball_travel = 0;
};

Figures play(const ssl::sim::FieldGeometry& field, std::uint32_t robots, double seconds) {
  PlannedMatch match({.field = field, .robots = robots, .seed = 42});
  // A kickoff, then normal play, a stop and a free kick, repeated: the planners' referee branches and
  // the base strategy both run.
  std::vector<ssl::planner::testing::ScriptedCommand> script = {{0.0, RefereeCommand::kStop}};
  for (double t = 1.0; t < seconds; t += 20.0) {
    script.push_back({t, RefereeCommand::kPrepareKickoffBlue});
    script.push_back({t + 2.0, RefereeCommand::kNormalStart});
    script.push_back({t + 12.0, RefereeCommand::kStop});
    script.push_back({t + 14.0, RefereeCommand::kDirectFreeYellow});
    script.push_back({t + 19.0, RefereeCommand::kStop});
  }
  match.script(script);
  Figures out;
  const auto start = std::chrono::steady_clock::now();
  match.run(ssl::time::duration_from_seconds(seconds),
            [&](const ssl::sim::DetectionFrame&, const ssl::sim::WorldSnapshot&) { ++out.frames; });
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.realtime_factor = seconds / wall;
  out.ball_travel = match.ball_travel();
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 60;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0) {
      std::printf("usage: match_lockstep [--seconds S]\n  plays S simulated seconds (default 60) of a 6 v 6 "
                  "and an 11 v 11 match in lockstep and prints the real-time factors\n");
      return 0;
    }
    if (std::strcmp(argv[i], "--seconds") == 0 && i + 1 < argc) {
      char* end = nullptr;
      seconds = std::strtod(argv[++i], &end);
      if (!end || *end != '\0' || !(seconds > 0 && seconds <= 3600)) {
        std::fprintf(stderr, "match_lockstep: --seconds needs a number in (0, 3600]\n");
        return 2;
      }
      continue;
    }
    std::fprintf(stderr, "match_lockstep: unknown argument '%s' (see --help)\n", argv[i]);
    return 2;
  }
  const Figures b = play(ssl::sim::FieldGeometry::division_b(), 6, seconds);
  std::printf("full match, lockstep, one process (simulator + 2 x (world model + planner) + referee script), "
              "%.0f s simulated:\n", seconds);
  std::printf("  6 v 6 division B:   %.1fx real time (budget >= 20x), %zu camera frames, ball travelled %.1f m\n",
              b.realtime_factor, b.frames, b.ball_travel);
  const Figures a = play(ssl::sim::FieldGeometry::division_a(), 11, seconds);
  std::printf("  11 v 11 division A: %.1fx real time, %zu camera frames, ball travelled %.1f m\n",
              a.realtime_factor, a.frames, a.ball_travel);
  return 0;
}
