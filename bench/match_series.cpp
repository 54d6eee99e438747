// Play quality over many matches (./ssl bench): N seeded whole 6 v 6 (or 11 v 11) matches per pairing of
// strategies, each in lockstep in one process (planner::testing::PlannedMatch: the Bullet simulator with
// realistic vision, both teams' world models and planners, the built-in referee), spread over the cores (one
// child process per match). The referee runs the `strict_ai` profile's rules (every foul refereed, cards,
// defense areas, no progress) with three changes so that matches run unattended and comparably: restarts
// continue without an operator (auto_continue), the half-time break is 10 s (nothing plays in it), and no
// early end or extra time (a match is always two full halves). As in `./ssl up`, the simulator places the
// ball for the referee.
// The strategies swap colours every other seed.
//
// Per pairing it prints, per strategy and per match on average: goals for / against, passes tried /
// completed, shots / on target, possession share, kickoffs, penalties and free kicks taken and kept (the
// next touch a teammate's, or a goal) and the goals scored from them (no opponent touch between) (sslctl's
// PlayAccount on the ground truth, the kicker's intent from its planner's skill), and every game event by
// type, fouls marked, "avoidable" ones (keep-out, too fast in STOP, defense area, double touch, crash)
// counted apart; per pairing, camera frames with two robots closer than two radii and a centimetre (contact
// frames, on the ground truth) and the closest two robots of the series. Under each match's line: each
// contact and each avoidable foul (when, which robot, where, under which command), the moment to replay.
// Over 20 seeds or more of base against ball_chaser it also prints the figures of the design's play-quality
// budgets as BUDGET lines (goal margin, passes completed, avoidable fouls; ./ssl bench's table).
//
// The conditions (--conditions, PlannedMatch's Conditions) default to realistic: the budgets hold there.
//
//   build/bench/match_series [--seeds N] [--first-seed S] [--half S] [--jobs J] [--pairing A:B ...] [--tactics]
//                            [--conditions ideal|realistic|harsh] [--robots 6|11]
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "services/planner/testing/planned_match.h"
#include "tools/sslctl/match_report.h"

namespace {

using ssl::TeamColor;
using ssl::planner::FreeKickPlay;
using ssl::planner::KickoffPlay;
using ssl::planner::PenaltyPlay;
using ssl::planner::Strategy;
using ssl::planner::testing::Conditions;
using ssl::planner::testing::PlannedMatch;
using ssl::referee::GameEventType;

/// A side of a pairing: a strategy, and for base how it takes its own restarts when not as configured by
/// default: "base+redirect" (the free-kick set play), "base+free_kick_pass" (that set play, else a pass),
/// "base+kickoff_shot" (kickoffs shot straight),
/// "base+penalty_shot" (penalties shot from the mark), or several: "base+redirect+kickoff_shot".
struct Side {
  Strategy strategy = Strategy::kBase;
  FreeKickPlay free_kick = ssl::planner::PlannerConfig().free_kick;
  KickoffPlay kickoff = ssl::planner::PlannerConfig().kickoff;
  PenaltyPlay penalty = ssl::planner::PlannerConfig().penalty;
};

std::optional<Side> side_named(const std::string& name) {
  const std::size_t plus = name.find('+');
  const std::string strategy = name.substr(0, plus);
  Side side;
  if (strategy == "ball_chaser") {
    side.strategy = Strategy::kBallChaser;
  } else if (strategy == "wander") {
    side.strategy = Strategy::kWander;
  } else if (strategy != "base") {
    return std::nullopt;
  }
  for (std::size_t at = plus; at != std::string::npos;) {
    if (side.strategy != Strategy::kBase) return std::nullopt;
    const std::size_t next = name.find('+', at + 1);
    const std::string modifier = name.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1);
    if (modifier == "redirect") {
      side.free_kick = FreeKickPlay::kRedirect;
    } else if (modifier == "free_kick_pass") {
      side.free_kick = FreeKickPlay::kPass;
    } else if (modifier == "kickoff_shot") {
      side.kickoff = KickoffPlay::kShot;
    } else if (modifier == "penalty_shot") {
      side.penalty = PenaltyPlay::kShot;
    } else {
      return std::nullopt;
    }
    at = next;
  }
  return side;
}

