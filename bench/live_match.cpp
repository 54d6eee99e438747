// Live match figures (./ssl bench; the design's live-match budgets): the real-time stack of `./ssl up`
// (simulator, gateways with the built-in referee, both team stacks, console) on its own DDS domain and ports,
// one match per team size (6 v 6, 11 v 11) and side assignment (blue on the positive half, then on the
// negative one), each read for --minutes of wall-clock time by `sslctl match report` (the referee's and
// vision's multicast) and then stopped with `./ssl down --domain D`, also after an error or Ctrl-C.
//
// Per run it prints in play from vision (share of the run's referee time), the longest stall, the closest two
// robots and the contact frames, and per team (yellow, blue, with the half it defends at kickoff): goals,
// balls out, fouls (the referee's counter), placements, yellow cards and avoidable fouls
// (referee::is_avoidable_foul, as bench/match_series counts them; per run with their types). Then the same
// team figures summed per colour and per side over the runs, and, when every run completed, the BUDGET lines
// of the live-match budgets (limits in bench/budget_table.cpp):
//   live_in_play_pct                lowest in play from vision over the runs, % of the run
//   live_goals_per_5min_11v11       both teams' goals per 300 s of a run's referee time, mean of the 11 v 11 runs
//   live_colour_goal_ratio          the series' goals of the colour with fewer / of the other (0 when none)
//   live_contact_frames             over the series (camera frames as delivered, tools/sslctl/match_report.h)
//   live_avoidable_fouls_per_match  both teams', per run
//   live_balls_out_per_40s_max      a team's balls out per 40 s of the referee's time in play, worst team-run
// Times are wall-clock (the stack runs in real time). Not part of ./ssl test: the default series is four runs
// of 5 minutes, plus each one's start and stop.
//
//   build/bench/live_match [--minutes M] [--robots 6|11 ...] [--seed S] [--conditions ideal|realistic|harsh]
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "services/referee_gateway/core/types.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

// Clear of a default `./ssl up` (domain 0, vision 10020, referee 10003, console 8080); the simulator takes
// the four ports above the vision port (control, blue, yellow, grSim).
constexpr int kDomain = 61;
constexpr int kVisionPort = 24520;
constexpr int kRefereePort = 24530;
constexpr int kHttpPort = 24540;

constexpr auto kStartTimeout = 180s;  // ./ssl up: every service started and the first STOP taken
constexpr auto kStopTimeout = 120s;   // ./ssl down
constexpr auto kReportGrace = 60s;    // sslctl beyond its --duration
constexpr auto kKillAfter = 10s;      // from SIGINT to a child's process group to SIGKILL

volatile std::sig_atomic_t g_stop_requested = 0;
void request_stop(int) { g_stop_requested = 1; }

struct Options {
  double minutes = 5;
  std::vector<int> robots;  // per team, one pair of runs each; empty: 6 and 11
  unsigned long long seed = 1;
  std::string conditions = "realistic";
};

struct Paths {
  fs::path ssl;     // the source tree's launcher
  fs::path sslctl;  // this build's
};

/// Starts `argv` in its own process group (Ctrl-C reaches this process alone, which stops its children
/// itself), its standard output into the file `output` (empty: this process's standard error).
pid_t spawn(const std::vector<std::string>& argv, const fs::path& output) {
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid != 0) return pid;
  setpgid(0, 0);
  const int fd = output.empty() ? dup(STDERR_FILENO) : open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0 || dup2(fd, STDOUT_FILENO) < 0) _exit(127);
  close(fd);
  std::vector<char*> args;
  for (const std::string& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
  args.push_back(nullptr);
  execv(args[0], args.data());
  std::fprintf(stderr, "live_match: cannot run %s\n", args[0]);
  _exit(127);
}

