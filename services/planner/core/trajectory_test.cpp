#include "services/planner/core/trajectory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace ssl::planner {
namespace {

constexpr TrajectoryLimits kLimits{.max_speed = 3.0, .max_acceleration = 3.0};

/// Samples `trajectory` every `step` s and checks that the position integrates the velocity and the velocity
/// the acceleration (no jumps), and that the acceleration stays within the limit.
void expect_consistent(const Trajectory1D& trajectory, double max_acceleration) {
  constexpr double kStep = 1e-3;
  for (double t = 0; t < trajectory.duration() + 0.01; t += kStep) {
    const double dx = trajectory.position(t + kStep) - trajectory.position(t);
    const double mean_v = 0.5 * (trajectory.velocity(t) + trajectory.velocity(t + kStep));
    ASSERT_NEAR(dx, mean_v * kStep, 1e-5) << "t " << t;
    ASSERT_NEAR(trajectory.velocity(t + kStep) - trajectory.velocity(t), 0, max_acceleration * kStep + 1e-9);
    ASSERT_LE(std::abs(trajectory.acceleration(t)), max_acceleration + 1e-9);
  }
}

TEST(Trajectory1D, FromRestItIsATriangleOrATrapezoid) {
  // 0.75 m: accelerate 0.5 s to 1.5 m/s, brake 0.5 s. 6 m: 1 s to 3 m/s, 1 s at 3 m/s, 1 s braking.
  const Trajectory1D triangle = Trajectory1D::plan(0, 0, 0.75, kLimits);
  EXPECT_NEAR(triangle.duration(), 1.0, 1e-12);
  EXPECT_NEAR(triangle.velocity(0.5), 1.5, 1e-12);
  const Trajectory1D trapezoid = Trajectory1D::plan(1, 0, 7, kLimits);
  EXPECT_NEAR(trapezoid.duration(), 3.0, 1e-12);
  EXPECT_NEAR(trapezoid.velocity(1.5), 3.0, 1e-12);
  EXPECT_NEAR(trapezoid.position(1.5), 1 + 1.5 + 1.5, 1e-12);
  const Trajectory1D backwards = Trajectory1D::plan(0, 0, -0.75, kLimits);
  EXPECT_NEAR(backwards.velocity(0.5), -1.5, 1e-12);
}

TEST(Trajectory1D, MovingAwayItBrakesFirstAndComesBack) {
  const Trajectory1D t = Trajectory1D::plan(0, -1.5, 1.0, kLimits);
  EXPECT_NEAR(t.acceleration(0.1), 3.0, 1e-12);
  EXPECT_NEAR(t.velocity(0.5), 0.0, 1e-12) << "at rest after 0.5 s of braking";
  EXPECT_NEAR(t.position(0.5), -0.375, 1e-12);
  // Then 1.375 m from rest: a triangle of 2 * sqrt(1.375 / 3) s.
  EXPECT_NEAR(t.duration(), 0.5 + 2 * std::sqrt(1.375 / 3.0), 1e-12);
}

TEST(Trajectory1D, TooFastToStopItOvershootsAndReturns) {
  const Trajectory1D t = Trajectory1D::plan(0, 3.0, 0.5, kLimits);  // needs 1.5 m to stop
  double furthest = 0;
  for (double s = 0; s < t.duration(); s += 1e-3) furthest = std::max(furthest, t.position(s));
  EXPECT_NEAR(furthest, 1.5, 1e-3);
  EXPECT_EQ(t.position(t.duration()), 0.5);
}

TEST(Trajectory1D, AboveTheSpeedLimitItSlowsDownFirst) {
  const Trajectory1D t = Trajectory1D::plan(0, 4.0, 10.0, kLimits);
  EXPECT_NEAR(t.acceleration(0.1), -3.0, 1e-12);
  EXPECT_NEAR(t.velocity(1.0 / 3.0), 3.0, 1e-9);
  for (double s = 1.0 / 3.0 + 1e-6; s < t.duration(); s += 1e-2) EXPECT_LE(t.velocity(s), 3.0 + 1e-9);
}

TEST(Trajectory1D, RandomStatesEndExactlyOnTheTargetWithinTheLimits) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> position(-5, 5);
  std::uniform_real_distribution<double> speed(-4, 4);
  for (int i = 0; i < 500; ++i) {
    const double x0 = position(random);
    const double v0 = speed(random);
    const double target = position(random);
    const Trajectory1D t = Trajectory1D::plan(x0, v0, target, kLimits);
    SCOPED_TRACE(::testing::Message() << "x0 " << x0 << " v0 " << v0 << " target " << target);
    EXPECT_EQ(t.position(0), x0);
    EXPECT_EQ(t.velocity(0), v0);
    EXPECT_EQ(t.position(t.duration()), target);
    EXPECT_EQ(t.velocity(t.duration()), 0.0);
    EXPECT_NEAR(t.position(t.duration() - 1e-9), target, 1e-8) << "no jump at the end";
    const double speed_limit = std::max(kLimits.max_speed, std::abs(v0));
    for (double s = 0; s < t.duration(); s += 0.01) ASSERT_LE(std::abs(t.velocity(s)), speed_limit + 1e-9);
    expect_consistent(t, kLimits.max_acceleration);
  }
}

