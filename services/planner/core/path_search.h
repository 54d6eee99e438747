// Path search for one robot among obstacles, on time-optimal trajectories (trajectory.h).
//
// Candidates: the direct trajectory to the destination, and for each sub-destination sampled around the
// robot and around the destination (directions x radii) the trajectory towards it, left at one of a few switch times for a trajectory
// from that state on to the destination. The best path of the last tick is a candidate too (re-planned from
// the current state through the same sub-destination), so plans do not flicker. Each candidate is swept
// in fixed time steps against every obstacle: between two steps the robot's move relative to a (moving)
// obstacle is a segment, so a fast robot cannot jump over one. Score = arrival time, plus, when the path
// collides, a penalty that is larger the sooner the first collision comes (see PathSearchParams). A static
// zone the robot stands in at the start counts only once the path has left it (leaving it is always
// allowed); a robot obstacle whose radius the robot starts inside must not be come any closer to.
// The sampled candidates are tried in the order of a lower bound of their arrival time, known before their
// second trajectory is planned; one that cannot beat the best so far is neither planned in full nor swept.
// Of equal scores the candidate generated first wins, so the order of trial does not change the result.
//
// Everything is in one frame (the planner's team frame), metres and seconds from now. Pure: no clocks.
//
//   PathObstacles obstacles;
//   obstacles.circles.push_back({.position = enemy.position, .velocity = enemy.velocity, .radius = 0.2});
//   PathResult path = search_path(robot.position, robot.velocity, target, limits, obstacles);
//   Vec2 reference = path.path.position(0.05);
#pragma once

#include <algorithm>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "libs/geometry/rectangle.h"
#include "libs/geometry/stadium.h"
#include "libs/geometry/vec2.h"
#include "services/planner/core/trajectory.h"

namespace ssl::planner {

/// A trajectory, optionally left at `switch_time` for a second one that starts from its state then.
class TrajectoryPath {
 public:
  TrajectoryPath() = default;
  explicit TrajectoryPath(const Trajectory2D& direct) : first_(direct) {}
  TrajectoryPath(const Trajectory2D& first, double switch_time, const Trajectory2D& second)
      : first_(first), second_(second), switch_time_(switch_time) {}

  double duration() const { return second_ ? switch_time_ + second_->duration() : first_.duration(); }
  geom::Vec2 position(double t) const;
  geom::Vec2 velocity(double t) const;
  geom::Vec2 destination() const { return second_ ? second_->target() : first_.target(); }
  /// The sub-destination the first trajectory heads for (the destination for a direct path).
  geom::Vec2 via() const { return first_.target(); }
  bool is_direct() const { return !second_.has_value(); }
  /// s from the start at which the second trajectory takes over (0 for a direct path).
  double switch_time() const { return switch_time_; }

 private:
  Trajectory2D first_;
  std::optional<Trajectory2D> second_;
  double switch_time_ = 0;
};

/// A disc moving at constant velocity for `moving_for` s, then standing (a robot; `radius`: the sum of both
/// robots' radii plus any margin). A measured velocity says little about where a robot is seconds later.
struct MovingCircle {
  geom::Vec2 position = geom::Vec2::Zero();
  geom::Vec2 velocity = geom::Vec2::Zero();
  double radius = 0;
  double moving_for = std::numeric_limits<double>::infinity();  // s

  geom::Vec2 position_at(double t) const { return position + velocity * std::min(t, moving_for); }
};

/// Where a path obstacle is every `step` s from now, and the box around those points: sampled once by a
/// caller whose searches share the obstacle (all robots of a tick), instead of once per search.
struct PathSamples {
  double step = 0;                   // s
  std::vector<geom::Vec2> positions;  // [k]: at k * step
  geom::Vec2 low = geom::Vec2::Zero();
  geom::Vec2 high = geom::Vec2::Zero();
};

/// A disc following a planned path (one of our robots: planned earlier this tick, or last tick).
struct PathCircle {
  TrajectoryPath path;
  double radius = 0;
  double elapsed = 0;  // s of the path already driven now (a path planned last tick: one tick)
  std::shared_ptr<const PathSamples> samples;  // optional: this path sampled (see sample_path)