/// Runs `argv` (see spawn) to its end; its exit status (128 + the signal that ended it). After `timeout`, or
/// on a stop request when `interruptible`, its process group gets SIGINT, and SIGKILL kKillAfter later.
int run_to_end(const std::vector<std::string>& argv, Clock::duration timeout, bool interruptible,
               const fs::path& output = {}) {
  const pid_t pid = spawn(argv, output);
  if (pid < 0) return 127;
  const auto deadline = Clock::now() + timeout;
  std::optional<Clock::time_point> interrupted;
  while (true) {
    int status = 0;
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (done < 0) return 127;
    const auto now = Clock::now();
    if (!interrupted && (now >= deadline || (interruptible && g_stop_requested))) {
      if (now >= deadline) std::fprintf(stderr, "live_match: %s did not end in time\n", argv[0].c_str());
      kill(-pid, SIGINT);
      interrupted = now;
    } else if (interrupted && now - *interrupted >= kKillAfter) {
      kill(-pid, SIGKILL);
    }
    std::this_thread::sleep_for(50ms);
  }
}

/// Stops whatever runs on the bench's domain (`./ssl down --domain D`); Ctrl-C does not interrupt it.
void stop_match(const Paths& paths) {
  const int status = run_to_end({paths.ssl.string(), "down", "--domain", std::to_string(kDomain)}, kStopTimeout,
                                /*interruptible=*/false);
  if (status != 0) std::fprintf(stderr, "live_match: ./ssl down --domain %d ended with status %d\n", kDomain, status);
}

/// Stops the match when it goes out of scope, whatever the way out.
class MatchGuard {
 public:
  explicit MatchGuard(const Paths& paths) : paths_(paths) {}
  ~MatchGuard() { stop_match(paths_); }
  MatchGuard(const MatchGuard&) = delete;
  MatchGuard& operator=(const MatchGuard&) = delete;

 private:
  const Paths& paths_;
};

struct Run {
  int robots = 6;             // per team
  bool blue_positive = true;  // blue defends the positive half at kickoff
};

std::string side_name(bool positive) { return positive ? "positive" : "negative"; }

struct TeamFigures {
  double goals = 0;
  double balls_out = 0;
  double fouls = 0;
  double placements = 0;
  double yellow_cards = 0;
  double avoidable_fouls = 0;
  std::string avoidable_foul_types;  // one run's: " TYPE xN" each (not summed by add)
  double in_play = 0;  // s the referee's game ran (the run's: the same for both teams)

  void add(const TeamFigures& other) {
    goals += other.goals;
    balls_out += other.balls_out;
    fouls += other.fouls;
    placements += other.placements;
    yellow_cards += other.yellow_cards;
    avoidable_fouls += other.avoidable_fouls;
    in_play += other.in_play;
  }
};

struct RunFigures {
  Run run;
  double duration = 0;                   // s from the first to the last referee packet
  double in_play = 0;                    // s, the referee's game running
  std::optional<double> in_play_vision;  // s, the game running with the ball seen inside the field
  std::optional<double> longest_stall;   // s
  std::string closest_robots;            // "0.201 m (yellow 2, blue 4) at 31.2 s"; empty: no frame with two
  double contact_frames = 0;
  std::optional<bool> blue_positive_reported;  // the referee's first word on the sides
  std::vector<double> side_changes;            // s since the first referee packet
  TeamFigures yellow;
  TeamFigures blue;

  double in_play_vision_pct() const { return duration > 0 && in_play_vision ? 100 * *in_play_vision / duration : 0; }
};