struct Pairing {
  std::string a;
  std::string b;
};

struct Job {
  std::size_t pairing = 0;
  std::uint64_t seed = 0;
};

/// Skill names that tell the play account what a kick meant.
ssl::sslctl::PlayAccount::Intent intent_of(const std::string& skill) {
  using Intent = ssl::sslctl::PlayAccount::Intent;
  if (skill == "pass") return Intent::kPass;
  if (skill == "shoot" || skill == "redirect") return Intent::kShot;
  if (skill == "clear_ball" || skill == "challenge") return Intent::kClear;  // away, to nobody in particular
  return Intent::kUnknown;
}

/// What each robot meant by its kicks: the skill it last armed its kicker in. A kick shows on a camera frame
/// a few planner ticks after the command that made it, when the planner may already have moved on (the
/// keeper back to defending after its clearance), so the skill of the moment would misname it. A robot that
/// did not arm its kicker lately did not kick: the ball came off its body (Intent::kNoKick).
class KickIntents {
 public:
  static constexpr double kArmedRecently = 0.3;  // s: a kick this soon after the kicker was armed is that skill's

  /// Every frame, with both planners' last outputs; `now` in s.
  void update(TeamColor team, const ssl::planner::PlannerOutput& out, double now) {
    for (const ssl::planner::RobotCommand& command : out.commands) {
      if (command.kick == ssl::planner::KickType::kNone) continue;
      for (const ssl::planner::RoleInfo& role : out.roles) {
        if (role.robot_id == command.id) armed_[key(team, command.id)] = Armed{role.skill, now};
      }
    }
  }
  /// The intent of robot `id` of `team` kicking now.
  ssl::sslctl::PlayAccount::Intent intent(TeamColor team, std::uint32_t id, double now) const {
    const auto it = armed_.find(key(team, id));
    if (it == armed_.end() || now - it->second.at > kArmedRecently) return ssl::sslctl::PlayAccount::Intent::kNoKick;
    return intent_of(it->second.skill);
  }

 private:
  struct Armed {
    std::string skill;
    double at = 0;
  };
  static std::uint32_t key(TeamColor team, std::uint32_t id) { return (team == TeamColor::kBlue ? 1000u : 0u) + id; }
  std::map<std::uint32_t, Armed> armed_;
};

