#include "services/world_model/adapter/convert.h"

#include <cmath>

#include "libs/domain/idl_convert.h"

namespace ssl::wm {
namespace {

time::Timestamp ts(std::int64_t unix_ns) { return time::Timestamp::from_nanoseconds(unix_ns); }

bool finite(double a, double b, double c = 0) { return std::isfinite(a) && std::isfinite(b) && std::isfinite(c); }

bool robots_from_idl(const std::vector<idl::vision::RobotDetection>& in, std::vector<RobotDetection>& out) {
  out.reserve(in.size());
  for (const auto& r : in) {
    if (!finite(r.x(), r.y(), r.has_orientation() ? r.orientation() : 0)) return false;
    out.push_back({.id = r.robot_id(), .position = Vec2(r.x(), r.y()), .orientation = r.orientation(),
                   .has_orientation = r.has_orientation(), .confidence = r.confidence()});
  }
  return true;
}

}  // namespace

std::optional<DetectionFrame> from_idl(const idl::vision::DetectionFrame& in) {
  DetectionFrame out;
  out.camera_id = in.camera_id();
  out.frame_number = in.frame_number();
  out.capture_time = ts(in.capture_unix_ns());
  out.sent_time = in.sent_unix_ns() != 0 ? ts(in.sent_unix_ns()) : out.capture_time;
  out.receive_time = ts(in.receive_unix_ns());
  out.balls.reserve(in.balls().size());
  for (const auto& b : in.balls()) {
    if (!finite(b.x(), b.y(), b.has_z() ? b.z() : 0)) return std::nullopt;
    out.balls.push_back({.position = Vec2(b.x(), b.y()), .z = b.z(), .has_z = b.has_z(),
                         .confidence = b.confidence()});
  }
  if (!robots_from_idl(in.robots_yellow(), out.robots_yellow)) return std::nullopt;
  if (!robots_from_idl(in.robots_blue(), out.robots_blue)) return std::nullopt;
  return out;
}

Result<Geometry> from_idl(const idl::vision::Geometry& in) {
  Result<FieldSize> field = field_from_idl(in);
  if (!field) return field.error();
  Geometry out;
  out.field = *field;
  for (const auto& c : in.calibrations()) {
    if (!c.has_derived_world()) continue;
    out.cameras.push_back(
        {c.camera_id(), Vec3(c.derived_world().x(), c.derived_world().y(), c.derived_world().z())});
  }
  const auto& m = in.straight_two_phase();
  if (m.present() && m.acc_slide() < 0 && m.acc_roll() < 0 && m.k_switch() > 0) {
    out.ball_model = BallModel{m.acc_slide(), m.acc_roll(), m.k_switch()};
  }
  return out;
}

Result<RefereeInfo> from_idl(const idl::referee::RefereeState& in) { return referee_info_from_idl(in); }

RobotFeedback from_idl(const idl::robot::RobotFeedback& in) {
  return {.id = in.robot_id(), .ball_in_dribbler = in.ball_in_dribbler()};
}

std::vector<RobotCommand> from_idl(const idl::robot::RobotCommands& in) {
  std::vector<RobotCommand> out;
  out.reserve(in.commands().size());
  for (const auto& c : in.commands()) {
    if (!finite(c.forward(), c.left(), c.angular())) continue;
    out.push_back({.id = c.id(), .forward = c.forward(), .left = c.left(), .angular = c.angular()});
  }
  return out;
}

idl::world::WorldState to_idl(const WorldState& in, std::uint64_t sequence_number, std::int64_t publish_unix_ns) {
  idl::world::WorldState out;
  out.team(in.team == TeamColor::kBlue ? idl::common::TEAM_COLOR_BLUE : idl::common::TEAM_COLOR_YELLOW);
  out.flipped(in.flipped);
  out.sequence_number(sequence_number);
  out.stamp().capture_unix_ns(in.stamp.capture_time.nanoseconds());
  out.stamp().receive_unix_ns(in.stamp.receive_time.nanoseconds());
  out.stamp().camera_id(in.stamp.camera_id);
  out.stamp().frame_number(in.stamp.frame_number);
  out.publish_unix_ns(publish_unix_ns);
  out.has_ball(in.has_ball);
  auto& ball = out.ball();
  ball.position().x(in.ball.position.x());
  ball.position().y(in.ball.position.y());
  ball.position().z(in.ball.position.z());
  ball.velocity().x(in.ball.velocity.x());
  ball.velocity().y(in.ball.velocity.y());
  ball.velocity().z(in.ball.velocity.z());
  ball.visible(in.ball.visible);
  ball.confidence(in.ball.confidence);
  ball.last_seen_unix_ns(in.ball.last_seen.nanoseconds());
  ball.in_dribbler(in.ball.in_dribbler);
  ball.airborne(in.ball.airborne);
  auto robots = [](const std::vector<RobotState>& from, std::vector<idl::world::RobotState>& to) {
    to.reserve(from.size());
    for (const RobotState& r : from) {
      idl::world::RobotState s;
      s.id(r.id);
      s.pose().x(r.position.x());
      s.pose().y(r.position.y());
      s.pose().theta(r.orientation);
      s.velocity().x(r.velocity.x());
      s.velocity().y(r.velocity.y());
      s.angular_velocity(r.angular_velocity);
      s.visible(r.visible);
      s.confidence(r.confidence);
      to.push_back(std::move(s));
    }
  };
  robots(in.friendly, out.friendly());
  robots(in.enemy, out.enemy());
  switch (in.possession) {
    case Possession::kNone: out.possession(idl::world::POSSESSION_NONE); break;
    case Possession::kFriendly: out.possession(idl::world::POSSESSION_FRIENDLY); break;
    case Possession::kEnemy: out.possession(idl::world::POSSESSION_ENEMY); break;
    case Possession::kContested: out.possession(idl::world::POSSESSION_CONTESTED); break;
  }
  out.has_possessing_robot(in.possessing_robot.has_value());
  out.possessing_robot(in.possessing_robot.value_or(0));
  out.has_command_delay(in.command_delay.has_value());
  out.command_delay(in.command_delay.value_or(0));
  return out;
}

}  // namespace ssl::wm