/// The figures of one `sslctl match report --json` object; throws nlohmann::json::exception when one is missing.
RunFigures figures_of(const nlohmann::json& report, const Run& run) {
  RunFigures f;
  f.run = run;
  f.duration = report.at("duration_s").get<double>();
  f.in_play = report.at("time_s").at("in_play").get<double>();
  if (const auto& seconds = report.at("time_s").at("in_play_vision"); !seconds.is_null()) {
    f.in_play_vision = seconds.get<double>();
  }
  if (const auto& stall = report.at("longest_stall"); !stall.is_null()) {
    f.longest_stall = stall.at("seconds").get<double>();
  }
  if (const auto& closest = report.at("closest_robots"); !closest.is_null()) {
    const auto& robots = closest.at("robots");
    char text[128];
    std::snprintf(text, sizeof text, "%.3f m (%s %u, %s %u) at %.1f s", closest.at("distance_m").get<double>(),
                  robots.at(0).at("team").get<std::string>().c_str(), robots.at(0).at("id").get<unsigned>(),
                  robots.at(1).at("team").get<std::string>().c_str(), robots.at(1).at("id").get<unsigned>(),
                  closest.at("at_s").get<double>());
    f.closest_robots = text;
  }
  f.contact_frames = report.at("contact_frames").get<double>();
  for (const auto& side : report.at("sides")) {
    if (f.blue_positive_reported) {
      f.side_changes.push_back(side.at("at_s").get<double>());
    } else {
      f.blue_positive_reported = side.at("blue_on_positive_half").get<bool>();
    }
  }
  for (auto [key, team] : {std::pair{"yellow", &f.yellow}, std::pair{"blue", &f.blue}}) {
    const auto& line = report.at("teams").at(key);
    team->goals = line.at("score").get<double>();
    team->balls_out = line.at("balls_out").get<double>();
    team->fouls = line.at("fouls").get<double>();
    team->placements = line.at("placements").get<double>();
    team->yellow_cards = line.at("yellow_cards").get<double>();
    team->in_play = f.in_play;
  }
  for (const auto& event : report.at("game_events")) {
    const auto type = ssl::referee::parse_game_event_type(event.at("type").get<std::string>());
    if (!type || !ssl::referee::is_avoidable_foul(*type)) continue;
    const std::string team = event.at("team").get<std::string>();
    TeamFigures* by = team == "yellow" ? &f.yellow : team == "blue" ? &f.blue : nullptr;
    if (!by) continue;
    by->avoidable_fouls += event.at("count").get<double>();
    by->avoidable_foul_types += " " + event.at("type").get<std::string>() + " x" +
                                std::to_string(event.at("count").get<unsigned>());
  }
  return f;
}

/// One match: ./ssl up, sslctl match report for the minutes, ./ssl down. Its figures, or nullopt (said why on
/// standard error, unless stopped by a signal).
std::optional<RunFigures> play(const Paths& paths, const Options& options, const Run& run) {
  stop_match(paths);  // what an earlier, killed bench may have left on the domain
  const MatchGuard guard(paths);
  const int up =
      run_to_end({paths.ssl.string(), "up", "--no-build", "--robots", std::to_string(run.robots), "--blue-side",
                  side_name(run.blue_positive), "--seed", std::to_string(options.seed), "--conditions",
                  options.conditions, "--domain", std::to_string(kDomain), "--vision-port", std::to_string(kVisionPort),
                  "--referee-port", std::to_string(kRefereePort), "--http-port", std::to_string(kHttpPort)},
                 kStartTimeout, /*interruptible=*/true);
  if (g_stop_requested) return std::nullopt;
  if (up != 0) {
    std::fprintf(stderr, "live_match: ./ssl up ended with status %d\n", up);
    return std::nullopt;
  }
  const double seconds = options.minutes * 60;
  char duration[32];
  std::snprintf(duration, sizeof duration, "%g", seconds);
  const fs::path output = fs::temp_directory_path() / ("live_match_report_" + std::to_string(getpid()) + ".json");
  const int status =
      run_to_end({paths.sslctl.string(), "match", "report", "--json", "--referee-port", std::to_string(kRefereePort),
                  "--vision-port", std::to_string(kVisionPort), "--duration", duration},
                 std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds)) + kReportGrace,
                 /*interruptible=*/true, output);
  std::string text;
  {
    std::ifstream in(output);
    std::getline(in, text);
  }
  std::error_code ignored;
  fs::remove(output, ignored);
  if (g_stop_requested) return std::nullopt;
  if (status != 0) {
    std::fprintf(stderr, "live_match: sslctl match report ended with status %d\n", status);
    return std::nullopt;
  }
  try {
    return figures_of(nlohmann::json::parse(text), run);
  } catch (const nlohmann::json::exception& error) {
    std::fprintf(stderr, "live_match: the match report lacks a figure: %s\n", error.what());
    return std::nullopt;
  }
}

std::string seconds_text(const std::optional<double>& seconds) {
  if (!seconds) return "unknown";
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", *seconds);
  return text;
}

std::string run_title(std::size_t index, std::size_t count, const Run& run) {
  char text[96];
  std::snprintf(text, sizeof text, "run %zu/%zu: %d v %d, blue on the %s half", index + 1, count, run.robots,
                run.robots, side_name(run.blue_positive).c_str());
  return text;
}

