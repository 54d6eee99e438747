// The last step of `./ssl bench`: every performance budget of ../shared/design.md beside the figure this run
// measured, PASS or MISS, and the anchor. The budgets are written here, once; the benches only print figures.
//
// Figures come from the results directory `./ssl bench` fills: each bench's standard output (<bench>.out),
// where a whole-pipeline bench prints one line `BUDGET <key> <value>` per figure, and each Google Benchmark
// binary's JSON (<bench>.json), read for one benchmark's time or counter. A budget whose bench did not run
// (or printed no figure) is listed as NOT RUN. Exit status: 0 when the table was printed (a MISS is a
// finding, not a failure), 2 on bad usage or an unreadable results directory.
//
//   build/bin/budget_table --results build/bench-results
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

/// Where a figure is read: a `BUDGET key value` line of any bench, or a field of one Google Benchmark.
struct Source {
  std::string budget_key;      // BUDGET line key; empty: read the Google Benchmark fields below
  std::string benchmark_file;  // e.g. "world_model_benchmark" (its .json)
  std::string benchmark_name;  // e.g. "BM_PathSearch22Obstacles"
  std::string counter;         // a counter's name; empty: the real time per iteration, in microseconds
};

enum class Direction { kAtMost, kAtLeast };

struct Budget {
  std::string what;
  std::string unit;  // of the figure and the limit
  Direction direction;
  double limit;
  std::string anchor;
  Source source;
};

std::vector<Budget> budgets() {
  using D = Direction;
  auto key = [](std::string k) { return Source{.budget_key = std::move(k)}; };
  auto google = [](std::string file, std::string name, std::string counter = "") {
    return Source{.benchmark_file = std::move(file), .benchmark_name = std::move(name), .counter = std::move(counter)};
  };
  return {
      {"simulator 11 v 11, 4 cameras, realistic vision, one core", "x real time", D::kAtLeast, 200,
       "grSim 3.9x flat out", key("simulator_realtime_factor")},
      {"lockstep match 6 v 6, full AI (simulator, 2 teams, referee)", "x real time", D::kAtLeast, 40,
       "-", key("lockstep_6v6_realtime_factor")},
      {"lockstep match 11 v 11, full AI", "x real time", D::kAtLeast, 50, "-",
       key("lockstep_11v11_realtime_factor")},
      {"world_model: one camera frame, 22 robots + ball, + state()", "us", D::kAtMost, 30, "-",
       google("world_model_benchmark", "BM_WorldModelFrameWithAll22RobotsPlusState")},
      {"world_model error vs raw, our robots, noise as configured", "% lower", D::kAtLeast, 50, "Utama 35%",
       key("world_model_error_reduction_ours_pct")},
      {"world_model error vs raw, opponents, noise as configured", "% lower", D::kAtLeast, 50, "Utama 35%",
       key("world_model_error_reduction_opponents_pct")},
      {"world_model error vs raw, our robots, mismatched vision", "% lower", D::kAtLeast, 50, "Utama 35%",
       key("world_model_error_reduction_ours_mismatched_pct")},
      {"world_model error vs raw, opponents, mismatched vision", "% lower", D::kAtLeast, 50, "Utama 35%",
       key("world_model_error_reduction_opponents_mismatched_pct")},
      {"planner tick 11 robots, tree + trajectories + coach, p99", "us", D::kAtMost, 1000,
       "anchors tick at 60-100 Hz", google("planner_benchmark", "BM_PlannerTickMatchCycleTrajectoriesP99", "p99_us")},
      {"one robot's path search (>= 64 candidates, 22 obstacles)", "us", D::kAtMost, 100, "UBC: 64 samples",
       google("trajectory_benchmark", "BM_PathSearch22Obstacles")},
      {"vision packet -> robot.commands, 3 processes, median", "ms", D::kAtMost, 1.0, "-",
       key("commands_latency_median_ms")},
      {"vision packet -> robot.commands, 3 processes, p99", "ms", D::kAtMost, 3.0, "-",
       key("commands_latency_p99_ms")},
      {"vision packet -> datagram out of robot_link, 4 processes, median", "ms", D::kAtMost, 1.5,
       "UBC: 16 ms -> < 1 ms in one process", key("pipeline_latency_median_ms")},
      {"vision packet -> datagram out of robot_link, 4 processes, p99", "ms", D::kAtMost, 4.0, "-",
       key("pipeline_latency_p99_ms")},
      {"DDS round trip / bare UDP, two processes, median", "x", D::kAtMost, 2.5, "-",
       key("dds_round_trip_ratio_median")},
      {"console, 22 robots at 30 Hz, 3 viewers: CPU", "% of a core", D::kAtMost, 10, "-", key("console_cpu_pct")},
      {"console: the page's redraws", "per s", D::kAtLeast, 30, "-", key("console_page_draws_per_s")},
      {"20 seeded 6 v 6 matches: base - ball_chaser goals per match", "goals", D::kAtLeast, 3, "-",
       key("match_series_margin_goals")},
      {"20 seeded 6 v 6 matches: base's passes completed", "%", D::kAtLeast, 70, "-",
       key("match_series_passes_completed_pct")},
      {"20 seeded 6 v 6 matches: base's avoidable fouls", "fouls", D::kAtMost, 0, "-",
       key("match_series_avoidable_fouls")},
      {"live match: in play from vision, lowest run", "%", D::kAtLeast, 70, "-", key("live_in_play_pct")},
      {"live match 11 v 11: goals of both teams per 5 min", "goals", D::kAtLeast, 3, "-",
       key("live_goals_per_5min_11v11")},
      {"live match: goals of the colour with fewer / the other's", "ratio", D::kAtLeast, 0.5, "-",
       key("live_colour_goal_ratio")},
      {"live match: frames with two robots closer than 2 radii + 1 cm", "frames", D::kAtMost, 0, "-",
       key("live_contact_frames")},
      {"live match: avoidable fouls per match, both teams", "fouls", D::kAtMost, 0, "-",
       key("live_avoidable_fouls_per_match")},
      {"live match: balls out per 40 s in play, worst team", "balls", D::kAtMost, 1, "-",
       key("live_balls_out_per_40s_max")},
  };
}

