#include "services/planner/core/trajectory.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ssl::planner {
namespace {

double sign_of(double value) { return value < 0 ? -1.0 : 1.0; }

/// Bisection steps on the share of the limits between x and y (each halves the remaining angle range).
constexpr int kSyncIterations = 30;
/// The first bracket around the guessed share of the limits (rad), doubled until it holds the answer.
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
  const auto share = [&](double angle, Trajectory1D& x, Trajectory1D& y) {
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    x = Trajectory1D::plan(p0.x(), v0.x(), target.x(),
                           {.max_speed = limits.max_speed * c, .max_acceleration = limits.max_acceleration * c});
    y = Trajectory1D::plan(p0.y(), v0.y(), target.y(),
                           {.max_speed = limits.max_speed * s, .max_acceleration = limits.max_acceleration * s});
  };
  // x's duration grows with the angle (its share shrinks), y's falls: find where they are equal. From rest
  // the answer is the direction to the target; moving, it is near it: bracket around it, then bisect.
  constexpr double kMin = 1e-6;
  constexpr double kMax = 0.5 * std::numbers::pi - 1e-6;
  Trajectory2D out;
  const auto difference = [&](double angle) {
    share(angle, out.x_, out.y_);
    return out.x_.duration() - out.y_.duration();
  };
  const geom::Vec2 distance = (target - p0).cwiseAbs();
  const double guess = std::clamp(std::atan2(distance.y(), distance.x()), kMin, kMax);
  const double at_guess = difference(guess);
  if (std::abs(at_guess) >= kSyncTolerance) {
    double low = guess;
    double high = guess;
    double width = kBracketStep;
    if (at_guess > 0) {  // x too slow: give it more (a smaller angle)
      do {
        high = low;
        low = std::max(kMin, guess - width);
        width *= 2;
      } while (low > kMin && difference(low) > 0);
    } else {
      do {
        low = high;
        high = std::min(kMax, guess + width);
        width *= 2;
      } while (high < kMax && difference(high) < 0);
    }
    for (int i = 0; i < kSyncIterations; ++i) {
      const double mid = 0.5 * (low + high);
      const double at_mid = difference(mid);
      if (std::abs(at_mid) < kSyncTolerance) break;
      (at_mid > 0 ? high : low) = mid;
    }
  }
  out.duration_ = std::max(out.x_.duration(), out.y_.duration());
  return out;
}

Trajectory1D plan_rotation(double heading, double angular_velocity, double target, const TrajectoryLimits& limits) {
  const double turn = std::remainder(target - heading, 2 * std::numbers::pi);  // in [-pi, pi]
  return Trajectory1D::plan(heading, angular_velocity, heading + turn, limits);
}

}  // namespace ssl::planner
