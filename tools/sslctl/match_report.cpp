#include "tools/sslctl/match_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

namespace ssl::sslctl {
namespace {

using referee::Command;
using referee::Team;

std::string team_name(Team team) {
  switch (team) {
    case Team::kYellow: return "yellow";
    case Team::kBlue: return "blue";
    case Team::kUnknown: break;
  }
  return "-";
}

/// "m:ss.s" for a time in seconds.
std::string clock_text(double seconds) {
  const double clamped = std::max(seconds, 0.0);
  const int minutes = static_cast<int>(clamped / 60);
  char text[32];
  std::snprintf(text, sizeof text, "%d:%04.1f", minutes, clamped - 60.0 * minutes);
  return text;
}

double percent(double part, double whole) { return whole > 0 ? 100.0 * part / whole : 0; }

/// "taken/kept/goals".
std::string tally_text(const RestartTally& t) {
  char text[48];
  std::snprintf(text, sizeof text, "%u/%u/%u", t.taken, t.kept, t.goals);
  return text;
}

nlohmann::json tally_json(const RestartTally& t) { return {{"taken", t.taken}, {"kept", t.kept}, {"goals", t.goals}}; }

/// Two robots as [{"team", "id"}, {"team", "id"}].
nlohmann::json robots_json(const MatchReport::RobotId& first, const MatchReport::RobotId& second) {
  return {{{"team", std::string(to_string(first.team))}, {"id", first.id}},
          {{"team", std::string(to_string(second.team))}, {"id", second.id}}};
}

}  // namespace

MatchReportBuilder::Activity MatchReportBuilder::activity_of(Command command) {
  switch (command) {
    case Command::kNormalStart:
    case Command::kForceStart:
    case Command::kDirectFreeYellow:
    case Command::kDirectFreeBlue:
    case Command::kIndirectFreeYellow:
    case Command::kIndirectFreeBlue:
      return Activity::kInPlay;
    case Command::kHalt:
      return Activity::kHalted;
    default:
      return Activity::kStopped;
  }
}

double MatchReportBuilder::since_start(time::Timestamp t) const {
  return first_ ? time::to_seconds(t - *first_) : 0;
}

void MatchReportBuilder::on_referee(const referee::RefereeState& state, time::Timestamp t) {
  if (last_ && t < *last_) return;
  if (!first_) first_ = t;
  ++report_.referee_samples;
  if (previous_ && last_) {
    const double dt = time::to_seconds(t - *last_);
    switch (activity_of(previous_->command)) {
      case Activity::kInPlay: report_.in_play += dt; break;
      case Activity::kStopped: report_.stopped += dt; break;
      case Activity::kHalted: report_.halted += dt; break;
    }
  }
  const double at = since_start(t);
  if (!previous_ || previous_->command_counter != state.command_counter) {
    ++report_.commands[state.command];
    if (state.command == Command::kBallPlacementYellow) ++report_.yellow.placements;
    if (state.command == Command::kBallPlacementBlue) ++report_.blue.placements;
  }
  if (!previous_ || previous_->stage != state.stage) report_.stages.push_back({at, state.stage});
  if (state.blue_team_on_positive_half &&
      (report_.sides.empty() || report_.sides.back().blue_on_positive_half != *state.blue_team_on_positive_half)) {
    report_.sides.push_back({at, *state.blue_team_on_positive_half});
  }
  if (activity_of(state.command) != Activity::kInPlay) stall_anchor_.reset();
  for (const referee::GameEvent& event : state.game_events) {
    if (!seen_events_.insert(referee::event_key(event)).second) continue;
    ++event_counts_[{event.type, event.by_team}];
    if (referee::is_avoidable_foul(event.type)) {
      report_.avoidable_fouls.push_back({.at = at,
                                         .type = event.type,
                                         .team = event.by_team,
                                         .by_bot = event.by_bot,
                                         .location = event.location,
                                         .command = state.command});
    }
    if (event.type == referee::GameEventType::kGoal) {
      MatchReport::Goal goal{.at = at, .stage = state.stage, .team = event.by_team, .by_bot = event.by_bot};
      if (state.stage_time_left) goal.stage_time_left = time::to_seconds(*state.stage_time_left);
      report_.goals.push_back(goal);
      if (event.by_team != referee::Team::kUnknown) {
        play_.on_goal(event.by_team == referee::Team::kBlue ? TeamColor::kBlue : TeamColor::kYellow);
      }
    }
  }
  report_.source = state.source_identifier;
  for (auto [line, info] : {std::pair{&report_.yellow, &state.yellow}, std::pair{&report_.blue, &state.blue}}) {
    line->name = info->name;
    line->score = info->score;
    line->fouls = info->foul_counter;
    line->yellow_cards = info->yellow_cards;
    line->red_cards = info->red_cards;
  }
  // The restart the ball is in play from: a free kick's, or the kickoff's or penalty's NORMAL_START.
  std::optional<Restart> restart;
  if (referee::is_kickoff(state.command) || referee::is_penalty(state.command)) {
    if (const auto team = referee::team_of(state.command)) {
      prepared_ = Restart{.team = *team,
                          .kind = referee::is_kickoff(state.command) ? RestartKind::kKickoff : RestartKind::kPenalty};
    }
  } else if (state.command == referee::Command::kNormalStart) {
    restart = prepared_;
  } else {
    prepared_.reset();
    if (referee::is_free_kick(state.command)) {
      if (const auto team = referee::team_of(state.command)) {
        restart = Restart{.team = *team, .kind = RestartKind::kFreeKick};
      }
    }
  }
  play_.set_keepers(state.blue.goalkeeper, state.yellow.goalkeeper);
  play_.on_referee(activity_of(state.command) == Activity::kInPlay, state.blue_team_on_positive_half, restart);
  report_.final_stage = state.stage;
  if (state.stage == referee::Stage::kPostGame) report_.final_whistle = true;
  report_.duration = at;
  previous_ = state;
  last_ = t;
}

void MatchReportBuilder::set_field(const FieldGeometry& field) {
  field_ = field;
  play_.set_field(field.field_length, field.goal_width);
}

bool MatchReportBuilder::inside_field(const geom::Vec2& ball) const {
  return field_ && std::abs(ball.x()) <= field_->half_length() + field_->ball_radius &&
         std::abs(ball.y()) <= field_->half_width() + field_->ball_radius;
}

void MatchReportBuilder::on_ball(const geom::Vec2& ball, time::Timestamp t) {
  if (last_ball_time_ && t < *last_ball_time_) return;
  if (last_ball_time_ && ball_in_play_) {
    in_play_vision_ += std::min(time::to_seconds(t - *last_ball_time_), kBallUnseenAfter);
  }
  last_ball_time_ = t;
  last_ball_ = ball;
  ball_in_play_ = previous_ && activity_of(previous_->command) == Activity::kInPlay && inside_field(ball);
  ++report_.ball_samples;
  if (!report_.longest_stall) report_.longest_stall = MatchReport::Stall{};
  if (!previous_ || activity_of(previous_->command) != Activity::kInPlay) {
    stall_anchor_.reset();
    return;
  }
  if (!stall_anchor_ || (ball - stall_anchor_->first).norm() >= kStallDistance) {
    stall_anchor_ = {ball, t};
    return;
  }
  const double seconds = time::to_seconds(t - stall_anchor_->second);
  if (seconds > report_.longest_stall->seconds) {
    report_.longest_stall = MatchReport::Stall{
        .seconds = seconds, .from = since_start(stall_anchor_->second), .ball = stall_anchor_->first};
  }
}

void MatchReportBuilder::on_frame(const geom::Vec2& ball, std::span<const PlayAccount::Robot> robots,
                                  time::Timestamp t, std::optional<PlayAccount::Camera> camera) {
  if (last_ball_time_ && t < *last_ball_time_) return;
  play_.on_frame(ball, robots, t, camera);
  on_ball(ball, t);
  on_robots(robots, t);
}

void MatchReportBuilder::on_robots(std::span<const PlayAccount::Robot> robots, time::Timestamp t) {
  if (last_robots_time_ && t < *last_robots_time_) return;
  last_robots_time_ = t;
  if (robots.empty()) return;
  ++report_.robot_frames;
  bool contact = false;
  for (std::size_t i = 0; i < robots.size(); ++i) {
    for (std::size_t j = i + 1; j < robots.size(); ++j) {
      const PlayAccount::Robot& a = robots[i];
      const PlayAccount::Robot& b = robots[j];
      if (a.team == b.team && a.id == b.id) continue;  // one robot detected twice
      const double distance = (a.position - b.position).norm();
      if (distance < kContactDistance) {
        contact = true;
        on_contact(a, b, distance, t);
      }
      if (!report_.closest_robots || distance < report_.closest_robots->distance) {
        report_.closest_robots = MatchReport::ClosestRobots{
            .distance = distance, .at = since_start(t), .first = {a.team, a.id}, .second = {b.team, b.id}};
      }
    }
  }
  if (contact) ++report_.contact_frames;
}

void MatchReportBuilder::on_contact(const PlayAccount::Robot& a, const PlayAccount::Robot& b, double distance,
                                    time::Timestamp t) {
  auto key_of = [](const PlayAccount::Robot& r) { return std::pair{static_cast<int>(r.team), r.id}; };
  const bool a_first = key_of(a) < key_of(b);
  const PlayAccount::Robot& first = a_first ? a : b;
  const PlayAccount::Robot& second = a_first ? b : a;
  const auto key = std::pair{key_of(first), key_of(second)};
  std::optional<double> ball_distance;
  if (last_ball_) {
    ball_distance = std::min((*last_ball_ - a.position).norm(), (*last_ball_ - b.position).norm());
  }
  const auto open = open_contacts_.find(key);
  if (open != open_contacts_.end() && time::to_seconds(t - open->second.second) <= kContactEpisodeGap) {
    MatchReport::ContactEpisode& episode = report_.contacts[open->second.first];
    episode.seconds = since_start(t) - episode.from;
    ++episode.frames;
    if (distance < episode.closest) {
      episode.closest = distance;
      episode.ball_distance = ball_distance;
    }
    open->second.second = t;
    return;
  }
  report_.contacts.push_back(MatchReport::ContactEpisode{
      .first = {first.team, first.id},
      .second = {second.team, second.id},
      .from = since_start(t),
      .frames = 1,
      .closest = distance,
      .command = previous_ ? std::optional(previous_->command) : std::nullopt,
      .ball_distance = ball_distance});
  open_contacts_[key] = {report_.contacts.size() - 1, t};
}

MatchReport MatchReportBuilder::report() const {
  MatchReport out = report_;
  out.blue.play = play_.team(TeamColor::kBlue);
  out.yellow.play = play_.team(TeamColor::kYellow);
  for (const auto& [key, count] : event_counts_) {
    out.events.push_back({.type = key.first, .team = key.second, .count = count});
    const bool ball_out = key.first == referee::GameEventType::kBallLeftFieldTouchLine ||
                          key.first == referee::GameEventType::kBallLeftFieldGoalLine;
    if (ball_out && key.second == Team::kYellow) out.yellow.balls_out += count;
    if (ball_out && key.second == Team::kBlue) out.blue.balls_out += count;
  }
  if (field_) out.in_play_vision = in_play_vision_;
  return out;
}

std::string to_text(const MatchReport& r) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "match report: %s, %.1f s of referee packets (%llu), %llu ball observations\n",
                r.source.empty() ? "unknown referee" : r.source.c_str(), r.duration,
                static_cast<unsigned long long>(r.referee_samples), static_cast<unsigned long long>(r.ball_samples));
  out << line;
  // "yellow 2 : 1 blue", with the team names when the referee gives others than the colours.
  const auto named = [](const std::string& name, const char* colour) {
    return name.empty() || name == colour ? std::string(colour) : name + " (" + colour + ")";
  };
  out << "score: " << named(r.yellow.name, "yellow") << ' ' << r.yellow.score << " : " << r.blue.score << ' '
      << named(r.blue.name, "blue")
      << (r.final_whistle ? ", final whistle" : ", not finished") << " (" << referee::to_string(r.final_stage)
      << ")\n";
  out << "goals:" << (r.goals.empty() ? " none" : "") << '\n';
  for (const MatchReport::Goal& goal : r.goals) {
    out << "  " << clock_text(goal.at) << "  " << team_name(goal.team);
    if (goal.by_bot) out << " robot " << *goal.by_bot;
    out << "  (" << referee::to_string(goal.stage);
    if (goal.stage_time_left) out << ", " << clock_text(*goal.stage_time_left) << " left";
    out << ")\n";
  }
  const double total = r.in_play + r.stopped + r.halted;
  std::snprintf(line, sizeof line, "time: in play %.1f s (%.0f %%), stopped %.1f s (%.0f %%), halted %.1f s (%.0f %%)\n",
                r.in_play, percent(r.in_play, total), r.stopped, percent(r.stopped, total), r.halted,
                percent(r.halted, total));
  out << line;
  if (!r.in_play_vision) {
    out << "in play from vision: unknown (no field size)\n";
  } else {
    std::snprintf(line, sizeof line,
                  "in play from vision (the ball seen inside the field): %.1f s (%.0f %% of %.1f s)\n",
                  *r.in_play_vision, percent(*r.in_play_vision, r.duration), r.duration);
    out << line;
  }
  if (!r.longest_stall) {
    out << "longest stall in play: unknown (no vision)\n";
  } else {
    std::snprintf(line, sizeof line, "longest stall in play: %.1f s from %s, ball at (%.2f, %.2f)\n",
                  r.longest_stall->seconds, clock_text(r.longest_stall->from).c_str(), r.longest_stall->ball.x(),
                  r.longest_stall->ball.y());
    out << line;
  }
  if (!r.closest_robots) {
    out << "robots: no frame with two robots\n";
  } else {
    const MatchReport::ClosestRobots& c = *r.closest_robots;
    std::snprintf(line, sizeof line,
                  "robots: closest two %.3f m apart at %s (%s %u, %s %u); contact frames (centres under %.2f m, "
                  "per camera frame) %llu\n",
                  c.distance, clock_text(c.at).c_str(), std::string(to_string(c.first.team)).c_str(), c.first.id,
                  std::string(to_string(c.second.team)).c_str(), c.second.id, MatchReportBuilder::kContactDistance,
                  static_cast<unsigned long long>(r.contact_frames));
    out << line;
  }
  if (!r.contacts.empty()) {
    out << "contacts: " << r.contacts.size() << " episodes\n";
    for (const MatchReport::ContactEpisode& c : r.contacts) {
      std::snprintf(line, sizeof line, "  %s for %.2f s (%llu frames): %s %u, %s %u, closest %.3f m, %s",
                    clock_text(c.from).c_str(), c.seconds, static_cast<unsigned long long>(c.frames),
                    std::string(to_string(c.first.team)).c_str(), c.first.id,
                    std::string(to_string(c.second.team)).c_str(), c.second.id, c.closest,
                    c.command ? std::string(referee::to_string(*c.command)).c_str() : "before any command");
      out << line;
      if (c.ball_distance) {
        std::snprintf(line, sizeof line, ", ball %.2f m from the nearer", *c.ball_distance);
        out << line;
      }
      out << '\n';
    }
  }
  if (!r.avoidable_fouls.empty()) {
    out << "avoidable fouls: " << r.avoidable_fouls.size() << '\n';
    for (const MatchReport::AvoidableFoul& foul : r.avoidable_fouls) {
      out << "  " << clock_text(foul.at) << "  " << referee::to_string(foul.type) << "  " << team_name(foul.team);
      if (foul.by_bot) out << " robot " << *foul.by_bot;
      if (foul.location) {
        std::snprintf(line, sizeof line, " at (%.2f, %.2f)", foul.location->x(), foul.location->y());
        out << line;
      }
      out << ", " << referee::to_string(foul.command) << '\n';
    }
  }
  out << "commands:";
  for (const auto& [command, count] : r.commands) out << ' ' << referee::to_string(command) << ' ' << count << ',';
  out << '\n' << "game events:" << (r.events.empty() ? " none" : "") << '\n';
  for (const MatchReport::EventCount& event : r.events) {
    out << "  " << referee::to_string(event.type) << "  " << team_name(event.team) << ' ' << event.count << '\n';
  }
  out << "fouls: yellow " << r.yellow.fouls << ", blue " << r.blue.fouls << "; cards: yellow " << r.yellow.yellow_cards
      << " yellow / " << r.yellow.red_cards << " red, blue " << r.blue.yellow_cards << " yellow / " << r.blue.red_cards
      << " red\n";
  out << "placements: yellow " << r.yellow.placements << ", blue " << r.blue.placements << "; balls out: yellow "
      << r.yellow.balls_out << ", blue " << r.blue.balls_out << '\n';
  if (r.robot_frames > 0) {
    const double possessed = r.yellow.play.possession + r.blue.play.possession;
    for (auto [name, team] : {std::pair{"yellow", &r.yellow}, std::pair{"blue", &r.blue}}) {
      const TeamPlay& p = team->play;
      char text[384];
      std::snprintf(text, sizeof text,
                    "play %s: passes %u tried, %u completed (%.0f %%), %u intercepted, %u out; shots %u, %u on "
                    "target, %u scored, %u saved, %u blocked, from %.1f m on average; kicks %u; possession %.0f %%; "
                    "kickoffs %s, penalties %s, free kicks %s (taken, kept, goals from them)\n",
                    name, p.passes_tried, p.passes_completed, percent(p.passes_completed, p.passes_tried),
                    p.passes_intercepted, p.passes_out, p.shots, p.shots_on_target, p.shots_scored, p.shots_saved,
                    p.shots_blocked, p.shot_distance_mean(), p.kicks,
                    percent(p.possession, possessed), tally_text(p.kickoffs).c_str(), tally_text(p.penalties).c_str(),
                    tally_text(p.free_kicks).c_str());
      out << text;
    }
  }
  out << "stages:";
  for (const MatchReport::StageChange& stage : r.stages) {
    out << ' ' << clock_text(stage.at) << ' ' << referee::to_string(stage.stage) << ',';
  }
  out << "\nsides:";
  for (const MatchReport::SideChange& side : r.sides) {
    out << ' ' << clock_text(side.at) << " blue on the " << (side.blue_on_positive_half ? "positive" : "negative")
        << " half,";
  }
  out << '\n';
  if (r.malformed > 0) out << "malformed packets: " << r.malformed << '\n';
  return out.str();
}