/// Every `BUDGET key value` line of the results' .out files (a later file's value of a key wins).
std::map<std::string, double> budget_lines(const fs::path& results) {
  std::map<std::string, double> figures;
  for (const auto& entry : fs::directory_iterator(results)) {
    if (entry.path().extension() != ".out") continue;
    std::ifstream in(entry.path());
    std::string line;
    while (std::getline(in, line)) {
      std::istringstream words(line);
      std::string tag, key;
      double value = 0;
      if (words >> tag >> key >> value && tag == "BUDGET" && std::isfinite(value)) figures[key] = value;
    }
  }
  return figures;
}

std::optional<double> google_benchmark_figure(const fs::path& results, const Source& source) {
  std::ifstream in(results / (source.benchmark_file + ".json"));
  if (!in) return std::nullopt;
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded() || !json.contains("benchmarks")) return std::nullopt;
  for (const auto& run : json["benchmarks"]) {
    if (run.value("name", "") != source.benchmark_name || run.value("run_type", "iteration") != "iteration") continue;
    if (!source.counter.empty()) {
      if (!run.contains(source.counter) || !run[source.counter].is_number()) return std::nullopt;
      return run[source.counter].get<double>();
    }
    static const std::map<std::string, double> kPerMicrosecond = {{"ns", 1e-3}, {"us", 1}, {"ms", 1e3}, {"s", 1e6}};
    const auto unit = kPerMicrosecond.find(run.value("time_unit", "ns"));
    if (unit == kPerMicrosecond.end() || !run.contains("real_time")) return std::nullopt;
    return run["real_time"].get<double>() * unit->second;
  }
  return std::nullopt;
}

std::string format_figure(double value) {
  char text[32];
  std::snprintf(text, sizeof text, std::fabs(value) >= 100 ? "%.0f" : std::fabs(value) >= 10 ? "%.1f" : "%.2f",
                value);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  fs::path results;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--results" && i + 1 < argc) {
      results = argv[++i];
    } else if (arg == "--help" || arg == "-h") {
      std::printf("usage: budget_table --results DIR\n"
                  "  prints every performance budget of the design beside the figure the benches wrote into DIR\n"
                  "  (<bench>.out with BUDGET lines, <bench>.json from Google Benchmark), PASS / MISS / NOT RUN\n");
      return 0;
    } else {
      std::fprintf(stderr, "budget_table: unknown argument '%s' (see --help)\n", arg.c_str());
      return 2;
    }
  }
  std::error_code error;
  if (results.empty() || !fs::is_directory(results, error)) {
    std::fprintf(stderr, "budget_table: --results needs the directory ./ssl bench wrote (got '%s')\n",
                 results.c_str());
    return 2;
  }
  const std::map<std::string, double> lines = budget_lines(results);
  std::printf("\n%-64s %-22s %-10s %-7s %s\n", "BUDGET", "LIMIT", "MEASURED", "RESULT", "ANCHOR");
  int passed = 0, missed = 0, not_run = 0;
  for (const Budget& budget : budgets()) {
    std::optional<double> figure;
    if (!budget.source.budget_key.empty()) {
      if (const auto it = lines.find(budget.source.budget_key); it != lines.end()) figure = it->second;
    } else {
      figure = google_benchmark_figure(results, budget.source);
    }
    const std::string limit =
        (budget.direction == Direction::kAtMost ? "<= " : ">= ") + format_figure(budget.limit) + " " + budget.unit;
    const char* verdict = "NOT RUN";
    if (figure) {
      const bool pass = budget.direction == Direction::kAtMost ? *figure <= budget.limit : *figure >= budget.limit;
      verdict = pass ? "PASS" : "MISS";
      ++(pass ? passed : missed);
    } else {
      ++not_run;
    }
    std::printf("%-64s %-22s %-10s %-7s %s\n", budget.what.c_str(), limit.c_str(),
                figure ? format_figure(*figure).c_str() : "-", verdict, budget.anchor.c_str());
  }
  std::printf("%d PASS, %d MISS, %d NOT RUN (results in %s)\n", passed, missed, not_run, results.c_str());
  return 0;
}