/// One match, in this (child) process: its report as JSON, plus which colour strategy A played.
std::string play(const Pairing& pairing, std::uint64_t seed, double half, Conditions conditions,
                 std::uint32_t robots_a_side) {
  auto profile = ssl::planner::testing::unattended_strict_ai(half);
  if (!profile) {
    std::fprintf(stderr, "match_series: %s\n", profile.error().message.c_str());
    std::exit(1);
  }
  const bool a_is_blue = seed % 2 == 0;
  const Side a = *side_named(pairing.a);
  const Side b = *side_named(pairing.b);
  const ssl::sim::FieldGeometry field =
      robots_a_side > 6 ? ssl::sim::FieldGeometry::division_a() : ssl::sim::FieldGeometry::division_b();
  PlannedMatch match({.conditions = conditions,
                      .field = field,
                      .robots = robots_a_side,
                      .seed = seed,
                      .referee = *profile,
                      .blue_strategy = a_is_blue ? a.strategy : b.strategy,
                      .yellow_strategy = a_is_blue ? b.strategy : a.strategy,
                      .blue_free_kick = a_is_blue ? a.free_kick : b.free_kick,
                      .yellow_free_kick = a_is_blue ? b.free_kick : a.free_kick,
                      .blue_kickoff = a_is_blue ? a.kickoff : b.kickoff,
                      .yellow_kickoff = a_is_blue ? b.kickoff : a.kickoff,
                      .blue_penalty = a_is_blue ? a.penalty : b.penalty,
                      .yellow_penalty = a_is_blue ? b.penalty : a.penalty});
  ssl::sslctl::MatchReportBuilder report;
  report.set_field(field);
  std::vector<ssl::sslctl::PlayAccount::Robot> robots;
  KickIntents kick_intents;
  std::map<std::string, std::map<std::string, double>> tactics;  // team -> tactic -> robot-frames in play
  match.start_match();
  const bool finished = match.run_until_final_whistle(
      std::chrono::hours(1), [&](const ssl::sim::DetectionFrame&, const ssl::sim::WorldSnapshot& truth) {
        report.on_referee(match.builtin_referee()->state(), truth.time);
        const double now = ssl::time::to_seconds(truth.time - match.start());
        for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) kick_intents.update(team, match.output(team), now);
        robots.clear();
        for (const ssl::sim::RobotState& robot : truth.robots) {
          ssl::sslctl::PlayAccount::Robot seen{.team = robot.key.team, .id = robot.key.id, .position = robot.position};
          seen.intent = kick_intents.intent(robot.key.team, robot.key.id, now);
          robots.push_back(seen);
        }
        report.on_frame(truth.ball.position.head<2>(), robots, truth.time);
        const ssl::referee::Command command = match.builtin_referee()->state().command;
        if (command == ssl::referee::Command::kNormalStart || command == ssl::referee::Command::kForceStart) {
          for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
            for (const ssl::planner::RoleInfo& role : match.output(team).roles) {
              tactics[team == TeamColor::kBlue ? "blue" : "yellow"][role.role + "/" + role.tactic] += 1;
            }
          }
        }
      });
  nlohmann::json out = nlohmann::json::parse(ssl::sslctl::to_json(report.report()));
  out["tactics"] = tactics;
  out["a_is_blue"] = a_is_blue;
  out["seed"] = seed;
  out["finished"] = finished;
  return out.dump();
}

/// Runs `play` in a child process; its JSON line, or nullopt when it failed.
std::optional<std::string> play_in_child(const Pairing& pairing, std::uint64_t seed, double half,
                                         Conditions conditions, std::uint32_t robots_a_side) {
  int fds[2];
  if (pipe(fds) != 0) return std::nullopt;
  const pid_t pid = fork();
  if (pid < 0) return std::nullopt;
  if (pid == 0) {
    close(fds[0]);
    const std::string line = play(pairing, seed, half, conditions, robots_a_side) + "\n";
    std::size_t written = 0;
    while (written < line.size()) {
      const ssize_t n = write(fds[1], line.data() + written, line.size() - written);
      if (n <= 0) _exit(1);
      written += static_cast<std::size_t>(n);
    }
    _exit(0);
  }
  close(fds[1]);
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || text.empty()) return std::nullopt;
  return text;
}

/// One strategy's sums over the matches of a pairing.
struct Totals {
  double goals_for = 0, goals_against = 0;
  double passes_tried = 0, passes_completed = 0, shots = 0, on_target = 0, possession = 0, possession_all = 0;
  double shots_saved = 0, shots_blocked = 0, shot_distance = 0;
  double passes_intercepted = 0, passes_out = 0;
  /// Restarts of one kind: taken, kept (or scored), goals with no opponent touch since.
  struct Restarts {
    double taken = 0, kept = 0, goals = 0;
  };
  Restarts kickoffs, penalties, free_kicks;
  std::map<std::string, double> events;  // by type
  double fouls = 0, avoidable_fouls = 0;
  double wins = 0, draws = 0;
  std::map<std::string, double> tactics;  // role/tactic -> robot-frames in normal play
};

