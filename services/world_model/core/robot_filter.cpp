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

void RobotFilter::set_command(const RobotCommand& command, time::Timestamp t_vision) {
  const time::Timestamp effective = t_vision + time::duration_from_seconds(params_.command_delay);
  // Commands arrive in order; one older than the newest (a clock offset correction) replaces nothing.
  if (command_count_ > 0 && effective < commands_[(command_count_ - 1) % kCommandHistory].effective) return;
  commands_[command_count_ % kCommandHistory] = {command, effective};
  ++command_count_;
}

const RobotCommand* RobotFilter::command_at(time::Timestamp t) const {
  if (in_contact_) return nullptr;
  const std::size_t stored = std::min(command_count_, kCommandHistory);
  for (std::size_t back = 1; back <= stored; ++back) {
    const TimedCommand& entry = commands_[(command_count_ - back) % kCommandHistory];
    if (entry.effective <= t) {
      return time::to_seconds(t - entry.effective) < params_.command_timeout ? &entry.command : nullptr;
    }
  }
  return nullptr;
}

time::Timestamp RobotFilter::next_command_change(time::Timestamp from, time::Timestamp to) const {
  // Pieces end where a newer command takes effect or the one in force expires.
  const time::Duration timeout = time::duration_from_seconds(params_.command_timeout);
  time::Timestamp next = to;
  const std::size_t stored = std::min(command_count_, kCommandHistory);
  for (std::size_t back = 1; back <= stored; ++back) {
    const TimedCommand& entry = commands_[(command_count_ - back) % kCommandHistory];
    if (entry.effective > from && entry.effective < next) next = entry.effective;
    const time::Timestamp expiry = entry.effective + timeout;
    if (expiry > from && expiry < next) next = expiry;
    if (entry.effective <= from) break;  // the command in force at `from`: older ones do not matter
  }
  return next;
}