void print_team(const char* name, bool positive, const TeamFigures& t) {
  const std::string types = t.avoidable_foul_types.empty() ? "" : " (" + t.avoidable_foul_types.substr(1) + ")";
  std::printf(
      "  %-6s (%s half): goals %.0f, balls out %.0f, fouls %.0f, placements %.0f, yellow cards %.0f, "
      "avoidable fouls %.0f%s\n",
      name, side_name(positive).c_str(), t.goals, t.balls_out, t.fouls, t.placements, t.yellow_cards,
      t.avoidable_fouls, types.c_str());
}

void print_run(std::size_t index, std::size_t count, const RunFigures& f) {
  std::printf("%s: %.1f s of referee packets, in play %.1f s by the referee\n", run_title(index, count, f.run).c_str(),
              f.duration, f.in_play);
  std::printf("  in play from vision %.0f %% (%s); longest stall %s; closest robots %s; contact frames %.0f\n",
              f.in_play_vision_pct(), seconds_text(f.in_play_vision).c_str(), seconds_text(f.longest_stall).c_str(),
              f.closest_robots.empty() ? "-" : f.closest_robots.c_str(), f.contact_frames);
  print_team("yellow", !f.run.blue_positive, f.yellow);
  print_team("blue", f.run.blue_positive, f.blue);
  for (double at : f.side_changes) {
    std::printf("  the teams changed sides at %.1f s (figures by the kickoff side)\n", at);
  }
  std::fflush(stdout);
}

void print_summary(const std::vector<RunFigures>& runs) {
  TeamFigures yellow, blue, positive, negative;
  for (const RunFigures& f : runs) {
    yellow.add(f.yellow);
    blue.add(f.blue);
    (f.run.blue_positive ? positive : negative).add(f.blue);
    (f.run.blue_positive ? negative : positive).add(f.yellow);
  }
  std::printf("\nover %zu runs %-23s %6s %9s %6s %10s %12s %15s\n", runs.size(), "", "goals", "balls out", "fouls",
              "placements", "yellow cards", "avoidable fouls");
  const auto row = [](const char* name, const TeamFigures& t) {
    std::printf("  %-35s %6.0f %9.0f %6.0f %10.0f %12.0f %15.0f\n", name, t.goals, t.balls_out, t.fouls, t.placements,
                t.yellow_cards, t.avoidable_fouls);
  };
  row("yellow", yellow);
  row("blue", blue);
  row("the team on the positive half", positive);
  row("the team on the negative half", negative);
}

/// The live-match budgets' figures over the runs (see the file's comment).
void print_budgets(const std::vector<RunFigures>& runs) {
  double lowest_in_play = 100, contact_frames = 0, avoidable_fouls = 0, worst_balls_out = 0;
  double yellow_goals = 0, blue_goals = 0, goal_rates_11v11 = 0;
  int runs_11v11 = 0;
  for (const RunFigures& f : runs) {
    lowest_in_play = std::min(lowest_in_play, f.in_play_vision_pct());
    contact_frames += f.contact_frames;
    avoidable_fouls += f.yellow.avoidable_fouls + f.blue.avoidable_fouls;
    yellow_goals += f.yellow.goals;
    blue_goals += f.blue.goals;
    for (const TeamFigures* team : {&f.yellow, &f.blue}) {
      if (team->in_play > 0) worst_balls_out = std::max(worst_balls_out, team->balls_out / (team->in_play / 40));
    }
    if (f.run.robots == 11 && f.duration > 0) {
      goal_rates_11v11 += (f.yellow.goals + f.blue.goals) / (f.duration / 300);
      ++runs_11v11;
    }
  }
  const double fewer = std::min(yellow_goals, blue_goals);
  const double more = std::max(yellow_goals, blue_goals);
  std::printf("\nBUDGET live_in_play_pct %.1f\n", lowest_in_play);
  if (runs_11v11 > 0) std::printf("BUDGET live_goals_per_5min_11v11 %.2f\n", goal_rates_11v11 / runs_11v11);
  std::printf("BUDGET live_colour_goal_ratio %.2f\n", more > 0 ? fewer / more : 0.0);
  std::printf("BUDGET live_contact_frames %.0f\n", contact_frames);
  std::printf("BUDGET live_avoidable_fouls_per_match %.2f\n", avoidable_fouls / static_cast<double>(runs.size()));
  std::printf("BUDGET live_balls_out_per_40s_max %.2f\n", worst_balls_out);
}