void add(Totals& t, const nlohmann::json& match, const char* us, const char* them) {
  const nlohmann::json& mine = match["teams"][us];
  const nlohmann::json& theirs = match["teams"][them];
  const double scored = mine["score"].get<double>();
  const double conceded = theirs["score"].get<double>();
  t.goals_for += scored;
  t.goals_against += conceded;
  t.wins += scored > conceded ? 1 : 0;
  t.draws += scored == conceded ? 1 : 0;
  if (mine.contains("play")) {
    t.passes_tried += mine["play"]["passes_tried"].get<double>();
    t.passes_completed += mine["play"]["passes_completed"].get<double>();
    t.shots += mine["play"]["shots"].get<double>();
    t.on_target += mine["play"]["shots_on_target"].get<double>();
    t.shots_saved += mine["play"]["shots_saved"].get<double>();
    t.shots_blocked += mine["play"]["shots_blocked"].get<double>();
    t.shot_distance += mine["play"]["shot_distance_mean_m"].get<double>() * mine["play"]["shots"].get<double>();
    t.possession += mine["play"]["possession_s"].get<double>();
    t.possession_all += mine["play"]["possession_s"].get<double>() + theirs["play"]["possession_s"].get<double>();
    t.passes_intercepted += mine["play"]["passes_intercepted"].get<double>();
    t.passes_out += mine["play"]["passes_out"].get<double>();
    for (auto [key, tally] : {std::pair{"kickoffs", &t.kickoffs}, std::pair{"penalties", &t.penalties},
                              std::pair{"free_kicks", &t.free_kicks}}) {
      const nlohmann::json& restarts = mine["play"][key];
      tally->taken += restarts["taken"].get<double>();
      tally->kept += restarts["kept"].get<double>();
      tally->goals += restarts["goals"].get<double>();
    }
  }
  if (match.contains("tactics") && match["tactics"].contains(us)) {
    for (const auto& [name, count] : match["tactics"][us].items()) t.tactics[name] += count.get<double>();
  }
  for (const nlohmann::json& event : match["game_events"]) {
    if (event["team"].get<std::string>() != us) continue;
    const std::string type = event["type"].get<std::string>();
    const double count = event["count"].get<double>();
    t.events[type] += count;
    const auto parsed = ssl::referee::parse_game_event_type(type);
    if (parsed && ssl::referee::is_foul(*parsed)) t.fouls += count;
    if (parsed && ssl::referee::is_avoidable_foul(*parsed)) t.avoidable_fouls += count;
  }
}

/// The match's avoidable fouls, " !! <colour> <TYPE> xN ..." (empty without any): which seed to look at.
std::string avoidable_fouls(const nlohmann::json& match) {
  std::string text;
  for (const nlohmann::json& event : match["game_events"]) {
    const auto parsed = ssl::referee::parse_game_event_type(event["type"].get<std::string>());
    if (!parsed || !ssl::referee::is_avoidable_foul(*parsed)) continue;
    text += " !! " + event["team"].get<std::string>() + " " + event["type"].get<std::string>() + " x" +
            std::to_string(event["count"].get<unsigned>());
  }
  return text;
}

double ratio(double part, double whole) { return whole > 0 ? 100.0 * part / whole : 0; }