void RobotFilter::set_prediction(Filter& filter, double dt, const RobotCommand* command) const {
  const State& x = filter.state();
  filter.F.setIdentity();
  filter.F(0, 3) = dt;
  filter.F(1, 4) = dt;
  filter.F(2, 5) = dt;
  filter.u.setZero();
  const bool commanded = command != nullptr && dt > 0;
  double sa = in_contact_ ? params_.contact_acceleration_stddev : params_.acceleration_stddev;
  double sw = in_contact_ ? params_.contact_angular_acceleration_stddev : params_.angular_acceleration_stddev;
  if (commanded) {
    sa = params_.commanded_acceleration_stddev;
    sw = params_.commanded_angular_acceleration_stddev;
    // Extended Kalman step of the commanded model: the robot's controller ramps its velocity towards the
    // command turned by its (mid-step) heading, at most max_acceleration; the position integrates the
    // velocity along the ramp. F is the Jacobian, u = f(x) - F x. A velocity that reaches the command
    // forgets its old value (dv'/dv = 0): that is what lets the filter trust the command.
    const double heading = x(2) + x(5) * dt / 2;
    const double c = std::cos(heading);
    const double s = std::sin(heading);
    const Vec2 target(c * command->forward - s * command->left, s * command->forward + c * command->left);
    const Vec2 dtarget_dheading(-target.y(), target.x());
    const Vec2 v(x(3), x(4));
    const Vec2 delta = target - v;
    const double max_dv = params_.max_acceleration * dt;
    Vec2 v_next = target;
    Eigen::Matrix2d dv_dv = Eigen::Matrix2d::Zero();
    Vec2 dv_dheading = dtarget_dheading;
    double reach_fraction = delta.norm() > 0 ? std::min(1.0, delta.norm() / max_dv) : 0;  // of dt to target
    if (delta.norm() > max_dv) {
      const Vec2 n = delta / delta.norm();
      const Eigen::Matrix2d across = Eigen::Matrix2d::Identity() - n * n.transpose();
      v_next = v + max_dv * n;
      dv_dv = Eigen::Matrix2d::Identity() - max_dv / delta.norm() * across;
      dv_dheading = max_dv / delta.norm() * across * dtarget_dheading;
      reach_fraction = 1;
    }
    const double w = x(5);
    const double max_dw = params_.max_angular_acceleration * dt;
    const double w_next = ramp(w, command->angular, max_dw);
    const double dw_dw = std::abs(command->angular - w) > max_dw ? 1 : 0;
    // Mean velocity over the step: the ramp part, then the reached velocity.
    const double ramp_weight = reach_fraction / 2;
    State f;
    f.head<2>() = x.head<2>() + dt * (ramp_weight * v + (1 - ramp_weight) * v_next);
    f(2) = x(2) + dt * (w + w_next) / 2;
    f.segment<2>(3) = v_next;
    f(5) = w_next;
    filter.F.setZero();
    filter.F.block<2, 2>(0, 0).setIdentity();
    filter.F.block<2, 2>(0, 3) = dt * (ramp_weight * Eigen::Matrix2d::Identity() + (1 - ramp_weight) * dv_dv);
    filter.F.block<2, 1>(0, 2) = dt * (1 - ramp_weight) * dv_dheading;
    filter.F(2, 2) = 1;
    filter.F(2, 5) = dt * (1 + dw_dw) / 2;
    filter.F.block<2, 2>(3, 3) = dv_dv;
    filter.F.block<2, 1>(3, 2) = dv_dheading;
    filter.F(5, 5) = dw_dw;
    filter.u = f - filter.F * x;
  } else if (turn_model_ && dt > 0 && !in_contact_) {
    // Extended Kalman step of the local-velocity model: the velocity turns with the robot (an omni robot
    // holding a local velocity command), v' = R(w dt) v, p' = p + dt (v + v') / 2; F is the Jacobian and
    // u = f(x) - F x, so that F x + u = f(x).
    const double turn = x(5) * dt;
    const double c = std::cos(turn);
    const double s = std::sin(turn);
    const Vec2 v(x(3), x(4));
    const Vec2 v_next(c * v.x() - s * v.y(), s * v.x() + c * v.y());
    State f = x;
    f.head<2>() += dt * (v + v_next) / 2;
    f(2) += turn;
    f.segment<2>(3) = v_next;
    filter.F(3, 3) = c;
    filter.F(3, 4) = -s;
    filter.F(4, 3) = s;
    filter.F(4, 4) = c;
    filter.F(3, 5) = -dt * v_next.y();
    filter.F(4, 5) = dt * v_next.x();
    filter.F(0, 3) = dt / 2 * (1 + c);
    filter.F(0, 4) = -dt / 2 * s;
    filter.F(1, 3) = dt / 2 * s;
    filter.F(1, 4) = dt / 2 * (1 + c);
    filter.F(0, 5) = dt / 2 * filter.F(3, 5);
    filter.F(1, 5) = dt / 2 * filter.F(4, 5);
    filter.u = f - filter.F * x;
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
  while (from < to) {
    const time::Timestamp until = next_command_change(from, to);
    set_prediction(filter, time::to_seconds(until - from), command_at(from));
    filter.predict(true);
    filter.mutable_state()(2) = wrap(filter.state()(2));
    from = until;
  }
}

RobotFilter::State RobotFilter::predict_state(time::Timestamp t) const {
  if (t > time_) {
    // The mean only (no covariance): state() asks this for every robot on every publish.
    Filter copy = filter_;
    for (time::Timestamp from = time_; from < t;) {
      const time::Timestamp until = next_command_change(from, t);
      set_prediction(copy, time::to_seconds(until - from), command_at(from));
      copy.mutable_state() = copy.F * copy.state() + copy.u;
      copy.mutable_state()(2) = wrap(copy.state()(2));
      from = until;
    }
    return copy.state();
  }
  State x = filter_.state();
  x.head<3>() += time::to_seconds(t - time_) * x.tail<3>();  // backwards: constant velocity
  x(2) = wrap(x(2));
  return x;
}

void RobotFilter::score_motion_models(const RobotDetection& detection, double dt) {
  // Without a command the robot either holds a LOCAL velocity (the velocity turns with it) or a GLOBAL
  // one (its controller re-aims it). Score both one-step predictions against the detection and use the
  // one that has recently explained the detections better (exponentially weighted squared errors).
  if (!params_.velocity_turns_with_robot || dt <= 0 || command_at(time_) != nullptr) return;
  const State& x = filter_.state();
  const Vec2 v(x(3), x(4));
  const Vec2 p_global = x.head<2>() + dt * v;
  const double turn = x(5) * dt;
  const Vec2 v_turned(std::cos(turn) * v.x() - std::sin(turn) * v.y(),
                      std::sin(turn) * v.x() + std::cos(turn) * v.y());
  const Vec2 p_local = x.head<2>() + dt * (v + v_turned) / 2;
  const double e_global = (detection.position - p_global).squaredNorm();
  const double e_local = (detection.position - p_local).squaredNorm();
  const double keep = params_.motion_model_memory;
  turn_score_ = keep * turn_score_ + (1 - keep) * (e_local - e_global);
  turn_model_ = turn_score_ < 0;
}

RobotFilter::UpdateResult RobotFilter::update(const RobotDetection& detection, time::Timestamp t_capture,
                                              bool in_contact) {
  in_contact_ = in_contact;
  score_motion_models(detection, time::to_seconds(t_capture - time_));
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