  geom::Vec2 position(double t) const { return path.position(t + elapsed); }
};

/// `circle`'s positions every `step` s over `horizon` s (the sweep's grid).
std::shared_ptr<const PathSamples> sample_path(const PathCircle& circle, double step, double horizon);

struct PathObstacles {
  std::vector<MovingCircle> circles;
  std::vector<PathCircle> paths;
  std::vector<geom::Rectangle> rectangles;  // static: defense areas, goals
  std::vector<geom::Stadium> stadiums;      // static: the placement corridor, a ball keep-out
  std::optional<geom::Rectangle> bounds;    // where the centre must stay (field or walls minus margin)
};

struct PathSearchParams {
  int directions = 16;                              // sub-destinations on each ring
  double direction_offset = 0;                      // rad, where on each ring the first one lies
  std::vector<double> radii = {0.5, 1.0, 2.0};  // m, rings around the robot
  // m, rings around the destination (half as many directions): the way in to a destination close to
  // obstacles (the placer getting behind a ball in a corner, next to a robot) is rarely on a ring around
  // the robot.
  std::vector<double> destination_radii = {0.4};
  std::vector<double> switch_times = {0.2, 0.5};    // s along the first trajectory
  // s: switches further out, tried only when every path above collides: the way round a wide obstacle
  // beside another (the centre circle at their kickoff, a robot above it) leaves the sub-destination late.
  // Not among the first tries: a late switch also wins where a nearer one is free and nearly as quick,
  // and changes what the robot does there.
  std::vector<double> late_switch_times = {1.0};
  double step = 0.1;  // s between collision checks (swept chords; obstacles grown by a * step^2 / 8 to cover the curve)
  double horizon = 3.0;                             // s: collisions later than this are not looked for
  // A colliding path's score grows by collision_penalty, plus early_collision_weight per second by which
  // its first collision comes sooner than near_collision. A near collision is certain and is avoided at
  // almost any price; a far one may well not happen (the obstacle moves, the next ticks re-plan, and the
  // sub-destinations near the robot cannot go round it yet), so among those the quickest path wins rather
  // than one that only puts the collision off.
  double collision_penalty = 1.0;       // s
  double near_collision = 1.0;          // s
  double early_collision_weight = 5.0;  // s per s
  double keep_previous_margin = 0.1;                // s another path must win by to replace last tick's
  // s: sub-destinations are sampled only when the best of the direct and the previous path collides sooner
  // than this (a caller re-planning every tick may leave a far collision to its next tick).
  double sample_below = std::numeric_limits<double>::infinity();
};

struct PathResult {
  TrajectoryPath path;
  double score = 0;                               // s (arrival time, plus the penalties)
  std::optional<double> first_collision;          // s from now; nullopt: collision-free over the horizon
  int candidates = 0;                             // paths generated (bounded; planned and swept if they may win)
};

/// The first time (s) `path` comes inside an obstacle grown by `margin` (m) within `horizon`, swept in
/// `step`s; nullopt if never.
std::optional<double> first_collision(const TrajectoryPath& path, const PathObstacles& obstacles, double step,
                                      double horizon, double margin = 0);

/// The best path from (`position`, `velocity`) to rest at `destination`. `previous`: the choice of an
/// earlier tick, `previous_age` s ago: it is tried again as it goes on from now (through the same
/// sub-destination, switching when it would have), not started afresh, so it cannot pull the robot
/// towards its sub-destination for ever.
PathResult search_path(const geom::Vec2& position, const geom::Vec2& velocity, const geom::Vec2& destination,
                       const TrajectoryLimits& limits, const PathObstacles& obstacles,
                       const PathSearchParams& params = {}, const TrajectoryPath* previous = nullptr,
                       double previous_age = 0);

}  // namespace ssl::planner
