#include "services/planner/core/trajectory.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ssl::planner {
namespace {

double sign_of(double value) { return value < 0 ? -1.0 : 1.0; }

/// Bisection steps on the share of the limits between x and y (each halves the remaining angle range).
constexpr int kSyncIterations = 30;
/// The first bracket around the guessed share of the limits, doubled until it holds the answer.
constexpr double kBracketStep = 0.05;
/// Durations closer than this (s) count as synchronised.
constexpr double kSyncTolerance = 1e-3;

}  // namespace

void Trajectory1D::add(double duration, double acceleration) {
  if (!(duration > 0)) return;
  phases_[count_++] = {duration, acceleration};
  duration_ += duration;
}

Trajectory1D Trajectory1D::plan(double x0, double v0, double target, const TrajectoryLimits& limits) {
  Trajectory1D out;
  out.x0_ = x0;
  out.v0_ = v0;
  out.target_ = target;
  const double a = limits.max_acceleration;
  const double v_max = limits.max_speed;
  double x = x0;
  double v = v0;

  // Moving away from the target, or too fast to stop before it: brake to rest first (an overshoot).
  const double to_target = target - x;
  const double stopping = v * std::abs(v) / (2 * a);  // signed, at full braking
  if (v != 0 && (to_target * v < 0 || std::abs(stopping) > std::abs(to_target))) {
    out.add(std::abs(v) / a, -sign_of(v) * a);
    x += stopping;
    v = 0;
  }

  // Now at rest or moving towards the target, able to stop before it.
  double distance = std::abs(target - x);
  if (distance == 0 && v == 0) return out;
  const double direction = v != 0 ? sign_of(v) : sign_of(target - x);
  double speed = std::abs(v);
  if (speed > v_max) {  // down to the limit first
    out.add((speed - v_max) / a, -direction * a);
    distance -= (speed * speed - v_max * v_max) / (2 * a);
    speed = v_max;
  }
  distance = std::max(distance, 0.0);
  const double peak = std::sqrt(a * distance + 0.5 * speed * speed);  // triangle: accelerate, then brake
  if (peak <= v_max) {
    out.add((peak - speed) / a, direction * a);
    out.add(peak / a, -direction * a);
  } else {
    const double accelerating = (v_max * v_max - speed * speed) / (2 * a);
    const double braking = v_max * v_max / (2 * a);
    out.add((v_max - speed) / a, direction * a);
    out.add(std::max(distance - accelerating - braking, 0.0) / v_max, 0.0);
    out.add(v_max / a, -direction * a);
  }
  return out;
}

Trajectory1D::State Trajectory1D::at(double t) const {
  if (!(t < duration_)) return {target_, 0.0, 0.0};
  double x = x0_;
  double v = v0_;
  t = std::max(t, 0.0);
  for (std::size_t i = 0; i < count_; ++i) {
    const Phase& phase = phases_[i];
    const double dt = std::min(t, phase.duration);
    if (t <= phase.duration) return {x + v * dt + 0.5 * phase.acceleration * dt * dt, v + phase.acceleration * dt,
                                     phase.acceleration};
    x += v * dt + 0.5 * phase.acceleration * dt * dt;
    v += phase.acceleration * dt;
    t -= dt;
  }
  return {target_, 0.0, 0.0};
}

double Trajectory1D::position(double t) const { return at(t).x; }
double Trajectory1D::velocity(double t) const { return at(t).v; }
double Trajectory1D::acceleration(double t) const { return at(t).a; }

Trajectory2D Trajectory2D::plan(const geom::Vec2& p0, const geom::Vec2& v0, const geom::Vec2& target,
                                const TrajectoryLimits& limits) {
  // The limits go to the axes as the components of a unit vector (c, s): y gets the share s, x the share
  // c = sqrt(1 - s^2). x's duration grows with s, y's falls: find where they are equal. From rest the
  // answer is the direction to the target; moving, it is near it: bracket around it, then bisect.
  constexpr double kMin = 1e-6;
  constexpr double kMax = 1 - 1e-6;
  Trajectory2D out;
  const auto difference = [&](double share) {
    const double c = std::sqrt(1 - share * share);
    out.x_ = Trajectory1D::plan(p0.x(), v0.x(), target.x(),
                                {.max_speed = limits.max_speed * c, .max_acceleration = limits.max_acceleration * c});
    out.y_ = Trajectory1D::plan(p0.y(), v0.y(), target.y(),
                                {.max_speed = limits.max_speed * share,
                                 .max_acceleration = limits.max_acceleration * share});
    return out.x_.duration() - out.y_.duration();
  };
  const geom::Vec2 distance = target - p0;
  const double length = distance.norm();
  const double guess = std::clamp(length > 0 ? std::abs(distance.y()) / length : 0.5, kMin, kMax);
  const double at_guess = difference(guess);
  if (std::abs(at_guess) >= kSyncTolerance) {
    double low = guess;
    double high = guess;
    double f_low = at_guess;
    double f_high = at_guess;
    double width = kBracketStep;
    if (at_guess > 0) {  // x too slow: give it more (a smaller share for y)
      do {
        high = low;
        f_high = f_low;
        low = std::max(kMin, guess - width);
        f_low = difference(low);
        width *= 2;
      } while (low > kMin && f_low > 0);
    } else {
      do {
        low = high;
        f_low = f_high;
        high = std::min(kMax, guess + width);
        f_high = difference(high);
        width *= 2;
      } while (high < kMax && f_high < 0);
    }
    // Regula falsi with the Illinois step (the retained end's value halved when it is kept twice), falling
    // back to bisection when the bracket does not hold a sign change (an axis that needs no time at all).
    int kept = 0;
    for (int i = 0; i < kSyncIterations; ++i) {
      const bool bracketed = f_low < 0 && f_high > 0;
      const double mid = bracketed ? (low * f_high - high * f_low) / (f_high - f_low) : 0.5 * (low + high);
      const double at_mid = difference(mid);
      if (std::abs(at_mid) < kSyncTolerance) break;
      if (at_mid > 0) {
        high = mid;
        f_high = at_mid;
        if (kept > 0) f_low *= 0.5;
        kept = kept > 0 ? kept + 1 : 1;
      } else {
        low = mid;
        f_low = at_mid;
        if (kept < 0) f_high *= 0.5;
        kept = kept < 0 ? kept - 1 : -1;
      }
    }
  }
  out.duration_ = std::max(out.x_.duration(), out.y_.duration());
  return out;
}

double Trajectory2D::duration_bound(const geom::Vec2& p0, const geom::Vec2& v0, const geom::Vec2& target,
                                    const TrajectoryLimits& limits) {
  // An axis of plan() accelerates at most at its share of the limit and never gets faster than its initial
  // speed or its share of the speed limit: it is one of the trajectories the 1D plan below is optimal among,
  // so it takes at least as long, and plan() ends with its slower axis.
  const auto axis = [&](double x0, double v, double to) {
    return Trajectory1D::plan(x0, v, to,
                              {.max_speed = std::max(limits.max_speed, std::abs(v)),
                               .max_acceleration = limits.max_acceleration})
        .duration();
  };
  return std::max(axis(p0.x(), v0.x(), target.x()), axis(p0.y(), v0.y(), target.y()));
}

Trajectory1D plan_rotation(double heading, double angular_velocity, double target, const TrajectoryLimits& limits) {
  const double turn = std::remainder(target - heading, 2 * std::numbers::pi);  // in [-pi, pi]
  return Trajectory1D::plan(heading, angular_velocity, heading + turn, limits);
}

}  // namespace ssl::planner
