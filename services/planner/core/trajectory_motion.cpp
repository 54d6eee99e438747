#include "services/planner/core/trajectory_motion.h"

#include <algorithm>
#include <numbers>


namespace ssl::planner {
namespace {

constexpr double kArrived = 0.005;              // m: closer to the target than this, at rest, is there
constexpr int kFreeTargetPasses = 3;            // moves of the target out of robots standing on it

}  // namespace

TrajectoryMotionPlanner::TrajectoryMotionPlanner(const MotionLimits& limits, const TrajectoryMotionParams& params)
    : limits_(limits), params_(params) {}

void TrajectoryMotionPlanner::sent(std::uint32_t id, const Vec2& velocity, double angular) {
  if (id >= memory_.size()) return;
  memory_[id].velocity = velocity;
  memory_[id].angular = angular;
}

void TrajectoryMotionPlanner::begin_tick() {
  ++ticks_;
  for (Memory& memory : memory_) {
    if (memory.planned_this_tick) {
      memory.previous = memory.planned ? std::optional<TrajectoryPath>(memory.planned->path) : std::nullopt;
    } else {
      memory.previous.reset();
      memory.planned.reset();
    }
    memory.planned_this_tick = false;
  }
}

TrajectoryMotionPlanner::Obstacles TrajectoryMotionPlanner::obstacles_for(const wm::RobotState& robot,
                                                                         const MotionIntent& intent,
                                                                         const Zones& zones) const {
  Obstacles out;
  PathObstacles& obstacles = out.obstacles;
  const double touching = 2 * params_.robot_radius;
  const double our_speed = memory_[robot.id].velocity.norm();
  for (const ZoneRobot& other : zones.robots) {
    if (other.ours && other.id == robot.id) continue;
    if (other.ours) {
      const Memory* planned = other.id < memory_.size() ? &memory_[other.id] : nullptr;
      if (planned && planned->planned_this_tick && planned->planned) {
        obstacles.paths.push_back({.path = planned->planned->path, .radius = touching + params_.our_margin});
        continue;
      }
      obstacles.circles.push_back(
          {.position = other.position, .velocity = other.velocity, .radius = touching + params_.our_margin});
      ++out.robots;
      continue;
    }
    obstacles.circles.push_back({.position = other.position,
                                 .velocity = other.velocity,
                                 .radius = touching + params_.their_margin +
                                           params_.their_margin_per_speed * our_speed});
    ++out.robots;
  }
  if (intent.avoid_their_defense_area) obstacles.rectangles.push_back(their_defense_zone(zones));
  if (intent.avoid_our_defense_area) obstacles.rectangles.push_back(our_defense_zone(zones));
  if (intent.avoid_placement_corridor && zones.placement_corridor) obstacles.stadiums.push_back(*zones.placement_corridor);
  if (intent.avoid_ball_radius > 0 && zones.ball) {
    obstacles.circles.push_back({.position = *zones.ball, .radius = intent.avoid_ball_radius});
  }
  obstacles.bounds = allowed_area(intent, zones);
  return out;
}

Vec2 TrajectoryMotionPlanner::free_target(const wm::RobotState& robot, Vec2 target, const Obstacles& obstacles) {
  // Where another robot stands (an opponent now, one of ours where its path ends) no path can end without a
  // contact: stop at its edge instead, on our side of it.
  for (int pass = 0; pass < kFreeTargetPasses; ++pass) {
    bool moved = false;
    const auto push_out = [&](const Vec2& center, double radius) {
      const Vec2 away = target - center;
      if (away.norm() >= radius) return;
      Vec2 direction = geom::normalized_or_zero(away);
      if (direction.squaredNorm() == 0) direction = geom::normalized_or_zero(Vec2(robot.position - center));
      if (direction.squaredNorm() == 0) direction = Vec2(-1, 0);
      target = center + direction * radius;
      moved = true;
    };
    for (std::size_t i = 0; i < obstacles.robots; ++i) {
      push_out(obstacles.obstacles.circles[i].position, obstacles.obstacles.circles[i].radius);
    }
    for (const PathCircle& other : obstacles.obstacles.paths) push_out(other.path.destination(), other.radius);
    if (!moved) break;
  }
  return target;
}

void TrajectoryMotionPlanner::describe(std::uint32_t id, double step, std::vector<Vec2>& path,
                                       std::optional<double>& tracking_error) const {
  path.clear();
  tracking_error.reset();
  if (id >= memory_.size() || !memory_[id].planned_this_tick) return;
  const Memory& memory = memory_[id];
  tracking_error = memory.tracking_error;
  if (!memory.planned) return;
  const TrajectoryPath& planned = memory.planned->path;
  for (double t = 0; t < planned.duration(); t += step) path.push_back(planned.position(t));
  path.push_back(planned.position(planned.duration()));
}

RobotCommand TrajectoryMotionPlanner::plan(const wm::RobotState& robot, const MotionIntent& intent,
                                           const Zones& zones, double dt) {
  RobotCommand command;
  command.id = robot.id;
  if (robot.id >= memory_.size()) return command;
  Memory& memory = memory_[robot.id];
  memory.planned_this_tick = true;
  memory.tracking_error.reset();
  if (memory.previous) memory.tracking_error = (memory.previous->position(dt) - robot.position).norm();
  if (!intent.active || intent.halt) {
    memory = Memory{.planned_this_tick = true};
    return command;
  }
  const TrajectoryLimits limits{.max_speed = std::min(intent.max_speed, limits_.max_speed),
                                .max_acceleration = limits_.max_acceleration};
  const Obstacles obstacles = obstacles_for(robot, intent, zones);
  const Vec2 target = free_target(robot, project_out(intent.target, intent, zones), obstacles);
  PathSearchParams search = params_.search;
  if (ticks_ % 2 == 1) search.direction_offset += std::numbers::pi / search.directions;
  // Until this command acts, the last one keeps driving the robot.
  const Vec2 start = robot.position + memory.velocity * params_.actuation_latency;
  memory.planned = search_path(start, memory.velocity, target, limits, obstacles.obstacles, search,
                               memory.previous ? &*memory.previous : nullptr);
  const TrajectoryPath& path = memory.planned->path;
  Vec2 velocity = path.velocity(dt);
  if ((target - robot.position).norm() < kArrived && velocity.norm() < 0.05) velocity = Vec2::Zero();

  const Trajectory1D turn =
      plan_rotation(robot.orientation, memory.angular, intent.orientation,
                    {.max_speed = limits_.max_angular_speed, .max_acceleration = limits_.max_angular_acceleration});
  command = to_local(robot.id, velocity, turn.velocity(dt), robot.orientation);
  set_ball_actions(intent, command);
  return command;
}

}  // namespace ssl::planner
