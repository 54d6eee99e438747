#include "services/world_model/core/robot_filter.h"

#include <algorithm>
#include <cmath>

#include "libs/geometry/angle.h"

namespace ssl::wm {
namespace {

double wrap(double radians) { return geom::Angle::from_radians(radians).radians(); }

double ramp(double current, double target, double max_step) {
  return current + std::clamp(target - current, -max_step, max_step);
}

}  // namespace

RobotFilter::RobotFilter(const RobotFilterParams& params, const RobotDetection& detection,
                         time::Timestamp t_capture)
    : params_(params) {
  reset(detection, t_capture);
}

void RobotFilter::reset(const RobotDetection& detection, time::Timestamp t_capture) {
  State x0;
  x0 << detection.position.x(), detection.position.y(), detection.has_orientation ? detection.orientation : 0,
      0, 0, 0;
  Filter::StateMatrix p0 = Filter::StateMatrix::Zero();
  const double sp = params_.position_stddev;
  const double so = detection.has_orientation ? params_.orientation_stddev : 3.0;
  p0.diagonal() << sp * sp, sp * sp, so * so, 4.0, 4.0, 25.0;
  filter_.reset(x0, p0);
  time_ = t_capture;
  last_update_ = t_capture;
  teleport_candidate_.reset();
}

void RobotFilter::set_prediction(Filter& filter, double dt) const {
  const State& x = filter.state();
  filter.F.setIdentity();
  filter.F(0, 3) = dt;
  filter.F(1, 4) = dt;
  filter.F(2, 5) = dt;
  filter.u.setZero();
  const bool commanded =
      command_ && time::to_seconds(time_ - command_time_) < params_.command_timeout && dt > 0;
  double sa = params_.acceleration_stddev;
  double sw = params_.angular_acceleration_stddev;
  if (commanded) {
    sa = params_.commanded_acceleration_stddev;
    sw = params_.commanded_angular_acceleration_stddev;
    // The robot's controller turns the local command with its heading; use the mid-step heading.
    const double heading = x(2) + x(5) * dt / 2;
    const double c = std::cos(heading);
    const double s = std::sin(heading);
    const Vec2 target(c * command_->forward - s * command_->left, s * command_->forward + c * command_->left);
    const Vec2 v(x(3), x(4));
    Vec2 dv = target - v;
    const double max_dv = params_.max_acceleration * dt;
    if (dv.norm() > max_dv) dv *= max_dv / dv.norm();
    const double dw = ramp(x(5), command_->angular, params_.max_angular_acceleration * dt) - x(5);
    filter.u << dv.x() * dt / 2, dv.y() * dt / 2, dw * dt / 2, dv.x(), dv.y(), dw;
  }
  // Discrete white-noise acceleration.
  const double adt = std::abs(dt);
  const double q11 = adt * adt * adt * adt / 4;
  const double q12 = adt * adt * adt / 2;
  const double q22 = adt * adt;
  filter.Q.setZero();
  for (int i = 0; i < 3; ++i) {
    const double var = (i < 2 ? sa * sa : sw * sw) * noise_scale_;
    filter.Q(i, i) = q11 * var;
    filter.Q(i, i + 3) = filter.Q(i + 3, i) = q12 * var;
    filter.Q(i + 3, i + 3) = q22 * var;
  }
}

void RobotFilter::predict_to(Filter& filter, time::Timestamp from, time::Timestamp to) const {
  const double dt = time::to_seconds(to - from);
  if (dt <= 0) return;
  set_prediction(filter, dt);
  filter.predict(true);
  filter.mutable_state()(2) = wrap(filter.state()(2));
}

RobotFilter::State RobotFilter::predict_state(time::Timestamp t) const {
  const double dt = time::to_seconds(t - time_);
  Filter copy = filter_;
  if (dt > 0) {
    set_prediction(copy, dt);
    copy.predict(false);
    State x = copy.predicted_state();
    x(2) = wrap(x(2));
    return x;
  }
  State x = filter_.state();
  x.head<3>() += dt * x.tail<3>();  // backwards: constant velocity
  x(2) = wrap(x(2));
  return x;
}

RobotFilter::UpdateResult RobotFilter::update(const RobotDetection& detection, time::Timestamp t_capture) {
  // Gate: how far could the robot have got from the prediction?
  const double dt = time::to_seconds(t_capture - time_);
  const State predicted = predict_state(t_capture);
  const double since_update = std::max(0.0, time::to_seconds(t_capture - last_update_));
  const double reach = params_.gate_distance + params_.max_speed * since_update;
  if ((detection.position - predicted.head<2>()).norm() > reach) {
    if (teleport_candidate_ && (detection.position - *teleport_candidate_).norm() <
                                   params_.gate_distance / 2 + params_.max_speed *
                                   std::abs(time::to_seconds(t_capture - teleport_candidate_time_))) {
      reset(detection, t_capture);
      return UpdateResult::kTeleported;
    }
    teleport_candidate_ = detection.position;
    teleport_candidate_time_ = t_capture;
    return UpdateResult::kOutlier;
  }
  teleport_candidate_.reset();

  // Adaptive process noise: a detection that the low-noise model cannot explain (collision, wall, a
  // command the robot did not follow) re-runs the prediction with maneuver_noise_scale times the noise.
  const Filter before = filter_;
  if (dt > 0) predict_to(filter_, time_, t_capture);
  const double lag = std::min(0.0, dt);  // <= 0: detection older than the filter state
  set_measurement(detection, lag);
  Filter::Measurement y = measurement_innovation(detection);
  if (dt > 0 && filter_.mahalanobis2(y) > params_.maneuver_gate) {
    filter_ = before;
    noise_scale_ = params_.maneuver_noise_scale;
    predict_to(filter_, time_, t_capture);
    noise_scale_ = 1;
    set_measurement(detection, lag);
    y = measurement_innovation(detection);
  }
  if (dt > 0) time_ = t_capture;
  filter_.update_with_innovation(y);
  filter_.mutable_state()(2) = wrap(filter_.state()(2));
  last_update_ = std::max(last_update_, t_capture);
  return UpdateResult::kFused;
}

void RobotFilter::set_measurement(const RobotDetection& detection, double lag) {
  filter_.H.setZero();
  filter_.H(0, 0) = filter_.H(1, 1) = filter_.H(2, 2) = 1;
  filter_.H(0, 3) = filter_.H(1, 4) = filter_.H(2, 5) = lag;
  const double sp = params_.position_stddev;
  const double so = detection.has_orientation ? params_.orientation_stddev : 1e3;
  filter_.R.setZero();
  filter_.R.diagonal() << sp * sp, sp * sp, so * so;
}

RobotFilter::Filter::Measurement RobotFilter::measurement_innovation(const RobotDetection& detection) const {
  Filter::Measurement z;
  z << detection.position.x(), detection.position.y(), detection.has_orientation ? detection.orientation : 0;
  Filter::Measurement y = filter_.innovation(z);
  y(2) = detection.has_orientation ? wrap(y(2)) : 0;
  return y;
}

}  // namespace ssl::wm