/// The shortest time to rest at `target` by brute force: the reachable positions per velocity, stepping
/// dt with the acceleration -a, 0 or +a (velocities on the grid a * dt, within the speed limit).
double brute_force_duration(double x0, int v0_steps, double target, const TrajectoryLimits& limits, double dt) {
  const double dv = limits.max_acceleration * dt;
  const int max_steps = static_cast<int>(std::floor(limits.max_speed / dv + 1e-9));
  const int size = 2 * max_steps + 1;
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> low(size, kNone), high(size, kNone), next_low(size), next_high(size);
  low[v0_steps + max_steps] = high[v0_steps + max_steps] = x0;
  const double tolerance = 0.5 * limits.max_acceleration * dt * dt + 1e-9;
  for (int step = 0; step < 100000; ++step) {
    const int rest = max_steps;
    if (!std::isnan(low[rest]) && low[rest] - tolerance <= target && target <= high[rest] + tolerance) {
      return step * dt;
    }
    std::fill(next_low.begin(), next_low.end(), kNone);
    std::fill(next_high.begin(), next_high.end(), kNone);
    for (int i = 0; i < size; ++i) {
      if (std::isnan(low[i])) continue;
      const double v = (i - max_steps) * dv;
      for (int u = -1; u <= 1; ++u) {
        const int j = i + u;
        if (j < 0 || j >= size) continue;
        const double moved = v * dt + 0.5 * u * dv * dt;
        const double lo = low[i] + moved;
        const double hi = high[i] + moved;
        next_low[j] = std::isnan(next_low[j]) ? lo : std::min(next_low[j], lo);
        next_high[j] = std::isnan(next_high[j]) ? hi : std::max(next_high[j], hi);
      }
    }
    low.swap(next_low);
    high.swap(next_high);
  }
  return kNone;
}

TEST(Trajectory1D, IsTimeOptimalAgainstABruteForceSearch) {
  constexpr double kDt = 2e-3;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> position(-3, 3);
  std::uniform_int_distribution<int> speed_steps(-500, 500);  // of 0.006 m/s: within +-3 m/s
  for (int i = 0; i < 12; ++i) {
    const double x0 = position(random);
    const int v0_steps = speed_steps(random);
    const double v0 = v0_steps * kLimits.max_acceleration * kDt;
    const double target = position(random);
    const double best = brute_force_duration(x0, v0_steps, target, kLimits, kDt);
    const double planned = Trajectory1D::plan(x0, v0, target, kLimits).duration();
    EXPECT_NEAR(planned, best, 0.02) << "x0 " << x0 << " v0 " << v0 << " target " << target;
  }
}