/// `budgets`: the series is the budgets' (6 v 6): print their BUDGET lines.
void print_pairing(const Pairing& pairing, const std::vector<nlohmann::json>& matches, bool print_tactics,
                   bool budgets) {
  Totals a, b;
  for (const nlohmann::json& match : matches) {
    const bool a_blue = match["a_is_blue"].get<bool>();
    add(a, match, a_blue ? "blue" : "yellow", a_blue ? "yellow" : "blue");
    add(b, match, a_blue ? "yellow" : "blue", a_blue ? "blue" : "yellow");
  }
  const double n = static_cast<double>(std::max<std::size_t>(matches.size(), 1));
  std::printf("\n%s vs %s: %zu matches\n", pairing.a.c_str(), pairing.b.c_str(), matches.size());
  std::printf("  %-32s %14s %14s\n", "per match", pairing.a.c_str(), pairing.b.c_str());
  const auto row = [&](const char* name, double va, double vb, const char* format = "%14.2f") {
    std::printf("  %-32s ", name);
    std::printf(format, va);
    std::printf(" ");
    std::printf(format, vb);
    std::printf("\n");
  };
  row("goals for", a.goals_for / n, b.goals_for / n);
  row("goals against", a.goals_against / n, b.goals_against / n);
  row("wins / draws (matches)", a.wins, b.wins, "%14.0f");
  row("passes tried", a.passes_tried / n, b.passes_tried / n);
  row("passes completed", a.passes_completed / n, b.passes_completed / n);
  row("passes completed (%)", ratio(a.passes_completed, a.passes_tried), ratio(b.passes_completed, b.passes_tried),
      "%14.0f");
  row("  intercepted", a.passes_intercepted / n, b.passes_intercepted / n);
  row("  out of play first", a.passes_out / n, b.passes_out / n);
  row("shots", a.shots / n, b.shots / n);
  row("shots on target", a.on_target / n, b.on_target / n);
  row("  saved by the keeper", a.shots_saved / n, b.shots_saved / n);
  row("  blocked by a field player", a.shots_blocked / n, b.shots_blocked / n);
  row("  from (m, mean)", a.shots > 0 ? a.shot_distance / a.shots : 0, b.shots > 0 ? b.shot_distance / b.shots : 0);
  row("possession (%)", ratio(a.possession, a.possession_all), ratio(b.possession, b.possession_all), "%14.0f");
  for (auto [name, restarts] : {std::pair{"kickoffs", &Totals::kickoffs}, std::pair{"penalties", &Totals::penalties},
                                 std::pair{"free kicks", &Totals::free_kicks}}) {
    const Totals::Restarts& ra = a.*restarts;
    const Totals::Restarts& rb = b.*restarts;
    row((std::string(name) + " taken").c_str(), ra.taken / n, rb.taken / n);
    row("  kept or scored (%)", ratio(ra.kept, ra.taken), ratio(rb.kept, rb.taken), "%14.0f");
    row("  goals from them", ra.goals / n, rb.goals / n);
  }
  row("fouls", a.fouls / n, b.fouls / n);
  row("avoidable fouls (!!)", a.avoidable_fouls / n, b.avoidable_fouls / n);
  std::set<std::string> types;
  for (const auto& [type, count] : a.events) types.insert(type);
  for (const auto& [type, count] : b.events) types.insert(type);
  std::printf("  game events by type (per match; * foul, !! avoidable foul)\n");
  for (const std::string& type : types) {
    const auto parsed = ssl::referee::parse_game_event_type(type);
    const char* mark = parsed && ssl::referee::is_avoidable_foul(*parsed) ? "!!" : parsed && ssl::referee::is_foul(*parsed) ? "* " : "  ";
    std::printf("  %s %-29s %14.2f %14.2f\n", mark, type.c_str(), a.events[type] / n, b.events[type] / n);
  }
  double contact_frames = 0;
  std::optional<double> closest;
  for (const nlohmann::json& match : matches) {
    contact_frames += match["contact_frames"].get<double>();
    if (!match["closest_robots"].is_null()) {
      const double distance = match["closest_robots"]["distance_m"].get<double>();
      closest = std::min(closest.value_or(distance), distance);
    }
  }
  std::printf("  contact frames (both teams, centres under %.2f m) %.2f per match, %.0f in all; closest robots "
              "%.3f m\n",
              ssl::sslctl::MatchReportBuilder::kContactDistance, contact_frames / n, contact_frames,
              closest.value_or(0.0));
  if (print_tactics) {
    std::printf("  roles/tactics in normal play (share of robot-frames)\n");
    std::set<std::string> names;
    double all_a = 0, all_b = 0;
    for (const auto& [name, count] : a.tactics) names.insert(name), all_a += count;
    for (const auto& [name, count] : b.tactics) names.insert(name), all_b += count;
    for (const std::string& name : names) {
      std::printf("     %-29s %13.1f%% %13.1f%%\n", name.c_str(), ratio(a.tactics[name], all_a), ratio(b.tactics[name], all_b));
    }
  }
  // The design's play-quality budgets are over 20 seeds of base against ball_chaser, 6 v 6
  // (bench/budget_table.cpp holds the limits).
  if (budgets && pairing.a == "base" && pairing.b == "ball_chaser" && matches.size() >= 20) {
    std::printf("BUDGET match_series_margin_goals %.2f\n", (a.goals_for - a.goals_against) / n);
    std::printf("BUDGET match_series_passes_completed_pct %.1f\n", ratio(a.passes_completed, a.passes_tried));
    std::printf("BUDGET match_series_avoidable_fouls %.0f\n", a.avoidable_fouls);
  }
}

