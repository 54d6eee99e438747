#include "services/console/adapter/convert.h"

#include "proto/ssl_simulation_control.pb.h"

namespace ssl::console {
namespace {

geom::Vec2 vec(const idl::common::Vec2& v) { return {v.x(), v.y()}; }

RobotView robot(const idl::world::RobotState& in, TeamColor team) {
  return {.team = team,
          .id = in.id(),
          .position = {in.pose().x(), in.pose().y()},
          .heading = in.pose().theta(),
          .velocity = vec(in.velocity()),
          .visible = in.visible()};
}

std::optional<TeamColor> team_color(idl::common::TeamColor team) {
  if (team == idl::common::TEAM_COLOR_BLUE) return TeamColor::kBlue;
  if (team == idl::common::TEAM_COLOR_YELLOW) return TeamColor::kYellow;
  return std::nullopt;
}

NodeStatus node_status(idl::planner::NodeStatus status) {
  switch (status) {
    case idl::planner::NODE_STATUS_RUNNING: return NodeStatus::kRunning;
    case idl::planner::NODE_STATUS_SUCCESS: return NodeStatus::kSuccess;
    case idl::planner::NODE_STATUS_FAILURE: return NodeStatus::kFailure;
    default: return NodeStatus::kIdle;
  }
}

}  // namespace

CameraView from_idl(const idl::vision::DetectionFrame& frame) {
  CameraView out{.camera_id = frame.camera_id()};
  for (const auto& ball : frame.balls()) out.balls.emplace_back(ball.x(), ball.y());
  for (const auto& [team, robots] : {std::pair{TeamColor::kYellow, &frame.robots_yellow()},
                                     std::pair{TeamColor::kBlue, &frame.robots_blue()}}) {
    for (const auto& r : *robots) {
      out.robots.push_back({.team = team,
                            .id = r.robot_id(),
                            .position = {r.x(), r.y()},
                            .heading = r.has_orientation() ? r.orientation() : 0.0});
    }
  }
  return out;
}

TeamWorld from_idl(const idl::world::WorldState& world) {
  TeamWorld out{.flipped = world.flipped()};
  const TeamColor us = team_color(world.team()).value_or(TeamColor::kBlue);
  if (world.has_ball()) {
    const auto& ball = world.ball();
    out.ball = BallView{.position = {ball.position().x(), ball.position().y()},
                        .height = ball.position().z(),
                        .velocity = {ball.velocity().x(), ball.velocity().y()},
                        .visible = ball.visible()};
  }
  for (const auto& r : world.friendly()) out.robots.push_back(robot(r, us));
  for (const auto& r : world.enemy()) out.robots.push_back(robot(r, opponent(us)));
  switch (world.possession()) {
    case idl::world::POSSESSION_FRIENDLY: out.possession = Possession::kOurs; break;
    case idl::world::POSSESSION_ENEMY: out.possession = Possession::kTheirs; break;
    case idl::world::POSSESSION_CONTESTED: out.possession = Possession::kContested; break;
    default: out.possession = Possession::kNone; break;
  }
  return out;
}

TeamDebug from_idl(const idl::planner::PlannerDebug& debug) {
  TeamDebug out{.play = debug.play(), .tactic = debug.game_tactic(), .tick_duration = debug.tick_duration()};
  for (const auto& role : debug.roles()) out.roles.push_back({role.robot_id(), role.role(), role.tactic(), role.skill()});
  for (const auto& node : debug.tree()) out.tree.push_back({node.name(), node.depth(), node_status(node.status())});
  for (const auto& path : debug.paths()) {
    PathView view{.id = path.robot_id(), .destination = vec(path.destination())};
    for (const auto& point : path.points()) view.points.push_back(vec(point));
    out.paths.push_back(std::move(view));
  }
  return out;
}

ServiceHealth from_idl(const idl::system::Health& health) {
  HealthLevel level = HealthLevel::kOk;
  if (health.level() == idl::system::HEALTH_WARN) level = HealthLevel::kWarn;
  if (health.level() == idl::system::HEALTH_ERROR) level = HealthLevel::kError;
  return {.service = health.service(),
          .host = health.host(),
          .level = level,
          .status = health.status(),
          .rate_hz = health.rate_hz(),
          .latency_p99 = health.latency_p99(),
          .errors = health.errors(),
          .dropped = health.dropped(),
          .uptime = static_cast<double>(health.uptime_ns()) * 1e-9};
}

RobotFeedbackView from_idl(const idl::robot::RobotFeedback& feedback, TeamColor team) {
  RobotFeedbackView out{.team = team, .id = feedback.robot_id()};
  if (feedback.has_battery()) out.battery_voltage = feedback.battery_voltage();
  if (feedback.has_link_quality()) out.link_quality = feedback.link_quality();
  return out;
}

EstopView from_idl(const idl::system::Estop& estop) {
  return {.engaged = estop.engaged(), .source = estop.source(), .reason = estop.reason()};
}

ParameterStateView from_idl(const idl::system::ParameterState& state) {
  ParameterStateView out{.target = state.target(),
                         .revision = state.revision(),
                         .accepted = state.accepted(),
                         .reason = state.reason(),
                         .saved_file = state.saved_file()};
  for (const auto& p : state.params()) {
    config::KeyInfo key{.key = p.key(), .type = p.type(), .value = p.value(), .allowed = p.allowed(),
                        .unit = p.unit(), .doc = p.description()};
    if (p.has_min()) key.min = p.min();
    if (p.has_max()) key.max = p.max();
    out.params.push_back(std::move(key));
  }
  return out;
}

idl::system::ParameterSet to_idl(const ParamAction& action, std::uint64_t revision, const std::string& author,
                                 std::int64_t stamp_unix_ns) {
  idl::system::ParameterSet out;
  out.target(action.target);
  out.revision(revision);
  idl::system::Parameter value;
  value.key(action.key);
  value.value(action.value);
  out.values({value});
  out.save(false);
  out.author(author);
  out.stamp_unix_ns(stamp_unix_ns);
  return out;
}

idl::system::ParameterSet save_request(const ParamSaveAction& action, std::uint64_t revision,
                                       const std::string& author, std::int64_t stamp_unix_ns) {
  idl::system::ParameterSet out;
  out.target(action.target);
  out.revision(revision);
  out.save(true);
  out.author(author);
  out.stamp_unix_ns(stamp_unix_ns);
  return out;
}

idl::referee::RefereeOperatorCommand to_idl(const RefereeAction& action, const std::string& author,
                                            std::int64_t stamp_unix_ns) {
  idl::referee::RefereeOperatorCommand out;
  out.command(static_cast<idl::referee::Command>(static_cast<int>(action.command)));
  out.has_designated_position(action.designated.has_value());
  if (action.designated) {
    idl::common::Vec2 point;
    point.x(action.designated->x());
    point.y(action.designated->y());
    out.designated_position(point);
  }
  out.author(author);
  out.stamp_unix_ns(stamp_unix_ns);
  return out;
}

idl::system::Estop to_idl(const EstopAction& action, const std::string& source, std::int64_t stamp_unix_ns) {
  idl::system::Estop out;
  out.engaged(action.engaged);
  out.source(source);
  out.reason(action.reason);
  out.stamp_unix_ns(stamp_unix_ns);
  return out;
}

std::string simulator_command(const PlaceAction& action, double heading) {
  ::SimulatorCommand command;
  ::SimulatorControl* control = command.mutable_control();
  if (action.object == PlaceObject::kBall) {
    ::TeleportBall* ball = control->mutable_teleport_ball();
    ball->set_x(static_cast<float>(action.position.x()));
    ball->set_y(static_cast<float>(action.position.y()));
    ball->set_z(0);
    ball->set_vx(0);
    ball->set_vy(0);
    ball->set_vz(0);
    ball->set_teleport_safely(true);  // robots touching the new place are moved off it
  } else {
    ::TeleportRobot* robot = control->add_teleport_robot();
    robot->mutable_id()->set_id(action.id);
    robot->mutable_id()->set_team(action.team == TeamColor::kBlue ? ::BLUE : ::YELLOW);
    robot->set_x(static_cast<float>(action.position.x()));
    robot->set_y(static_cast<float>(action.position.y()));
    robot->set_orientation(static_cast<float>(heading));
    robot->set_v_x(0);
    robot->set_v_y(0);
    robot->set_v_angular(0);
    robot->set_present(true);
  }
  std::string bytes;
  command.SerializeToString(&bytes);
  return bytes;
}

}  // namespace ssl::console
