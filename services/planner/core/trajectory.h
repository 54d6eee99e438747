// Time-optimal "bang-bang" trajectories: under a speed limit and a symmetric acceleration limit, from any
// initial position and velocity to a target at rest. The acceleration is always +a, 0 or -a, so the speed
// over time is a trapezoid (or a triangle when the top speed is never reached), after a first braking
// phase when the robot starts too fast or moving the wrong way.
//
// Trajectory1D: one axis (or the heading, on an unwrapped angle). Trajectory2D: x and y synchronised so that
// both finish together, by sharing the limits between the axes along the direction that makes their
// durations equal (TIGERs Mannheim's method): it is time-optimal for the shared limits, and the acceleration
// vector never exceeds the 2D limit. The velocity vector neither, from rest; from a moving start an axis
// above its share of the speed limit is braked down to it while the other speeds up, so the speed may
// exceed the limit by a few per cent for a moment (tested: <= 5 %). Units: metres (or radians), seconds.
//
//   Trajectory2D path = Trajectory2D::plan(position, velocity, target, {.max_speed = 3, .max_acceleration = 3});
//   Vec2 where = path.position(0.25);   // reference position 0.25 s from now
//   double when = path.duration();      // at rest on the target
#pragma once

#include <array>
#include <cstddef>

#include "libs/geometry/vec2.h"

namespace ssl::planner {

struct TrajectoryLimits {
  double max_speed = 3.0;         // m/s (rad/s), > 0
  double max_acceleration = 3.0;  // m/s^2 (rad/s^2), > 0
};

/// One axis: at most four phases of constant acceleration.
class Trajectory1D {
 public:
  /// The time-optimal trajectory from (`x0`, `v0`) to rest at `target`. Limits must be positive; an initial
  /// speed above max_speed is first brought down at max_acceleration.
  static Trajectory1D plan(double x0, double v0, double target, const TrajectoryLimits& limits);

  double duration() const { return duration_; }
  double position(double t) const;
  double velocity(double t) const;
  double acceleration(double t) const;
  double target() const { return target_; }

 private:
  struct Phase {
    double duration = 0;  // s
    double acceleration = 0;
  };
  struct State {
    double x;
    double v;
    double a;
  };
  State at(double t) const;
  void add(double duration, double acceleration);

  double x0_ = 0;
  double v0_ = 0;
  double target_ = 0;
  std::array<Phase, 4> phases_{};
  std::size_t count_ = 0;
  double duration_ = 0;
};

class Trajectory2D {
 public:
  /// From (`p0`, `v0`) to rest at `target`, with the 2D limits shared between x and y so that both axes
  /// end together.
  static Trajectory2D plan(const geom::Vec2& p0, const geom::Vec2& v0, const geom::Vec2& target,
                           const TrajectoryLimits& limits);
  /// A lower bound (s) of plan(`p0`, `v0`, `target`, `limits`).duration(), at the cost of two 1D plans
  /// instead of plan's search for the share of the limits: each axis alone, with the whole acceleration
  /// limit and the speed limit raised to that axis' initial speed (a shared axis never exceeds either).
  static double duration_bound(const geom::Vec2& p0, const geom::Vec2& v0, const geom::Vec2& target,
                               const TrajectoryLimits& limits);

  double duration() const { return duration_; }
  geom::Vec2 position(double t) const { return {x_.position(t), y_.position(t)}; }
  geom::Vec2 velocity(double t) const { return {x_.velocity(t), y_.velocity(t)}; }
  geom::Vec2 acceleration(double t) const { return {x_.acceleration(t), y_.acceleration(t)}; }
  geom::Vec2 target() const { return {x_.target(), y_.target()}; }

 private:
  Trajectory1D x_;
  Trajectory1D y_;
  double duration_ = 0;
};

/// The heading: a 1D trajectory over the shortest way round from `heading` to `target` (rad).
Trajectory1D plan_rotation(double heading, double angular_velocity, double target, const TrajectoryLimits& limits);

}  // namespace ssl::planner