std::string to_json(const MatchReport& r) {
  using nlohmann::json;
  json out;
  out["source"] = r.source;
  out["referee_samples"] = r.referee_samples;
  out["ball_samples"] = r.ball_samples;
  out["robot_frames"] = r.robot_frames;
  out["duration_s"] = r.duration;
  for (auto [key, line] : {std::pair{"yellow", &r.yellow}, std::pair{"blue", &r.blue}}) {
    out["teams"][key] = {{"name", line->name},           {"score", line->score},
                         {"fouls", line->fouls},         {"yellow_cards", line->yellow_cards},
                         {"red_cards", line->red_cards}, {"placements", line->placements},
                         {"balls_out", line->balls_out}};
    if (r.robot_frames > 0) {
      const TeamPlay& p = line->play;
      out["teams"][key]["play"] = {{"passes_tried", p.passes_tried}, {"passes_completed", p.passes_completed},
                                   {"passes_intercepted", p.passes_intercepted}, {"passes_out", p.passes_out},
                                   {"shots", p.shots},               {"shots_on_target", p.shots_on_target},
                                   {"shots_scored", p.shots_scored}, {"shots_saved", p.shots_saved},
                                   {"shots_blocked", p.shots_blocked},
                                   {"shot_distance_mean_m", p.shot_distance_mean()},
                                   {"kicks", p.kicks},               {"possession_s", p.possession},
                                   {"kickoffs", tally_json(p.kickoffs)},
                                   {"penalties", tally_json(p.penalties)},
                                   {"free_kicks", tally_json(p.free_kicks)}};
    }
  }
  out["goals"] = json::array();
  for (const MatchReport::Goal& goal : r.goals) {
    json g = {{"at_s", goal.at}, {"stage", referee::to_string(goal.stage)}, {"team", team_name(goal.team)}};
    if (goal.stage_time_left) g["stage_time_left_s"] = *goal.stage_time_left;
    if (goal.by_bot) g["by_bot"] = *goal.by_bot;
    out["goals"].push_back(g);
  }
  out["time_s"] = {{"in_play", r.in_play}, {"stopped", r.stopped}, {"halted", r.halted}, {"in_play_vision", nullptr}};
  out["in_play_vision_share"] = nullptr;  // of duration_s
  if (r.in_play_vision) {
    out["time_s"]["in_play_vision"] = *r.in_play_vision;
    out["in_play_vision_share"] = r.duration > 0 ? *r.in_play_vision / r.duration : 0;
  }
  out["closest_robots"] = nullptr;
  if (r.closest_robots) {
    const MatchReport::ClosestRobots& c = *r.closest_robots;
    out["closest_robots"] = {{"distance_m", c.distance},
                             {"at_s", c.at},
                             {"robots", robots_json(c.first, c.second)}};
  }
  out["contact_frames"] = r.contact_frames;
  out["contacts"] = json::array();
  for (const MatchReport::ContactEpisode& c : r.contacts) {
    out["contacts"].push_back(
        {{"robots", robots_json(c.first, c.second)},
         {"from_s", c.from},
         {"seconds", c.seconds},
         {"frames", c.frames},
         {"closest_m", c.closest},
         {"command", c.command ? json(std::string(referee::to_string(*c.command))) : json(nullptr)},
         {"ball_distance_m", c.ball_distance ? json(*c.ball_distance) : json(nullptr)}});
  }
  out["avoidable_fouls"] = json::array();
  for (const MatchReport::AvoidableFoul& foul : r.avoidable_fouls) {
    out["avoidable_fouls"].push_back(
        {{"at_s", foul.at},
         {"type", std::string(referee::to_string(foul.type))},
         {"team", team_name(foul.team)},
         {"by_bot", foul.by_bot ? json(*foul.by_bot) : json(nullptr)},
         {"location", foul.location ? json{foul.location->x(), foul.location->y()} : json(nullptr)},
         {"command", std::string(referee::to_string(foul.command))}});
  }
  if (r.longest_stall) {
    out["longest_stall"] = {{"seconds", r.longest_stall->seconds},
                            {"from_s", r.longest_stall->from},
                            {"ball", {r.longest_stall->ball.x(), r.longest_stall->ball.y()}}};
  } else {
    out["longest_stall"] = nullptr;
  }
  out["commands"] = json::object();
  for (const auto& [command, count] : r.commands) out["commands"][std::string(referee::to_string(command))] = count;
  out["game_events"] = json::array();
  for (const MatchReport::EventCount& event : r.events) {
    out["game_events"].push_back(
        {{"type", referee::to_string(event.type)}, {"team", team_name(event.team)}, {"count", event.count}});
  }
  out["stages"] = json::array();
  for (const MatchReport::StageChange& stage : r.stages) {
    out["stages"].push_back({{"at_s", stage.at}, {"stage", referee::to_string(stage.stage)}});
  }
  out["sides"] = json::array();
  for (const MatchReport::SideChange& side : r.sides) {
    out["sides"].push_back({{"at_s", side.at}, {"blue_on_positive_half", side.blue_on_positive_half}});
  }
  out["final_stage"] = referee::to_string(r.final_stage);
  out["final_whistle"] = r.final_whistle;
  out["malformed_packets"] = r.malformed;
  return out.dump();
}

}  // namespace ssl::sslctl
