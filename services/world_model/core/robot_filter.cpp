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
      0, 0, 0, 0, 0;
  Filter::StateMatrix p0 = Filter::StateMatrix::Zero();
  const double sp = params_.position_stddev;
  const double so = detection.has_orientation ? params_.orientation_stddev : 3.0;
  const double sa = params_.acceleration_stddev;
  p0.diagonal() << sp * sp, sp * sp, so * so, 4.0, 4.0, 25.0, sa * sa, sa * sa;
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

RobotFilter::State RobotFilter::free_step(const State& x, double dt, bool turning,
                                          Filter::StateMatrix* jacobian) const {
  const double decay =
      params_.acceleration_time_constant > 0 ? std::exp(-dt / params_.acceleration_time_constant) : 1.0;
  State f = x;
  f(2) += x(5) * dt;
  const Vec2 v = x.segment<2>(3);
  const Vec2 a = x.segment<2>(6);
  if (!turning) {
    // The acceleration stays in the field (a controller that re-aims the robot's velocity).
    f.head<2>() += dt * v + dt * dt / 2 * a;
    f.segment<2>(3) += dt * a;
    f.segment<2>(6) = decay * a;
    if (jacobian) {
      jacobian->setIdentity();
      (*jacobian)(0, 3) = (*jacobian)(1, 4) = (*jacobian)(2, 5) = dt;
      (*jacobian)(0, 6) = (*jacobian)(1, 7) = dt * dt / 2;
      (*jacobian)(3, 6) = (*jacobian)(4, 7) = dt;
      (*jacobian)(6, 6) = (*jacobian)(7, 7) = decay;
    }
    return f;
  }
  // The robot holds (or smoothly changes) a LOCAL velocity: what is left of the acceleration once the
  // centripetal part w J v is taken off, a_r = a - w J v, turns with the robot: with R = R(w dt),
  // v' = R (v + a_r dt), a_r' = R a_r, a' = a_r' + w J v', p' = p + dt (v + v') / 2.
  const double w = x(5);
  const double c = std::cos(w * dt);
  const double s = std::sin(w * dt);
  Eigen::Matrix2d rot;
  rot << c, -s, s, c;
  Eigen::Matrix2d perp;  // J: a quarter turn
  perp << 0, -1, 1, 0;
  const Vec2 a_r = a - w * (perp * v);
  const Vec2 v_next = rot * (v + dt * a_r);
  const Vec2 a_r_next = decay * (rot * a_r);
  const Vec2 a_next = a_r_next + w * (perp * v_next);
  f.head<2>() += dt / 2 * (v + v_next);
  f.segment<2>(3) = v_next;
  f.segment<2>(6) = a_next;
  if (jacobian) {
    using Rows = Eigen::Matrix<double, 2, 8>;
    Rows d_v = Rows::Zero();  // dv/dx
    d_v(0, 3) = d_v(1, 4) = 1;
    Rows d_ar = Rows::Zero();
    d_ar.block<2, 2>(0, 3) = -w * perp;
    d_ar.col(5) = -(perp * v);
    d_ar.block<2, 2>(0, 6).setIdentity();
    const Rows d_vn = [&] {
      Rows d = rot * (d_v + dt * d_ar);
      d.col(5) += dt * (perp * v_next);  // dR/dw = dt J R
      return d;
    }();
    Rows d_arn = decay * (rot * d_ar);
    d_arn.col(5) += dt * (perp * a_r_next);
    Rows d_an = d_arn + w * (perp * d_vn);
    d_an.col(5) += perp * v_next;
    jacobian->setIdentity();
    jacobian->block<2, 8>(0, 0) += dt / 2 * (d_v + d_vn);
    (*jacobian)(2, 5) = dt;
    jacobian->block<2, 8>(3, 0) = d_vn;
    jacobian->block<2, 8>(6, 0) = d_an;
  }
  return f;
}

