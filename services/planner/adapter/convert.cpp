#include "services/planner/adapter/convert.h"

#include <cmath>
#include <string>

namespace ssl::planner {
namespace {

time::Timestamp ts(std::int64_t unix_ns) { return time::Timestamp::from_nanoseconds(unix_ns); }

bool finite(std::initializer_list<double> values) {
  for (const double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

Error not_finite(const std::string& what) { return Error{what + " is not a finite number"}; }

Result<std::vector<wm::RobotState>> robots_from_idl(const std::vector<idl::world::RobotState>& in,
                                                    const char* side) {
  std::vector<wm::RobotState> out;
  out.reserve(in.size());
  for (const auto& r : in) {
    const std::string name = std::string("world.state ") + side + " robot " + std::to_string(r.id());
    if (r.id() >= wm::kMaxRobotsPerTeam) {
      return Error{std::string("world.state ") + side + " robot id " + std::to_string(r.id()) +
                   " is out of range 0.." + std::to_string(wm::kMaxRobotsPerTeam - 1)};
    }
    if (!finite({r.pose().x(), r.pose().y(), r.pose().theta()})) return not_finite(name + " pose");
    if (!finite({r.velocity().x(), r.velocity().y(), r.angular_velocity()})) return not_finite(name + " velocity");
    if (!std::isfinite(r.confidence())) return not_finite(name + " confidence");
    out.push_back({.id = r.id(),
                   .position = wm::Vec2(r.pose().x(), r.pose().y()),
                   .orientation = r.pose().theta(),
                   .velocity = wm::Vec2(r.velocity().x(), r.velocity().y()),
                   .angular_velocity = r.angular_velocity(),
                   .visible = r.visible(),
                   .confidence = r.confidence()});
  }
  return out;
}

std::optional<TeamColor> team_from_idl(idl::common::TeamColor team) {
  switch (team) {
    case idl::common::TEAM_COLOR_BLUE: return TeamColor::kBlue;
    case idl::common::TEAM_COLOR_YELLOW: return TeamColor::kYellow;
    default: return std::nullopt;
  }
}


}  // namespace

Result<wm::WorldState> from_idl(const idl::world::WorldState& in) {
  wm::WorldState out;
  const auto team = team_from_idl(in.team());
  if (!team) return Error{"world.state team is neither blue nor yellow"};
  out.team = *team;
  out.flipped = in.flipped();
  out.stamp.capture_time = ts(in.stamp().capture_unix_ns());
  out.stamp.receive_time = ts(in.stamp().receive_unix_ns());
  out.stamp.camera_id = in.stamp().camera_id();
  out.stamp.frame_number = in.stamp().frame_number();
  out.predicted_to = ts(in.publish_unix_ns());
  out.has_ball = in.has_ball();
  if (in.has_ball()) {
    const auto& b = in.ball();
    if (!finite({b.position().x(), b.position().y(), b.position().z()})) return not_finite("world.state ball position");
    if (!finite({b.velocity().x(), b.velocity().y(), b.velocity().z()})) return not_finite("world.state ball velocity");
    if (!std::isfinite(b.confidence())) return not_finite("world.state ball confidence");
    out.ball.position = wm::Vec3(b.position().x(), b.position().y(), b.position().z());
    out.ball.velocity = wm::Vec3(b.velocity().x(), b.velocity().y(), b.velocity().z());
    out.ball.visible = b.visible();
    out.ball.confidence = b.confidence();
    out.ball.last_seen = ts(b.last_seen_unix_ns());
    out.ball.airborne = b.airborne();
    out.ball.in_dribbler = b.in_dribbler();
  }
  auto friendly = robots_from_idl(in.friendly(), "friendly");
  if (!friendly) return friendly.error();
  out.friendly = std::move(*friendly);
  auto enemy = robots_from_idl(in.enemy(), "enemy");
  if (!enemy) return enemy.error();
  out.enemy = std::move(*enemy);
  switch (in.possession()) {
    case idl::world::POSSESSION_NONE: out.possession = wm::Possession::kNone; break;
    case idl::world::POSSESSION_FRIENDLY: out.possession = wm::Possession::kFriendly; break;
    case idl::world::POSSESSION_ENEMY: out.possession = wm::Possession::kEnemy; break;
    case idl::world::POSSESSION_CONTESTED: out.possession = wm::Possession::kContested; break;
    default: return Error{"world.state possession has an unknown value " + std::to_string(in.possession())};
  }
  if (in.has_possessing_robot()) {
    if (in.possessing_robot() >= wm::kMaxRobotsPerTeam) {
      return Error{"world.state possessing_robot " + std::to_string(in.possessing_robot()) + " is out of range"};
    }
    out.possessing_robot = in.possessing_robot();
  }
  if (in.has_command_delay()) {
    if (!std::isfinite(in.command_delay()) || in.command_delay() < 0 || in.command_delay() > 1) {
      return Error{"world.state command_delay " + std::to_string(in.command_delay()) + " is not in [0, 1] s"};
    }
    out.command_delay = in.command_delay();
  }
  return out;
}

Result<wm::RefereeInfo> from_idl(const idl::referee::RefereeState& in) {
  Result<wm::RefereeInfo> info = referee_info_from_idl(in);
  if (info) info->blue_team_on_positive_half.reset();
  return info;
}

Result<wm::FieldSize> from_idl(const idl::vision::Geometry& in) { return field_from_idl(in); }

idl::common::TeamColor to_idl(TeamColor team) {
  return team == TeamColor::kBlue ? idl::common::TEAM_COLOR_BLUE : idl::common::TEAM_COLOR_YELLOW;
}

idl::robot::KickType to_idl(KickType kick) {
  switch (kick) {
    case KickType::kFlat: return idl::robot::KICK_FLAT;
    case KickType::kChip: return idl::robot::KICK_CHIP;
    case KickType::kNone: break;
  }
  return idl::robot::KICK_NONE;
}

idl::robot::RobotCommand to_idl(const RobotCommand& in, std::uint64_t* non_finite) {
  idl::robot::RobotCommand out;
  out.id(in.id);
  if (!finite({in.forward, in.left, in.angular, in.kick_speed, in.chip_angle, in.dribbler_rpm})) {
    if (non_finite != nullptr) ++*non_finite;
    out.kick(idl::robot::KICK_NONE);
    return out;  // every number 0: a full stop
  }
  out.forward(in.forward);
  out.left(in.left);
  out.angular(in.angular);
  out.kick(to_idl(in.kick));
  out.kick_speed(in.kick_speed);
  out.chip_angle(in.chip_angle);
  out.dribbler_rpm(in.dribbler_rpm);
  return out;
}

idl::robot::RobotCommands to_idl(const std::vector<RobotCommand>& commands, TeamColor team,
                                 const idl::common::VisionStamp& stamp, std::uint64_t sequence_number,
                                 std::int64_t publish_unix_ns, std::uint64_t* non_finite) {
  idl::robot::RobotCommands out;
  out.team(to_idl(team));
  out.sequence_number(sequence_number);
  out.stamp(stamp);
  out.publish_unix_ns(publish_unix_ns);
  out.commands().reserve(commands.size());
  for (const RobotCommand& c : commands) out.commands().push_back(to_idl(c, non_finite));
  return out;
}

idl::planner::PlannerDebug to_idl(const PlannerOutput& in, TeamColor team, const idl::common::VisionStamp& stamp,
                                  double tick_duration) {
  idl::planner::PlannerDebug out;
  out.team(to_idl(team));
  out.tick(in.tick);
  out.stamp(stamp);
  out.play(in.play);
  out.game_tactic(in.game_tactic);
  out.roles().reserve(in.roles.size());
  out.paths().reserve(in.roles.size());
  for (const RoleInfo& r : in.roles) {
    idl::planner::RoleAssignment role;
    role.robot_id(r.robot_id);
    role.role(r.role);
    role.tactic(r.tactic);
    role.skill(r.skill);
    out.roles().push_back(std::move(role));
    if (std::isfinite(r.target.x()) && std::isfinite(r.target.y())) {
      idl::planner::PlannedPath path;
      path.robot_id(r.robot_id);
      path.destination().x(r.target.x());
      path.destination().y(r.target.y());
      for (const Vec2& p : r.path) {
        if (!std::isfinite(p.x()) || !std::isfinite(p.y())) continue;
        idl::common::Vec2 point;
        point.x(p.x());
        point.y(p.y());
        path.points().push_back(point);
      }
      path.has_tracking_error(r.tracking_error.has_value());
      path.tracking_error(r.tracking_error.value_or(0.0));
      out.paths().push_back(std::move(path));
    }
  }
  out.tree().reserve(in.tree.size());
  for (const TreeNodeInfo& n : in.tree) {
    idl::planner::TreeNode node;
    node.name(n.name);
    node.depth(n.depth);
    switch (n.status) {
      case TreeNodeInfo::Status::kIdle: node.status(idl::planner::NODE_STATUS_IDLE); break;
      case TreeNodeInfo::Status::kRunning: node.status(idl::planner::NODE_STATUS_RUNNING); break;
      case TreeNodeInfo::Status::kSuccess: node.status(idl::planner::NODE_STATUS_SUCCESS); break;
      case TreeNodeInfo::Status::kFailure: node.status(idl::planner::NODE_STATUS_FAILURE); break;
    }
    out.tree().push_back(std::move(node));
  }
  out.tick_duration(tick_duration);
  return out;
}

}  // namespace ssl::planner