TEST(Trajectory2D, BothAxesEndTogetherOnTheTargetWithinTheLimits) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> position(-4, 4);
  std::uniform_real_distribution<double> speed(-2, 2);
  for (int i = 0; i < 200; ++i) {
    const geom::Vec2 p0(position(random), position(random));
    const geom::Vec2 target(position(random), position(random));
    const geom::Vec2 v0 = i % 2 == 0 ? geom::Vec2::Zero() : geom::Vec2(speed(random), speed(random));
    const Trajectory2D t = Trajectory2D::plan(p0, v0, target, kLimits);
    SCOPED_TRACE(::testing::Message() << "p0 " << p0.transpose() << " v0 " << v0.transpose() << " to "
                                      << target.transpose());
    EXPECT_EQ(t.position(t.duration()), target);
    EXPECT_EQ(t.velocity(t.duration()), geom::Vec2::Zero());
    // From rest the speed stays within the limit; a moving start may briefly exceed it a little while an
    // axis above its share of the limit is braked down to it (see trajectory.h).
    const double speed_limit = v0.isZero() ? kLimits.max_speed : 1.05 * std::max(kLimits.max_speed, v0.norm());
    for (double s = 0; s < t.duration(); s += 0.01) {
      ASSERT_LE(t.velocity(s).norm(), speed_limit + 1e-6);
      ASSERT_LE(t.acceleration(s).norm(), kLimits.max_acceleration + 1e-6);
    }
    if (v0.isZero()) {
      // From rest the two axes are synchronised: neither arrives early and waits.
      EXPECT_GT(t.velocity(t.duration() - 0.02).norm(), 0.0);
      const double straight = Trajectory1D::plan(0, 0, (target - p0).norm(), kLimits).duration();
      EXPECT_NEAR(t.duration(), straight, 1e-3) << "from rest the 2D path is the straight 1D one";
    }
  }
}

TEST(Trajectory2D, TheDurationBoundIsNeverAbovePlansDuration) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> position(-4, 4);
  std::uniform_real_distribution<double> speed(-4, 4);
  for (int i = 0; i < 2000; ++i) {
    const geom::Vec2 p0(position(random), position(random));
    const geom::Vec2 target(position(random), position(random));
    const geom::Vec2 v0 = i % 4 == 0 ? geom::Vec2::Zero() : geom::Vec2(speed(random), speed(random));
    const double planned = Trajectory2D::plan(p0, v0, target, kLimits).duration();
    const double bound = Trajectory2D::duration_bound(p0, v0, target, kLimits);
    SCOPED_TRACE(::testing::Message() << "p0 " << p0.transpose() << " v0 " << v0.transpose() << " to "
                                      << target.transpose());
    ASSERT_LE(bound, planned + 1e-12);
    ASSERT_GT(bound, 0.0);
  }
  // Along an axis from rest the bound is the duration itself.
  EXPECT_NEAR(Trajectory2D::duration_bound({0, 1}, {0, 0}, {5, 1}, kLimits),
              Trajectory2D::plan({0, 1}, {0, 0}, {5, 1}, kLimits).duration(), 1e-3);
}

TEST(Trajectory2D, StandingOnTheTargetTakesNoTime) {
  const Trajectory2D t = Trajectory2D::plan({1, 2}, {0, 0}, {1, 2}, kLimits);
  EXPECT_EQ(t.duration(), 0.0);
  EXPECT_EQ(t.position(0.3), geom::Vec2(1, 2));
}

TEST(Rotation, TurnsTheShortWayRound) {
  const TrajectoryLimits limits{.max_speed = 6.0, .max_acceleration = 30.0};
  const Trajectory1D t = plan_rotation(3.0, 0.0, -3.0, limits);
  EXPECT_NEAR(t.target() - 3.0, 2 * std::numbers::pi - 6.0, 1e-12) << "+0.28 rad across pi, not -6 rad";
  EXPECT_GT(t.velocity(0.01), 0.0);
  EXPECT_NEAR(std::remainder(t.position(t.duration()) - (-3.0), 2 * std::numbers::pi), 0.0, 1e-12);
}

}  // namespace
}  // namespace ssl::planner