RobotFilter::State RobotFilter::step(const State& x, double dt, const RobotCommand* command,
                                     Filter::StateMatrix* jacobian, Filter::StateMatrix* noise) const {
  // In contact without a command: constant velocity, the acceleration forgotten (reset to its prior).
  State f = x;
  f.head<3>() += dt * x.segment<3>(3);
  f.segment<2>(6).setZero();
  if (jacobian) {
    jacobian->setIdentity();
    (*jacobian)(0, 3) = (*jacobian)(1, 4) = (*jacobian)(2, 5) = dt;
    (*jacobian)(6, 6) = (*jacobian)(7, 7) = 0;
  }
  const bool commanded = command != nullptr && dt > 0;
  const bool free = !commanded && !in_contact_ && dt > 0;  // the uncommanded (Singer) acceleration model
  double sa = in_contact_ ? params_.contact_acceleration_stddev : params_.acceleration_stddev;
  double sw = in_contact_ ? params_.contact_angular_acceleration_stddev : params_.angular_acceleration_stddev;
  if (commanded) {
    sa = params_.commanded_acceleration_stddev;
    sw = params_.commanded_angular_acceleration_stddev;
    // Extended Kalman step of the commanded model: the robot's controller ramps its velocity towards the
    // command turned by its (mid-step) heading, at most max_acceleration; the position integrates the
    // velocity along the ramp. `jacobian` is its Jacobian (EKF). A velocity that reaches the command
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
    f.head<2>() = x.head<2>() + dt * (ramp_weight * v + (1 - ramp_weight) * v_next);
    f(2) = x(2) + dt * (w + w_next) / 2;
    f.segment<2>(3) = v_next;
    f(5) = w_next;
    if (jacobian) {
      Filter::StateMatrix& F = *jacobian;
      F.setZero();
      F.block<2, 2>(0, 0).setIdentity();
      F.block<2, 2>(0, 3) = dt * (ramp_weight * Eigen::Matrix2d::Identity() + (1 - ramp_weight) * dv_dv);
      F.block<2, 1>(0, 2) = dt * (1 - ramp_weight) * dv_dheading;
      F(2, 2) = 1;
      F(2, 5) = dt * (1 + dw_dw) / 2;
      F.block<2, 2>(3, 3) = dv_dv;
      F.block<2, 1>(3, 2) = dv_dheading;
      F(5, 5) = dw_dw;
    }
  } else if (free) {
    // Constant (Singer: mean-reverting) FIELD acceleration, held in the field or turning with the robot.
    f = free_step(x, dt, turn_model_, jacobian);
  }
  if (!noise) return f;
  Filter::StateMatrix& Q = *noise;
  const double adt = std::abs(dt);
  Q.setZero();
  if (free) {
    // Continuous white jerk (integrated three times), per axis over [p, v, a].
    const double q = params_.jerk_stddev * params_.jerk_stddev * noise_scale_;
    const double d2 = adt * adt, d3 = d2 * adt, d4 = d3 * adt, d5 = d4 * adt;
    for (int i = 0; i < 2; ++i) {
      Q(i, i) = q * d5 / 20;
      Q(i, i + 3) = Q(i + 3, i) = q * d4 / 8;
      Q(i, i + 6) = Q(i + 6, i) = q * d3 / 6;
      Q(i + 3, i + 3) = q * d3 / 3;
      Q(i + 3, i + 6) = Q(i + 6, i + 3) = q * d2 / 2;
      Q(i + 6, i + 6) = q * adt;
    }
    sa = 0;  // the jerk noise moves the velocity
  } else {
    // The acceleration state is not part of these models: it restarts unknown (zero, its prior variance).
    Q(6, 6) = Q(7, 7) = params_.acceleration_stddev * params_.acceleration_stddev;
  }
  // Discrete white-noise acceleration.
  const double q11 = adt * adt * adt * adt / 4;
  const double q12 = adt * adt * adt / 2;
  const double q22 = adt * adt;
  for (int i = 0; i < 3; ++i) {
    const double var = (i < 2 ? sa * sa : sw * sw) * noise_scale_;
    Q(i, i) += q11 * var;
    Q(i, i + 3) += q12 * var;
    Q(i + 3, i) += q12 * var;
    Q(i + 3, i + 3) += q22 * var;
  }
  return f;
}

void RobotFilter::predict_to(Filter& filter, time::Timestamp from, time::Timestamp to) const {
  // x = f(x), P = F P F^T + Q. Products of 8x8 matrices are written as lazy (coefficient-wise, unrolled)
  // products: Eigen would send them to its cache-blocked GEMM, several times slower at this size.
  Filter::StateMatrix jacobian;
  Filter::StateMatrix noise;
  while (from < to) {
    const time::Timestamp until = next_command_change(from, to);
    State x = step(filter.state(), time::to_seconds(until - from), command_at(from), &jacobian, &noise);
    x(2) = wrap(x(2));
    filter.mutable_state() = x;
    const Filter::StateMatrix fp = jacobian.lazyProduct(filter.covariance());
    filter.mutable_covariance() = fp.lazyProduct(jacobian.transpose()) + noise;
    from = until;
  }
}

