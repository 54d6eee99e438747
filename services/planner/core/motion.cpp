#include "services/planner/core/motion.h"

#include <algorithm>
#include <cmath>

#include "libs/domain/keep_out.h"
#include "libs/geometry/angle.h"
#include "libs/geometry/project.h"
#include "libs/geometry/segment.h"
#include "libs/geometry/vec2.h"

namespace ssl::planner {
namespace {

constexpr double kDribblerRpm = 3000;
constexpr double kChipAngle = 0.6;     // rad
constexpr double kPositionGain = 3.0;  // 1/s: speed per metre of remaining distance, close to the target
constexpr double kHeadingGain = 5.0;   // 1/s
constexpr double kEscapeSpeed = 0.6;   // m/s, minimum speed out of a zone we are inside
constexpr double kRobotClearance = 0.22;  // m between two robots' centres when passing (2 radii + 0.04)
constexpr double kRobotLookAhead = 1.0;   // m along the way in which robots are gone around
constexpr int kProjectionPasses = 4;
/// How far a defense-area zone reaches behind its goal line (into the goal and up to the wall).
constexpr double kDefenseZoneBehindGoal = 1.0;  // m

/// The nearest point on `zone`'s boundary, leaving through the faces towards the field (not the goal line).
Vec2 exit_towards_field(const geom::Rectangle& zone, const Vec2& p, bool opens_towards_positive_x) {
  if (zone_exit_normal(zone, p, opens_towards_positive_x).x() != 0) {
    return {opens_towards_positive_x ? zone.max().x() : zone.min().x(), p.y()};
  }
  return {p.x(), p.y() >= 0 ? zone.max().y() : zone.min().y()};
}

Vec2 push_out_of_circle(const Vec2& p, const Vec2& center, double radius, const Vec2& fallback) {
  const Vec2 d = p - center;
  const double n = d.norm();
  if (n >= radius) return p;
  const Vec2 u = n > 1e-9 ? Vec2(d / n) : fallback;
  return center + u * radius;
}

Vec2 clamp_to_field(const Vec2& p, const MotionIntent& intent, const Zones& zones) {
  const geom::Rectangle area = allowed_area(intent, zones);
  return {std::clamp(p.x(), area.min().x(), area.max().x()), std::clamp(p.y(), area.min().y(), area.max().y())};
}

double clamp_abs(double value, double limit) { return std::clamp(value, -limit, limit); }

Vec2 limit_norm(const Vec2& v, double limit) {
  const double n = v.norm();
  return n > limit && n > 0 ? Vec2(v * (limit / n)) : v;
}

/// Direction that passes a disc (center, radius) on the side nearer to `dir`, if the way along `dir` for
/// `length` metres from `p` hits it; nullopt otherwise.
std::optional<Vec2> detour(const Vec2& p, const Vec2& dir, double length, const Vec2& center, double radius) {
  const Vec2 to_c = center - p;
  const double along = to_c.dot(dir);
  if (along <= 0 || along >= length + radius) return std::nullopt;
  const double lateral = geom::cross(dir, to_c);
  if (std::abs(lateral) >= radius) return std::nullopt;
  const double dist = to_c.norm();
  const double alpha = std::asin(std::min(1.0, radius * 1.05 / std::max(dist, 1e-9)));
  const double side = lateral >= 0 ? 1.0 : -1.0;  // centre on the left: pass on the right
  return geom::rotate(Vec2(to_c / dist), geom::Angle::from_radians(-side * alpha));
}

}  // namespace

Vec2 zone_exit_normal(const geom::Rectangle& zone, const Vec2& p, bool opens_towards_positive_x) {
  const double to_front = opens_towards_positive_x ? zone.max().x() - p.x() : p.x() - zone.min().x();
  const double to_side = zone.max().y() - std::abs(p.y());
  if (to_front <= to_side) return {opens_towards_positive_x ? 1.0 : -1.0, 0.0};
  return {0.0, p.y() >= 0 ? 1.0 : -1.0};
}

geom::Rectangle our_defense_zone(const Zones& zones) {
  return defense_area_keep_out(zones.field.size(), -1, zones.our_defense_margin, kDefenseZoneBehindGoal);
}

geom::Rectangle their_defense_zone(const Zones& zones) {
  return defense_area_keep_out(zones.field.size(), +1, zones.their_defense_margin, kDefenseZoneBehindGoal);
}

geom::Rectangle allowed_area(const MotionIntent& intent, const Zones& zones) {
  // The walls stand boundary_width beyond the touch lines and boundary_width_goal_line beyond the goal
  // lines (0.6 m in division A: a ball resting there, as it does on grSim, is fetched from there too).
  const wm::FieldSize& size = zones.field.size();
  const double hx = intent.may_enter_boundary ? size.wall_half_length() - zones.wall_margin
                                              : zones.field.half_length() + zones.field_margin;
  const double hy = intent.may_enter_boundary ? size.wall_half_width() - zones.wall_margin
                                              : zones.field.half_width() + zones.field_margin;
  return {{-hx, -hy}, {hx, hy}};
}

void set_ball_actions(const MotionIntent& intent, RobotCommand& command) {
  command.dribbler_rpm = intent.dribble ? kDribblerRpm : 0;
  command.kick = intent.kick;
  command.kick_speed = intent.kick == KickType::kNone ? 0 : intent.kick_speed;
  command.chip_angle = intent.kick == KickType::kChip ? kChipAngle : 0;
}

Vec2 project_out(const Vec2& target, const MotionIntent& intent, const Zones& zones) {
  Vec2 p = clamp_to_field(target, intent, zones);
  for (int pass = 0; pass < kProjectionPasses; ++pass) {
    const Vec2 before = p;
    if (intent.avoid_their_defense_area) {
      const geom::Rectangle zone = their_defense_zone(zones);
      if (zone.contains(p)) p = exit_towards_field(zone, p, false);
    }
    if (intent.avoid_our_defense_area) {
      const geom::Rectangle zone = our_defense_zone(zones);
      if (zone.contains(p)) p = exit_towards_field(zone, p, true);
    }
    if (intent.avoid_placement_corridor && zones.placement_corridor) {
      const geom::Segment& spine = zones.placement_corridor->spine;
      const Vec2 q = geom::project(p, spine).point;
      Vec2 side = geom::perpendicular(geom::normalized_or_zero(spine.direction()));
      if (side.squaredNorm() == 0) side = Vec2(-1, 0);
      p = push_out_of_circle(p, q, zones.placement_corridor->radius, side);
    }
    if (intent.avoid_ball_radius > 0 && zones.ball) {
      // Fallback direction: towards our goal (where defenders want to be anyway).
      p = push_out_of_circle(p, *zones.ball, intent.avoid_ball_radius, Vec2(-1, 0));
    }
    p = clamp_to_field(p, intent, zones);
    if ((p - before).squaredNorm() < 1e-12) break;
  }
  return p;
}

SimpleMotionPlanner::SimpleMotionPlanner(const MotionLimits& limits) : limits_(limits) {}

void SimpleMotionPlanner::sent(std::uint32_t id, const Vec2& velocity, double angular) {
  if (id >= memory_.size()) return;
  memory_[id] = {velocity, angular};
}

RobotCommand SimpleMotionPlanner::plan(const wm::RobotState& robot, const MotionIntent& intent,
                                       const Zones& zones, double dt) {
  RobotCommand command;
  command.id = robot.id;
  if (!intent.active || intent.halt || robot.id >= memory_.size()) {
    if (robot.id < memory_.size()) memory_[robot.id] = {};
    return command;
  }
  Memory& memory = memory_[robot.id];
  const Vec2 p = robot.position;
  const Vec2 target = project_out(intent.target, intent, zones);
  const double max_speed = std::min(intent.max_speed, limits_.max_speed);

  // Proportional approach, capped by the speed from which we can still brake before the target.
  const Vec2 delta = target - p;
  const double dist = delta.norm();
  double speed = 0;
  Vec2 dir = Vec2::Zero();
  if (dist > 0.005) {
    dir = delta / dist;
    speed = std::min({max_speed, std::sqrt(2 * 0.8 * limits_.max_acceleration * dist), kPositionGain * dist});
  }

  // Zones we are inside: leave them the shortest way, keeping the part of the wish that does not go deeper.
  Vec2 escape = Vec2::Zero();
  const auto leave_disc = [&](const Vec2& center, double radius) {
    const Vec2 d = p - center;
    const double n = d.norm();
    if (n >= radius) return;
    escape += n > 1e-9 ? Vec2(d / n) : Vec2(-1, 0);
  };
  if (intent.avoid_ball_radius > 0 && zones.ball) leave_disc(*zones.ball, intent.avoid_ball_radius);
  std::optional<geom::Stadium> corridor;
  if (intent.avoid_placement_corridor && zones.placement_corridor) {
    corridor = zones.placement_corridor;
    leave_disc(geom::project(p, corridor->spine).point, corridor->radius);
  }
  const auto leave_box = [&](const geom::Rectangle& zone, bool towards_positive_x) {
    if (!zone.contains(p)) return;
    escape += geom::normalized_or_zero(exit_towards_field(zone, p, towards_positive_x) - p);
  };
  const geom::Rectangle their = their_defense_zone(zones);
  const geom::Rectangle ours = our_defense_zone(zones);
  if (intent.avoid_their_defense_area) leave_box(their, false);
  if (intent.avoid_our_defense_area) leave_box(ours, true);

  Vec2 velocity;
  if (escape.squaredNorm() > 0) {
    const Vec2 out = geom::normalized_or_zero(escape);
    const Vec2 tangential = dir - dir.dot(out) * out;
    velocity = out * std::min(max_speed, std::max(kEscapeSpeed, speed)) + tangential * speed * 0.5;
  } else {
    // Outside every zone: go around the ones on the way (discs: the ball, the corridor's nearest point;
    // boxes: through the nearer front corner).
    if (speed > 0) {
      // Other robots first: pass the nearest one on the way within kRobotLookAhead (planner I's local
      // detour; planner II plans around all of them); the rule zones below then correct that direction. A
      // robot standing on our target is not gone around.
      std::optional<Vec2> around_robot;
      double nearest = kRobotLookAhead;
      for (const ZoneRobot& zone_robot : zones.robots) {
        const Vec2& other = zone_robot.position;
        const double distance = (other - p).norm();
        if (distance < 1e-3 || distance >= nearest || (other - target).norm() < kRobotClearance) continue;
        if (auto d = detour(p, dir, std::min(dist, kRobotLookAhead), other, kRobotClearance)) {
          around_robot = d;
          nearest = distance;
        }
      }
      if (around_robot) dir = *around_robot;
      if (intent.avoid_ball_radius > 0 && zones.ball) {
        if (auto d = detour(p, dir, dist, *zones.ball, intent.avoid_ball_radius)) dir = *d;
      }
      if (corridor) {
        const Vec2 q = geom::project(p + dir * std::min(dist, 0.5), corridor->spine).point;
        if (auto d = detour(p, dir, dist, q, corridor->radius)) dir = *d;
      }
      const auto around_box = [&](const geom::Rectangle& zone, bool towards_positive_x) {
        bool hit = false;
        for (int i = 1; i <= 8 && !hit; ++i) hit = zone.contains(p + dir * (dist * i / 8.0));
        if (!hit) return;
        const double x = towards_positive_x ? zone.max().x() + 0.05 : zone.min().x() - 0.05;
        const Vec2 corners[2] = {{x, zone.max().y() + 0.05}, {x, zone.min().y() - 0.05}};
        const auto cost = [&](const Vec2& c) { return (c - p).norm() + (target - c).norm(); };
        const Vec2 corner = cost(corners[0]) <= cost(corners[1]) ? corners[0] : corners[1];
        dir = geom::normalized_or_zero(corner - p);
      };
      if (intent.avoid_their_defense_area) around_box(their, false);
      if (intent.avoid_our_defense_area) around_box(ours, true);
    }
    velocity = dir * speed;
  }
  velocity = limit_norm(velocity, max_speed);

  // Acceleration limit, from what was sent last.
  velocity = memory.velocity + limit_norm(velocity - memory.velocity, limits_.max_acceleration * dt);

  const double heading_error =
      (geom::Angle::from_radians(intent.orientation) - geom::Angle::from_radians(robot.orientation))
          .radians();
  double angular =
      clamp_abs(kHeadingGain * heading_error,
                std::min(limits_.angular_speed_at(std::max(velocity.norm(), robot.velocity.norm())),
                         intent.max_angular_speed));
  angular = memory.angular + clamp_abs(angular - memory.angular, limits_.max_angular_acceleration * dt);
  memory = {velocity, angular};

  command = to_local(robot.id, velocity, angular, robot.orientation);
  set_ball_actions(intent, command);
  return command;
}

RobotCommand to_local(std::uint32_t id, const Vec2& velocity, double angular, double heading) {
  RobotCommand command;
  command.id = id;
  const double c = std::cos(heading);
  const double s = std::sin(heading);
  command.forward = c * velocity.x() + s * velocity.y();
  command.left = -s * velocity.x() + c * velocity.y();
  command.angular = angular;
  return command;
}

Vec2 to_team(const RobotCommand& command, double heading) {
  const double c = std::cos(heading);
  const double s = std::sin(heading);
  return {c * command.forward - s * command.left, s * command.forward + c * command.left};
}

}  // namespace ssl::planner