[[noreturn]] void usage_error(const std::string& message) {
  std::fprintf(stderr, "live_match: %s (see --help)\n", message.c_str());
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::printf(
          "usage: live_match [--minutes M] [--robots 6|11 ...] [--seed S] [--conditions ideal|realistic|harsh]\n"
          "  runs `./ssl up` (the real-time stack) on DDS domain %d (vision port %d, referee port %d, console port\n"
          "  %d) for each team size (--robots, repeatable; default 6 and 11) with blue on the positive half, then\n"
          "  on the negative one, reads each match for M minutes of wall-clock time (default 5) with `sslctl match\n"
          "  report`, stops it with `./ssl down --domain %d` (also on an error or Ctrl-C), and prints per run and\n"
          "  team goals, balls out, fouls, placements, yellow cards, avoidable fouls (and their types), in play\n"
          "  from vision, the longest stall, the closest two robots and the contact frames, sums per colour and\n"
          "  side, and the live-match BUDGET lines; --seed and --conditions (default realistic) go to ./ssl up\n",
          kDomain, kVisionPort, kRefereePort, kHttpPort, kDomain);
      std::exit(0);
    }
    if (arg == "--minutes") {
      const std::string text = value();
      char* end = nullptr;
      options.minutes = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != '\0' || !(options.minutes > 0 && options.minutes <= 600)) {
        usage_error("--minutes takes a number of minutes in (0, 600]");
      }
    } else if (arg == "--robots") {
      const std::string text = value();
      if (text != "6" && text != "11") usage_error("--robots takes 6 or 11");
      options.robots.push_back(std::stoi(text));
    } else if (arg == "--seed") {
      const std::string text = value();
      char* end = nullptr;
      options.seed = std::strtoull(text.c_str(), &end, 10);
      if (text.empty() || text[0] == '-' || *end != '\0') usage_error("--seed takes a non-negative integer");
    } else if (arg == "--conditions") {
      options.conditions = value();
      if (options.conditions != "ideal" && options.conditions != "realistic" && options.conditions != "harsh") {
        usage_error("--conditions takes ideal, realistic or harsh");
      }
    } else {
      usage_error("unknown argument '" + arg + "'");
    }
  }
  if (options.robots.empty()) options.robots = {6, 11};
  return options;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  const fs::path build = fs::canonical("/proc/self/exe").parent_path().parent_path();
  const Paths paths{.ssl = fs::path(SSL_SOURCE_DIR) / "ssl", .sslctl = build / "bin" / "sslctl"};
  setenv("SSL_BUILD_DIR", build.c_str(), 1);  // ./ssl runs this build's binaries
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal, &action, nullptr);

  std::vector<Run> runs;
  for (int robots : options.robots) {
    for (bool blue_positive : {true, false}) runs.push_back({robots, blue_positive});
  }
  std::printf(
      "live match: %zu runs of %.1f min (wall clock), seed %llu, conditions %s; ./ssl up on domain %d "
      "(console http://127.0.0.1:%d while a run lasts)\n",
      runs.size(), options.minutes, options.seed, options.conditions.c_str(), kDomain, kHttpPort);
  std::vector<RunFigures> figures;
  for (std::size_t i = 0; i < runs.size() && !g_stop_requested; ++i) {
    std::optional<RunFigures> run = play(paths, options, runs[i]);
    if (!run) {
      std::printf("%s: %s\n", run_title(i, runs.size(), runs[i]).c_str(),
                  g_stop_requested ? "interrupted" : "failed (see above)");
      continue;
    }
    print_run(i, runs.size(), *run);
    if (run->blue_positive_reported != runs[i].blue_positive) {
      std::printf("  !! the referee did not report blue on the %s half: the run does not count\n",
                  side_name(runs[i].blue_positive).c_str());
      continue;
    }
    figures.push_back(std::move(*run));
  }
  if (!figures.empty()) print_summary(figures);
  if (g_stop_requested) {
    std::printf("live match: interrupted; no budget figures\n");
    return 130;
  }
  if (figures.size() != runs.size()) {
    std::printf("live match: %zu of %zu runs did not count; no budget figures\n", runs.size() - figures.size(),
                runs.size());
    return 1;
  }
  print_budgets(figures);
  return 0;
}