RobotFilter::State RobotFilter::predict_state(time::Timestamp t) const {
  if (t > time_) {
    // The mean only (no covariance): state() asks this for every robot on every publish.
    State x = filter_.state();
    for (time::Timestamp from = time_; from < t;) {
      const time::Timestamp until = next_command_change(from, t);
      x = step(x, time::to_seconds(until - from), command_at(from), nullptr, nullptr);
      x(2) = wrap(x(2));
      from = until;
    }
    return x;
  }
  State x = filter_.state();
  const double back = time::to_seconds(t - time_);  // backwards: constant acceleration
  x.head<3>() += back * x.segment<3>(3);
  x.head<2>() += back * back / 2 * x.segment<2>(6);
  x.segment<2>(3) += back * x.segment<2>(6);
  x(2) = wrap(x(2));
  return x;
}

void RobotFilter::score_motion_models(const RobotDetection& detection, double dt) {
  // Without a command the robot either holds a LOCAL velocity (the velocity turns with it) or a GLOBAL
  // one (its controller re-aims it). Score both one-step predictions against the detection and use the
  // one that has recently explained the detections better (exponentially weighted squared errors).
  if (!params_.velocity_turns_with_robot || dt <= 0 || command_at(time_) != nullptr) return;
  const State& x = filter_.state();
  const Vec2 p_global = free_step(x, dt, false, nullptr).head<2>();
  const Vec2 p_local = free_step(x, dt, true, nullptr).head<2>();
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
  const State x_before = filter_.state();
  const Filter::StateMatrix p_before = filter_.covariance();
  if (dt > 0) predict_to(filter_, time_, t_capture);
  const double lag = std::min(0.0, dt);  // <= 0: detection older than the filter state
  set_measurement(detection, lag);
  Filter::Measurement y = measurement_innovation(detection);
  // The Kalman update, as KalmanFilter::update_with_innovation (Joseph form) but with lazy products (see
  // predict_to()) and S computed once for the gate and the gain.
  Eigen::Matrix<double, 8, 3> pht = filter_.covariance().lazyProduct(filter_.H.transpose());
  Filter::MeasurementCovariance s_inv = (filter_.H.lazyProduct(pht) + filter_.R).inverse();
  if (dt > 0 && y.dot(s_inv * y) > params_.maneuver_gate) {
    filter_.mutable_state() = x_before;
    filter_.mutable_covariance() = p_before;
    noise_scale_ = params_.maneuver_noise_scale;
    predict_to(filter_, time_, t_capture);
    noise_scale_ = 1;
    y = measurement_innovation(detection);
    pht = filter_.covariance().lazyProduct(filter_.H.transpose());
    s_inv = (filter_.H.lazyProduct(pht) + filter_.R).inverse();
  }
  if (dt > 0) time_ = t_capture;
  const Eigen::Matrix<double, 8, 3> gain = pht.lazyProduct(s_inv);
  filter_.mutable_state() += gain.lazyProduct(y);
  filter_.mutable_state()(2) = wrap(filter_.state()(2));
  const Filter::StateMatrix i_kh = Filter::StateMatrix::Identity() - gain.lazyProduct(filter_.H);
  const Filter::StateMatrix kp = i_kh.lazyProduct(filter_.covariance());
  const Eigen::Matrix<double, 8, 3> kr = gain * filter_.R.diagonal().asDiagonal();
  filter_.mutable_covariance() = kp.lazyProduct(i_kh.transpose()) + kr.lazyProduct(gain.transpose());
  last_update_ = std::max(last_update_, t_capture);
  return UpdateResult::kFused;
}

void RobotFilter::set_measurement(const RobotDetection& detection, double lag) {
  filter_.H.setZero();
  filter_.H(0, 0) = filter_.H(1, 1) = filter_.H(2, 2) = 1;
  filter_.H(0, 3) = filter_.H(1, 4) = filter_.H(2, 5) = lag;
  filter_.H(0, 6) = filter_.H(1, 7) = lag * lag / 2;
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