[[noreturn]] void usage_error(const std::string& message) {
  std::fprintf(stderr, "match_series: %s (see --help)\n", message.c_str());
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t seeds = 20;
  std::uint64_t first_seed = 1;
  double half = 300;
  unsigned jobs = std::max(1u, std::thread::hardware_concurrency());
  std::vector<Pairing> pairings;
  bool print_tactics = false;
  Conditions conditions = Conditions::kRealistic;
  std::uint32_t robots_a_side = 6;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(arg + " needs a value");
      return argv[++i];
    };
    const auto number = [&](double low, double high) {
      const std::string text = value();
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (!end || *end != '\0' || !(v >= low && v <= high)) {
        usage_error(arg + " takes a number in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
      }
      return v;
    };
    if (arg == "--help") {
      std::printf(
          "usage: match_series [--seeds N] [--first-seed S] [--half S] [--jobs J] [--pairing A:B ...] [--tactics]\n"
          "                    [--conditions ideal|realistic|harsh] [--robots 6|11]\n"
          "  plays N seeded whole 6 v 6 matches (division B; --robots 11: 11 v 11 in division A) (default 20;\n"
          "  seeds S, S+1, ...) per pairing of strategies (base, base+redirect: base with the free-kick set\n"
          "  play, base+free_kick_pass: that set play, else a pass, base+kickoff_shot: kickoffs shot straight,\n"
          "  base+penalty_shot: penalties shot from the mark,\n"
          "  or several: base+redirect+kickoff_shot; ball_chaser, wander; default base:ball_chaser and\n"
          "  base:base) in lockstep under the strict_ai rules, halves of --half s of playing time (default 300),\n"
          "  J matches at a time (default: the cores), and prints goals, passes, shots, possession and game\n"
          "  events per strategy and match, contact frames and the closest robots, and the budgets' figures\n"
          "  (6 v 6); --tactics: also the share of each role/tactic in normal play; --conditions: what the\n"
          "  robots and the referee are like (PlannedMatch's Conditions; default realistic: about 40 ms from camera\n"
          "  to wheels, lagging velocity, robots that differ, the referee sees vision)\n");
      return 0;
    }
    if (arg == "--tactics") {
      print_tactics = true;
    } else if (arg == "--seeds") {
      seeds = static_cast<std::uint64_t>(number(1, 1000));
    } else if (arg == "--first-seed") {
      first_seed = static_cast<std::uint64_t>(number(0, 1e15));
    } else if (arg == "--half") {
      half = number(1, 3600);
    } else if (arg == "--conditions") {
      const std::optional<Conditions> named = ssl::planner::testing::conditions_named(value());
      if (!named) usage_error("--conditions takes ideal, realistic or harsh");
      conditions = *named;
    } else if (arg == "--robots") {
      const std::string text = value();
      if (text != "6" && text != "11") usage_error("--robots takes 6 or 11");
      robots_a_side = static_cast<std::uint32_t>(std::stoul(text));
    } else if (arg == "--jobs") {
      jobs = static_cast<unsigned>(number(1, 256));
    } else if (arg == "--pairing") {
      const std::string text = value();
      const std::size_t colon = text.find(':');
      if (colon == std::string::npos || !side_named(text.substr(0, colon)) || !side_named(text.substr(colon + 1))) {
        usage_error("--pairing takes A:B, each base (+redirect, +kickoff_shot, +penalty_shot), ball_chaser or wander");
      }
      pairings.push_back({text.substr(0, colon), text.substr(colon + 1)});
    } else {
      usage_error("unknown argument '" + arg + "'");
    }
  }
  if (pairings.empty()) pairings = {{"base", "ball_chaser"}, {"base", "base"}};

  std::vector<Job> queue;
  for (std::size_t p = 0; p < pairings.size(); ++p) {
    for (std::uint64_t s = 0; s < seeds; ++s) queue.push_back({p, first_seed + s});
  }
  std::printf("match series: %zu pairings x %llu seeds of %u v %u (division %s), halves of %.0f s, strict_ai rules "
              "(auto continue, no early end or extra time), conditions %s, %u at a time\n",
              pairings.size(), static_cast<unsigned long long>(seeds), robots_a_side, robots_a_side,
              robots_a_side > 6 ? "A" : "B", half,
              ssl::planner::testing::to_string(conditions), jobs);
  std::fflush(stdout);
  std::vector<std::vector<nlohmann::json>> results(pairings.size());
  std::mutex results_mutex;
  std::atomic<std::size_t> next{0};
  std::atomic<int> failed{0};
  const auto started = std::chrono::steady_clock::now();
  std::vector<std::thread> workers;
  for (unsigned w = 0; w < jobs; ++w) {
    workers.emplace_back([&] {
      for (std::size_t j = next++; j < queue.size(); j = next++) {
        const Job& job = queue[j];
        const std::optional<std::string> line =
            play_in_child(pairings[job.pairing], job.seed, half, conditions, robots_a_side);
        std::lock_guard lock(results_mutex);
        if (!line) {
          ++failed;
          std::fprintf(stderr, "match_series: the match of seed %llu (%s vs %s) failed\n",
                       static_cast<unsigned long long>(job.seed), pairings[job.pairing].a.c_str(),
                       pairings[job.pairing].b.c_str());
          continue;
        }
        nlohmann::json match = nlohmann::json::parse(*line);
        const bool a_blue = match["a_is_blue"].get<bool>();
        const unsigned contact_frames = match["contact_frames"].get<unsigned>();
        std::printf("  seed %3llu %s vs %s: %s %u : %u%s%s%s\n", static_cast<unsigned long long>(job.seed),
                    pairings[job.pairing].a.c_str(), pairings[job.pairing].b.c_str(), a_blue ? "(a blue)" : "(a yellow)",
                    match["teams"][a_blue ? "blue" : "yellow"]["score"].get<unsigned>(),
                    match["teams"][a_blue ? "yellow" : "blue"]["score"].get<unsigned>(),
                    contact_frames > 0 ? (", " + std::to_string(contact_frames) + " contact frames").c_str() : "",
                    match["finished"].get<bool>() ? "" : " (no final whistle)", avoidable_fouls(match).c_str());
        for (const nlohmann::json& contact : match["contacts"]) {
          std::printf("      contact at %.1f s for %.2f s: %s %d, %s %d, closest %.3f m, %s",
                      contact["from_s"].get<double>(), contact["seconds"].get<double>(),
                      contact["robots"][0]["team"].get<std::string>().c_str(), contact["robots"][0]["id"].get<int>(),
                      contact["robots"][1]["team"].get<std::string>().c_str(), contact["robots"][1]["id"].get<int>(),
                      contact["closest_m"].get<double>(),
                      contact["command"].is_null() ? "before any command"
                                                   : contact["command"].get<std::string>().c_str());
          if (!contact["ball_distance_m"].is_null()) {
            std::printf(", ball %.2f m from the nearer", contact["ball_distance_m"].get<double>());
          }
          std::printf("\n");
        }
        for (const nlohmann::json& foul : match["avoidable_fouls"]) {
          std::printf("      avoidable foul at %.1f s: %s by %s", foul["at_s"].get<double>(),
                      foul["type"].get<std::string>().c_str(), foul["team"].get<std::string>().c_str());
          if (!foul["by_bot"].is_null()) std::printf(" robot %d", foul["by_bot"].get<int>());
          if (!foul["location"].is_null()) {
            std::printf(" at (%.2f, %.2f)", foul["location"][0].get<double>(), foul["location"][1].get<double>());
          }
          std::printf(", %s\n", foul["command"].get<std::string>().c_str());
        }
        std::fflush(stdout);
        results[job.pairing].push_back(std::move(match));
      }
    });
  }
  for (std::thread& worker : workers) worker.join();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  for (std::size_t p = 0; p < pairings.size(); ++p) {
    print_pairing(pairings[p], results[p], print_tactics, robots_a_side == 6);
  }
  std::printf("\n%zu matches in %.0f s of wall time\n", queue.size(), wall);
  return failed == 0 ? 0 : 1;
}
