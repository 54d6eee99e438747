#include "services/simulator/core/physics/robot_kinematics.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace ssl::sim {
namespace {

// Row i maps a local velocity {forward, left, angular} to wheel i's surface speed (see the header).
Eigen::Matrix<double, 4, 3> wheel_matrix(const RobotSpec& spec, double wheel_distance) {
  Eigen::Matrix<double, 4, 3> m;
  for (int i = 0; i < 4; ++i) {
    const double theta = -spec.wheel_angles[static_cast<std::size_t>(i)];  // CCW from forward
    m(i, 0) = -std::sin(theta);
    m(i, 1) = std::cos(theta);
    m(i, 2) = wheel_distance;
  }
  return m;
}

}  // namespace

std::array<double, 4> wheel_velocities_from_local(const RobotSpec& spec, double wheel_distance,
                                                  const Vec3& local_velocity) {
  const Eigen::Vector4d wheels = wheel_matrix(spec, wheel_distance) * local_velocity;
  return {wheels(0), wheels(1), wheels(2), wheels(3)};
}

Vec3 local_velocity_from_wheels(const RobotSpec& spec, double wheel_distance,
                                const std::array<double, 4>& wheel_velocity) {
  const Eigen::Matrix<double, 4, 3> m = wheel_matrix(spec, wheel_distance);
  const Eigen::Vector4d wheels(wheel_velocity[0], wheel_velocity[1], wheel_velocity[2], wheel_velocity[3]);
  // Least squares by complete orthogonal decomposition: equals (M^T M)^-1 M^T w for any layout that can
  // drive the robot in every direction, and gives the minimum-norm solution for a degenerate one.
  return m.completeOrthogonalDecomposition().solve(wheels);
}

Vec2 clamp_norm(const Vec2& v, double max_norm) {
  const double norm = v.norm();
  if (norm <= max_norm) return v;
  return v * (max_norm / norm);
}

double ramp_angular_velocity(double current, double target, double speedup, double brake, double dt) {
  return ramp_velocity(Vec2(current, 0.0), Vec2(target, 0.0), speedup, brake, dt).x();
}

}  // namespace ssl::sim
