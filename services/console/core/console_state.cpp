#include "services/console/core/console_state.h"

#include <cmath>
#include <cstdio>

#include "libs/domain/keep_out.h"
#include "libs/domain/rules.h"
#include "libs/domain/team_frame.h"

namespace ssl::console {
namespace {

using nlohmann::json;
using referee::Command;

/// A finite number, or null: JSON has no NaN and the page must never see one.
json number(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

json point(const geom::Vec2& p) { return json::array({number(p.x()), number(p.y())}); }

std::string_view team_name(TeamColor team) { return to_string(team); }

std::optional<TeamColor> team_of(referee::Team team) {
  if (team == referee::Team::kBlue) return TeamColor::kBlue;
  if (team == referee::Team::kYellow) return TeamColor::kYellow;
  return std::nullopt;
}

json team_or_null(std::optional<TeamColor> team) {
  return team ? json(team_name(*team)) : json(nullptr);
}

std::string_view to_string(NodeStatus status) {
  switch (status) {
    case NodeStatus::kIdle: return "idle";
    case NodeStatus::kRunning: return "running";
    case NodeStatus::kSuccess: return "success";
    case NodeStatus::kFailure: return "failure";
  }
  return "idle";
}

std::string_view to_string(HealthLevel level) {
  switch (level) {
    case HealthLevel::kOk: return "ok";
    case HealthLevel::kWarn: return "warn";
    case HealthLevel::kError: return "error";
  }
  return "error";
}

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

json robot_json(const RobotView& robot, const wm::TeamFrame& frame) {
  return {{"team", team_name(robot.team)},
          {"id", robot.id},
          {"x", number(frame.to_vision_point(robot.position).x())},
          {"y", number(frame.to_vision_point(robot.position).y())},
          {"a", number(frame.to_vision_angle(robot.heading))},
          {"vx", number(frame.vector(robot.velocity).x())},
          {"vy", number(frame.vector(robot.velocity).y())},
          {"visible", robot.visible}};
}

json team_info_json(const referee::TeamInfo& team) {
  return {{"name", team.name},
          {"score", team.score},
          {"yellow_cards", team.yellow_cards},
          {"red_cards", team.red_cards},
          {"timeouts", team.timeouts},
          {"goalkeeper", team.goalkeeper},
          {"fouls", team.foul_counter}};
}

json on_off(std::string label, bool on) { return {{"label", std::move(label)}, {"on", on}}; }
json value(std::string label, std::string text) { return {{"label", std::move(label)}, {"value", std::move(text)}}; }
json metres(std::string label, double m) { return value(std::move(label), fixed(m, 2) + " m"); }
json seconds(std::string label, double s) { return value(std::move(label), fixed(s, 1) + " s"); }

}  // namespace

void ConsoleState::log(LogEntry entry) {
  new_entries_.push_back(entry);
  log_.add(std::move(entry));
}

std::vector<LogEntry> ConsoleState::take_new_entries() { return std::exchange(new_entries_, {}); }

void ConsoleState::on_geometry(const FieldGeometry& field) {
  field_ = field;
  has_field_ = true;
}

void ConsoleState::on_vision(const CameraView& camera, time::Timestamp now) {
  cameras_[camera.camera_id] = {camera, now};
  if (!camera.balls.empty()) report_.on_ball(camera.balls.front(), now);
}

void ConsoleState::on_world(TeamColor team, const TeamWorld& world, time::Timestamp now) {
  TeamSlot& slot = teams_[team];
  slot.world = world;
  slot.world_at = now;
}

void ConsoleState::on_debug(TeamColor team, const TeamDebug& debug) { teams_[team].debug = debug; }

bool ConsoleState::on_referee(const referee::RefereeState& state, time::Timestamp now) {
  report_.on_referee(state, now);
  const std::optional<referee::RefereeState> previous = std::exchange(referee_, state);
  if (!previous) {
    log({now, LogKind::kCommand, std::string(referee::to_string(state.command)), referee::team_of(state.command)});
    return true;
  }
  if (state.command_counter != previous->command_counter || state.command != previous->command) {
    std::string text(referee::to_string(state.command));
    if (state.designated_position &&
        (state.command == Command::kBallPlacementBlue || state.command == Command::kBallPlacementYellow)) {
      text += " to (" + fixed(state.designated_position->x(), 2) + ", " + fixed(state.designated_position->y(), 2) + ")";
    }
    log({now, LogKind::kCommand, std::move(text), referee::team_of(state.command)});
  }
  for (const auto& [team, before, after] :
       {std::tuple{TeamColor::kYellow, previous->yellow.score, state.yellow.score},
        std::tuple{TeamColor::kBlue, previous->blue.score, state.blue.score}}) {
    if (after == before) continue;
    log({now, LogKind::kGoal,
         std::string(after > before ? "goal " : "goal revoked ") + std::string(team_name(team)) + ": yellow " +
             std::to_string(state.yellow.score) + " : " + std::to_string(state.blue.score) + " blue",
         team});
  }
  if (!state.status_message.empty() && state.status_message != previous->status_message) {
    log({now, LogKind::kStatus, state.status_message, std::nullopt});
  }
  // Everything the page shows except the clocks that run in every packet.
  return state.command != previous->command || state.command_counter != previous->command_counter ||
         state.stage != previous->stage || state.yellow != previous->yellow || state.blue != previous->blue ||
         state.designated_position != previous->designated_position ||
         state.blue_team_on_positive_half != previous->blue_team_on_positive_half ||
         state.next_command != previous->next_command || state.status_message != previous->status_message ||
         state.stage_time_left.has_value() != previous->stage_time_left.has_value() ||
         (state.stage_time_left && previous->stage_time_left &&
          std::chrono::duration_cast<std::chrono::seconds>(*state.stage_time_left) !=
              std::chrono::duration_cast<std::chrono::seconds>(*previous->stage_time_left));
}

void ConsoleState::on_referee_event(const referee::RefereeEvent& event, time::Timestamp now) {
  const referee::GameEvent& game_event = event.event;
  const LogKind kind = referee::is_foul(game_event.type)    ? LogKind::kFoul
                       : game_event.type == referee::GameEventType::kGoal ? LogKind::kGoal
                                                                          : LogKind::kEvent;
  std::string text(referee::to_string(game_event.type));
  const std::optional<TeamColor> team = team_of(game_event.by_team);
  if (team) text += std::string(" by ") + std::string(team_name(*team));
  if (game_event.by_bot) text.append(" ").append(std::to_string(*game_event.by_bot));
  if (!game_event.text.empty()) text += ": " + game_event.text;
  log({now, kind, std::move(text), team});
}

void ConsoleState::on_health(const ServiceHealth& health, time::Timestamp now) {
  health_[health.service] = {health, now};
}

void ConsoleState::on_feedback(const RobotFeedbackView& feedback, time::Timestamp now) {
  feedback_[{feedback.team, feedback.id}] = {feedback, now};
}

void ConsoleState::on_estop(const EstopView& estop, time::Timestamp now) {
  const bool changed = !estop_ || estop_->engaged != estop.engaged;
  estop_ = estop;
  if (!changed) return;
  std::string text = estop.engaged ? "e-stop engaged" : "e-stop released";
  if (!estop.source.empty()) text += " by " + estop.source;
  if (!estop.reason.empty()) text += ": " + estop.reason;
  log({now, LogKind::kEstop, std::move(text), std::nullopt});
}

bool ConsoleState::on_parameters(const ParameterStateView& state) {
  auto [it, inserted] = parameters_.try_emplace(state.target, state);
  if (inserted) return true;
  const ParameterStateView before = std::exchange(it->second, state);
  if (before.revision != state.revision || before.accepted != state.accepted || before.saved_file != state.saved_file ||
      before.params.size() != state.params.size()) {
    return true;
  }
  for (std::size_t i = 0; i < state.params.size(); ++i) {
    if (before.params[i].key != state.params[i].key || before.params[i].value != state.params[i].value) return true;
  }
  return false;
}

const ParameterStateView* ConsoleState::parameters(const std::string& target) const {
  const auto it = parameters_.find(target);
  return it == parameters_.end() ? nullptr : &it->second;
}

void ConsoleState::on_operator(std::string text, time::Timestamp now) {
  log({now, LogKind::kOperator, std::move(text), std::nullopt});
}

std::optional<geom::Vec2> ConsoleState::vision_ball() const {
  const CameraSlot* freshest = nullptr;
  for (const auto& [id, slot] : cameras_) {
    if (!slot.camera.balls.empty() && (!freshest || slot.at > freshest->at)) freshest = &slot;
  }
  if (!freshest) return std::nullopt;
  return freshest->camera.balls.front();
}

std::optional<RobotView> ConsoleState::vision_robot(TeamColor team, std::uint32_t id) const {
  std::optional<RobotView> found;
  time::Timestamp found_at;
  for (const auto& [camera_id, slot] : cameras_) {
    for (const RobotView& robot : slot.camera.robots) {
      if (robot.team == team && robot.id == id && (!found || slot.at > found_at)) {
        found = robot;
        found_at = slot.at;
      }
    }
  }
  return found;
}

json ConsoleState::hello_json(bool operator_allowed, bool simulator) const {
  json profile = nullptr;
  if (profile_) {
    const referee::RefereeRules& r = profile_->rules;
    const referee::GameSettings& g = profile_->game;
    json game = json::array({seconds("half duration", g.half_duration),
                             value("kickoff team", std::string(team_name(g.kickoff_team))),
                             on_off("force start after goal", g.force_start_after_goal),
                             on_off("continues by itself", g.auto_continue), seconds("stop duration", g.stop_duration),
                             on_off("ball placement by the teams", g.ball_placement)});
    json sections = json::array();
    sections.push_back({{"title", "Game settings"}, {"fields", game}});
    sections.push_back({{"title", "Goal detection"},
                        {"fields", {on_off("enabled", r.goal_detection.enabled),
                                    seconds("cooldown", r.goal_detection.cooldown)}}});
    sections.push_back({{"title", "Out of bounds"},
                        {"fields", {on_off("enabled", r.out_of_bounds.enabled),
                                    on_off("ball placement", r.out_of_bounds.ball_placement)}}});
    sections.push_back({{"title", "Defense area"},
                        {"fields", {on_off("enabled", r.defense_area.enabled),
                                    value("max defenders", std::to_string(r.defense_area.max_defenders)),
                                    on_off("attacker infringement", r.defense_area.attacker_infringement)}}});
    sections.push_back({{"title", "Keep-out zone"},
                        {"fields", {on_off("enabled", r.keep_out.enabled), metres("radius", r.keep_out.radius),
                                    seconds("violation persistence", r.keep_out.violation_persistence)}}});
    sections.push_back(
        {{"title", "Other rules"},
         {"fields", {on_off("no progress", r.no_progress.enabled),
                     on_off("placement interference", r.placement_interference.enabled),
                     on_off("crash", r.crash.enabled), on_off("speed in STOP", r.stop_speed.enabled),
                     on_off("double touch", r.double_touch.enabled), on_off("ball speed", r.ball_speed.enabled),
                     on_off("boundary crossing", r.boundary_crossing.enabled),
                     on_off("dribbling", r.dribbling.enabled),
                     on_off("attacker near defense area", r.attacker_defense_area_distance.enabled),
                     on_off("keeper held ball", r.keeper_held_ball.enabled),
                     on_off("robot count", r.robot_count.enabled), on_off("cards", r.cards.enabled)}}});
    profile = {{"name", profile_->name}, {"sections", std::move(sections)}};
  }
  return {{"version", 1}, {"operator", operator_allowed}, {"simulator", simulator}, {"profile", std::move(profile)}};
}

json ConsoleState::geometry_json() const {
  const FieldGeometry field = has_field_ ? field_ : FieldGeometry::division_b();
  return {{"field_length", field.field_length},
          {"field_width", field.field_width},
          {"goal_width", field.goal_width},
          {"goal_depth", field.goal_depth},
          {"boundary_width", field.boundary_width},
          {"penalty_area_depth", field.penalty_area_depth},
          {"penalty_area_width", field.penalty_area_width},
          {"center_circle_radius", field.center_circle_radius},
          {"ball_radius", field.ball_radius},
          {"robot_radius", field.max_robot_radius},
          {"known", has_field_}};
}

json ConsoleState::team_json(TeamColor team, const TeamSlot& slot, time::Timestamp now) const {
  if (!slot.world && !slot.debug) return nullptr;
  const wm::TeamFrame frame = wm::TeamFrame::with_flip(slot.world ? slot.world->flipped : false);
  json out;
  out["age"] = slot.world ? number(time::to_seconds(now - slot.world_at)) : json(nullptr);
  out["ball"] = nullptr;
  out["robots"] = json::array();
  out["possession"] = "none";
  if (slot.world) {
    const TeamWorld& world = *slot.world;
    if (world.ball) {
      const geom::Vec2 p = frame.to_vision_point(world.ball->position);
      const geom::Vec2 v = frame.vector(world.ball->velocity);
      out["ball"] = {{"x", number(p.x())}, {"y", number(p.y())}, {"z", number(world.ball->height)},
                     {"vx", number(v.x())}, {"vy", number(v.y())}, {"visible", world.ball->visible}};
    }
    for (const RobotView& robot : world.robots) out["robots"].push_back(robot_json(robot, frame));
    switch (world.possession) {
      case Possession::kNone: out["possession"] = "none"; break;
      case Possession::kOurs: out["possession"] = team_name(team); break;
      case Possession::kTheirs: out["possession"] = team_name(opponent(team)); break;
      case Possession::kContested: out["possession"] = "contested"; break;
    }
  }
  out["play"] = slot.debug ? slot.debug->play : "";
  out["tactic"] = slot.debug ? slot.debug->tactic : "";
  out["tick_ms"] = slot.debug ? number(slot.debug->tick_duration * 1e3) : json(nullptr);
  out["roles"] = json::array();
  out["tree"] = json::array();
  out["paths"] = json::array();
  if (slot.debug) {
    for (const RoleView& role : slot.debug->roles) {
      out["roles"].push_back({{"id", role.id}, {"role", role.role}, {"tactic", role.tactic}, {"skill", role.skill}});
    }
    for (const TreeNodeView& node : slot.debug->tree) {
      out["tree"].push_back({{"name", node.name}, {"depth", node.depth}, {"status", to_string(node.status)}});
    }
    for (const PathView& path : slot.debug->paths) {
      json points = json::array();
      for (const geom::Vec2& p : path.points) points.push_back(point(frame.to_vision_point(p)));
      out["paths"].push_back({{"id", path.id},
                              {"points", std::move(points)},
                              {"destination", point(frame.to_vision_point(path.destination))}});
    }
  }
  return out;
}

json ConsoleState::frame_json(time::Timestamp now) const {
  json balls = json::array();
  json robots = json::array();
  for (const auto& [id, slot] : cameras_) {
    for (const geom::Vec2& ball : slot.camera.balls) balls.push_back({{"x", number(ball.x())}, {"y", number(ball.y())}});
    for (const RobotView& robot : slot.camera.robots) {
      robots.push_back({{"team", team_name(robot.team)},
                        {"id", robot.id},
                        {"x", number(robot.position.x())},
                        {"y", number(robot.position.y())},
                        {"a", number(robot.heading)}});
    }
  }
  json teams = {{"blue", nullptr}, {"yellow", nullptr}};
  for (const auto& [team, slot] : teams_) teams[std::string(team_name(team))] = team_json(team, slot, now);
  return {{"t", now.nanoseconds()},
          {"vision", {{"balls", std::move(balls)}, {"robots", std::move(robots)}}},
          {"teams", std::move(teams)}};
}

json ConsoleState::keep_out_json() const {
  json zones = json::array();
  if (!referee_) return zones;
  const std::optional<geom::Vec2> ball = vision_ball();
  if (!ball) return zones;
  const double radius = has_field_ ? field_.max_robot_radius : FieldGeometry{}.max_robot_radius;
  const Command command = referee_->command;
  const std::optional<TeamColor> team = referee::team_of(command);
  auto circle = [&](const char* who) {
    const geom::Circle zone = ball_keep_out(*ball, radius);
    zones.push_back({{"kind", "circle"}, {"center", point(zone.center)}, {"radius", zone.radius}, {"team", who}});
  };
  switch (command) {
    case Command::kStop:
    case Command::kGoalBlue:
    case Command::kGoalYellow:
      circle("both");
      break;
    case Command::kPrepareKickoffBlue:
    case Command::kPrepareKickoffYellow:
    case Command::kDirectFreeBlue:
    case Command::kDirectFreeYellow:
    case Command::kIndirectFreeBlue:
    case Command::kIndirectFreeYellow:
      circle(team_name(opponent(*team)).data());
      break;
    case Command::kBallPlacementBlue:
    case Command::kBallPlacementYellow:
      if (referee_->designated_position) {
        const geom::Stadium zone = placement_keep_out(*ball, *referee_->designated_position, radius);
        zones.push_back({{"kind", "stadium"},
                         {"a", point(zone.spine.start)},
                         {"b", point(zone.spine.end)},
                         {"radius", zone.radius},
                         {"team", team_name(opponent(*team))}});
      }
      break;
    default:
      break;
  }
  return zones;
}

json ConsoleState::referee_json() const {
  if (!referee_) return nullptr;
  const referee::RefereeState& r = *referee_;
  return {{"source", r.source == referee::RefereeSource::kBuiltin ? "builtin" : "gc"},
          {"command", referee::to_string(r.command)},
          {"next_command", r.next_command ? json(referee::to_string(*r.next_command)) : json(nullptr)},
          {"command_counter", r.command_counter},
          {"stage", referee::to_string(r.stage)},
          {"stage_time_left", r.stage_time_left ? number(time::to_seconds(*r.stage_time_left)) : json(nullptr)},
          {"designated", r.designated_position ? point(*r.designated_position) : json(nullptr)},
          {"blue_on_positive_half",
           r.blue_team_on_positive_half ? json(*r.blue_team_on_positive_half) : json(nullptr)},
          {"status_message", r.status_message},
          {"yellow", team_info_json(r.yellow)},
          {"blue", team_info_json(r.blue)},
          {"keep_out", keep_out_json()}};
}

json ConsoleState::log_json() const {
  json entries = json::array();
  for (const LogEntry& entry : log_.entries()) {
    entries.push_back({{"t", entry.at.nanoseconds()},
                       {"kind", to_string(entry.kind)},
                       {"text", entry.text},
                       {"team", team_or_null(entry.team)}});
  }
  return {{"entries", std::move(entries)}};
}

json ConsoleState::health_json(time::Timestamp now) const {
  json services = json::array();
  for (const auto& [name, slot] : health_) {
    const ServiceHealth& h = slot.health;
    services.push_back({{"service", h.service},
                        {"host", h.host},
                        {"level", to_string(h.level)},
                        {"status", h.status},
                        {"rate_hz", number(h.rate_hz)},
                        {"latency_p99_ms", number(h.latency_p99 * 1e3)},
                        {"errors", h.errors},
                        {"dropped", h.dropped},
                        {"uptime_s", number(h.uptime)},
                        {"age_s", number(time::to_seconds(now - slot.at))}});
  }
  json robots = json::array();
  for (const auto& [key, slot] : feedback_) {
    const RobotFeedbackView& f = slot.feedback;
    const bool battery_low = f.battery_voltage && *f.battery_voltage < options_.battery_low_volts;
    const bool link_low = f.link_quality && *f.link_quality < options_.link_low_quality;
    robots.push_back({{"team", team_name(f.team)},
                      {"id", f.id},
                      {"battery_v", f.battery_voltage ? number(*f.battery_voltage) : json(nullptr)},
                      {"battery_low", battery_low},
                      {"link_quality", f.link_quality ? number(*f.link_quality) : json(nullptr)},
                      {"link_low", link_low},
                      {"age_s", number(time::to_seconds(now - slot.at))}});
  }
  json estop = {{"engaged", estop_ && estop_->engaged},
                {"source", estop_ ? estop_->source : ""},
                {"reason", estop_ ? estop_->reason : ""}};
  return {{"services", std::move(services)}, {"robots", std::move(robots)}, {"estop", std::move(estop)}};
}

json ConsoleState::report_json() const {
  const sslctl::MatchReport report = report_.report();
  std::uint32_t placements = 0;
  for (const auto& [command, count] : report.commands) {
    if (command == Command::kBallPlacementBlue || command == Command::kBallPlacementYellow) placements += count;
  }
  std::uint32_t placed = 0;
  for (const auto& event : report.events) {
    if (event.type == referee::GameEventType::kPlacementSucceeded) placed += event.count;
  }
  return {{"duration_s", number(report.duration)},
          {"score", {{"yellow", report.yellow.score}, {"blue", report.blue.score}}},
          {"fouls", {{"yellow", report.yellow.fouls}, {"blue", report.blue.fouls}}},
          {"placements", {{"tried", placements}, {"succeeded", placed}}},
          {"in_play_share", report.duration > 0 ? number(report.in_play / report.duration) : json(nullptr)},
          {"longest_stall_s", report.longest_stall ? number(report.longest_stall->seconds) : json(nullptr)}};
}

json ConsoleState::params_json() const {
  json params = json::array();
  for (const auto& [target, state] : parameters_) {
    for (const config::KeyInfo& key : state.params) {
      params.push_back({{"target", target},
                        {"key", key.key},
                        {"value", key.value},
                        {"type", key.type},
                        {"min", key.min ? json(*key.min) : json(nullptr)},
                        {"max", key.max ? json(*key.max) : json(nullptr)},
                        {"allowed", key.allowed},
                        {"unit", key.unit},
                        {"description", key.doc},
                        {"revision", state.revision},
                        {"status", state.accepted ? "ok" : "rejected"},
                        {"reason", state.reason},
                        {"saved_file", state.saved_file}});
    }
  }
  return {{"params", std::move(params)}};
}

}  // namespace ssl::console
