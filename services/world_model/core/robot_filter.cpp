#include "services/world_model/core/robot_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "libs/geometry/angle.h"
#include "libs/geometry/vec2.h"

namespace ssl::wm {
namespace {

double wrap(double radians) { return geom::Angle::from_radians(radians).radians(); }

double ramp(double current, double target, double max_step) {
  return current + std::clamp(target - current, -max_step, max_step);
}

/// What is left of an acceleration after dt (s) with time constant `time_constant` (s; 0: all of it).
double decay_over(double dt, double time_constant) { return time_constant > 0 ? std::exp(-dt / time_constant) : 1.0; }

}  // namespace

RobotFilter::RobotFilter(const RobotFilterParams& params, const RobotDetection& detection,
                         time::Timestamp t_capture, std::optional<DetectionNoise> noise)
    : params_(params),
      noise_(noise.value_or(DetectionNoise{params.position_stddev, params.orientation_stddev})),
      mode_count_(std::clamp<std::size_t>(params.mode_jerk_stddev.size(), 1, kMaxJerkModes) +
                  (params.stationary_mode ? 1 : 0)) {
  if (params_.mode_jerk_stddev.empty() || params_.mode_jerk_stddev.size() > kMaxJerkModes) {
    throw std::invalid_argument("RobotFilterParams::mode_jerk_stddev needs 1 to 4 values");
  }
  if (params_.mode_angular_acceleration_stddev.size() != params_.mode_jerk_stddev.size() ||
      params_.mode_acceleration_time_constant.size() != params_.mode_jerk_stddev.size()) {
    throw std::invalid_argument("RobotFilterParams::mode_angular_acceleration_stddev and "
                                "mode_acceleration_time_constant need one value per mode_jerk_stddev");
  }
  reset(detection, t_capture);
}

void RobotFilter::reset(const RobotDetection& detection, time::Timestamp t_capture) {
  State x0;
  x0 << detection.position.x(), detection.position.y(), detection.has_orientation ? detection.orientation : 0,
      0, 0, 0, 0, 0;
  Filter::StateMatrix p0 = Filter::StateMatrix::Zero();
  const double sp = noise_.position_stddev;
  const double so = detection.has_orientation ? noise_.orientation_stddev : 3.0;
  const double sa = params_.acceleration_stddev;
  p0.diagonal() << sp * sp, sp * sp, so * so, 4.0, 4.0, 25.0, sa * sa, sa * sa;
  filter_.reset(x0, p0);
  time_ = t_capture;
  last_update_ = t_capture;
  teleport_candidate_.reset();
  modes_stale_ = true;
  mode_probability_.fill(0);
  std::fill_n(mode_probability_.begin(), mode_count_, 1.0 / static_cast<double>(mode_count_));
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

RobotFilter::State RobotFilter::free_step(const State& x, double dt, bool turning, double decay,
                                          Filter::StateMatrix* jacobian) {
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

RobotFilter::Filter::StateMatrix RobotFilter::heading_noise(const State& x, double dt, double angular_stddev,
                                                           bool turning) {
  // Discrete white angular acceleration on [theta, omega], mapped by G onto the state. Turning: the
  // velocity and the acceleration turn with the heading (a turn dtheta adds dtheta J v and dtheta J a), and
  // a change domega of the turn rate changes the centripetal acceleration by domega J v.
  const double var = angular_stddev * angular_stddev;
  Eigen::Matrix2d q;
  q << dt * dt * dt * dt / 4 * var, dt * dt * dt / 2 * var, dt * dt * dt / 2 * var, dt * dt * var;
  Eigen::Matrix<double, 8, 2> g = Eigen::Matrix<double, 8, 2>::Zero();
  g(2, 0) = g(5, 1) = 1;
  if (turning) {
    g.block<2, 1>(3, 0) = geom::perpendicular(x.segment<2>(3));
    g.block<2, 1>(6, 0) = geom::perpendicular(x.segment<2>(6));
    g.block<2, 1>(6, 1) = geom::perpendicular(x.segment<2>(3));
  }
  const Eigen::Matrix<double, 8, 2> gq = g.lazyProduct(q);
  return gq.lazyProduct(g.transpose());
}

RobotFilter::State RobotFilter::step(const State& x, double dt, const RobotCommand* command, double jerk_stddev,
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
    f = free_step(x, dt, turn_model_, decay_over(dt, params_.acceleration_time_constant), jacobian);
  }
  if (!noise) return f;
  Filter::StateMatrix& Q = *noise;
  const double adt = std::abs(dt);
  Q.setZero();
  if (free) {
    // Continuous white jerk (integrated three times), per axis over [p, v, a].
    const double q = jerk_stddev * jerk_stddev * noise_scale_;
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
  for (int i = 0; i < 2; ++i) {
    const double var = sa * sa * noise_scale_;
    Q(i, i) += q11 * var;
    Q(i, i + 3) += q12 * var;
    Q(i + 3, i) += q12 * var;
    Q(i + 3, i + 3) += q22 * var;
  }
  Q += heading_noise(x, adt, sw * std::sqrt(noise_scale_), free && turn_model_);
  return f;
}

void RobotFilter::predict_to(Filter& filter, time::Timestamp from, time::Timestamp to,
                             double jerk_stddev) const {
  // x = f(x), P = F P F^T + Q. Products of 8x8 matrices are written as lazy (coefficient-wise, unrolled)
  // products: Eigen would send them to its cache-blocked GEMM, several times slower at this size.
  Filter::StateMatrix jacobian;
  Filter::StateMatrix noise;
  while (from < to) {
    const time::Timestamp until = next_command_change(from, to);
    State x = step(filter.state(), time::to_seconds(until - from), command_at(from), jerk_stddev, &jacobian,
                   &noise);
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
      x = step(x, time::to_seconds(until - from), command_at(from), 0, nullptr, nullptr);
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

void RobotFilter::score_motion_models(time::Timestamp t_capture) {
  // Without a command the robot either holds a LOCAL velocity (the velocity turns with it) or a GLOBAL
  // one (its controller re-aims it). Both models predict alike over a frame (they share the acceleration
  // state), but they differ in what they expect to stay constant: the acceleration in the field, or what
  // is left of it without the centripetal part omega J v. The robot follows the one under which it
  // accelerates less (exponentially weighted over motion_model_time_constant): holding a local velocity
  // while turning at omega, its field acceleration is omega |v| and the rest zero; driving straight while
  // turning, the other way round.
  const double dt = time::to_seconds(t_capture - time_);
  if (!params_.velocity_turns_with_robot || dt <= 0 || command_at(time_) != nullptr) return;
  const State& x = filter_.state();
  const Vec2 a = x.segment<2>(6);
  const Vec2 a_turning = a - x(5) * geom::perpendicular(x.segment<2>(3));
  const double keep = std::exp(-dt / params_.motion_model_time_constant);
  turn_score_ = keep * turn_score_ + (1 - keep) * (a_turning.squaredNorm() - a.squaredNorm());
  turn_model_ = turn_score_ < 0;
}

RobotFilter::UpdateResult RobotFilter::update(const RobotDetection& detection, time::Timestamp t_capture,
                                              bool in_contact, std::optional<DetectionNoise> noise) {
  noise_ = noise.value_or(DetectionNoise{params_.position_stddev, params_.orientation_stddev});
  // Contact makes a command untrustworthy; without one it changes nothing (the IMM's loose modes take the
  // pushes), so an uncommanded robot next to others keeps the IMM's smoothing.
  in_contact_ = false;
  const bool commanded = command_at(std::min(time_, t_capture)) != nullptr || command_at(t_capture) != nullptr;
  in_contact_ = in_contact && commanded;
  score_motion_models(t_capture);
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

  if (!commanded && mode_count_ > 1) {
    update_modes(detection, t_capture);
  } else {
    // Commanded (or in contact): one filter. A command that expires inside the interval leaves a free
    // piece, predicted with the loosest jerk density.
    predict_and_fuse(filter_, detection, t_capture, params_.mode_jerk_stddev.back());
    modes_stale_ = true;
  }
  if (dt > 0) time_ = t_capture;
  last_update_ = std::max(last_update_, t_capture);
  return UpdateResult::kFused;
}

RobotFilter::Innovation RobotFilter::innovation_of(const Filter& filter, const RobotDetection& detection,
                                                   double lag) const {
  // The measurement: x, y and (when detected) the heading of the state `lag` (<= 0) seconds back, i.e.
  // H = [I_3 | lag I_3 | lag^2/2 I_2 (position rows)]. Lazy products: Eigen would send these small
  // fixed-size products to its cache-blocked GEMM.
  const double sp = noise_.position_stddev;
  const double so = detection.has_orientation ? noise_.orientation_stddev : 1e3;
  const State& x = filter.state();
  const Filter::StateMatrix& p = filter.covariance();
  Innovation out;
  if (lag == 0) {
    // H picks x, y and the heading: P H^T is P's first three columns.
    out.y << detection.position.x() - x(0), detection.position.y() - x(1),
        detection.has_orientation ? wrap(detection.orientation - x(2)) : 0;
    out.pht = p.leftCols<3>();
    out.s = out.pht.topRows<3>();
  } else {
    Filter::MeasurementMatrix h = Filter::MeasurementMatrix::Zero();
    h(0, 0) = h(1, 1) = h(2, 2) = 1;
    h(0, 3) = h(1, 4) = h(2, 5) = lag;
    h(0, 6) = h(1, 7) = lag * lag / 2;
    const Filter::Measurement predicted = h.lazyProduct(x);
    out.y << detection.position.x() - predicted(0), detection.position.y() - predicted(1),
        detection.has_orientation ? wrap(detection.orientation - predicted(2)) : 0;
    out.pht = p.lazyProduct(h.transpose());
    out.s = h.lazyProduct(out.pht);
  }
  out.s.diagonal() += Eigen::Vector3d(sp * sp, sp * sp, so * so);
  out.s_inv = out.s.inverse();
  out.mahalanobis2 = out.y.dot(out.s_inv * out.y);
  return out;
}

double RobotFilter::fuse(Filter& filter, const Innovation& in) {
  const Eigen::Matrix<double, 8, 3> gain = in.pht.lazyProduct(in.s_inv);
  filter.mutable_state() += gain.lazyProduct(in.y);
  filter.mutable_state()(2) = wrap(filter.state()(2));
  // P - K H P with H P = (P H^T)^T, symmetrised: a fifth of the Joseph form's work, and with the optimal
  // gain the same result up to rounding.
  Filter::StateMatrix& p = filter.mutable_covariance();
  p -= gain.lazyProduct(in.pht.transpose());
  p = 0.5 * (p + p.transpose()).eval();
  return -0.5 * (in.mahalanobis2 + std::log(in.s.determinant()));
}

void RobotFilter::predict_and_fuse(Filter& filter, const RobotDetection& detection, time::Timestamp t_capture,
                                   double jerk_stddev) {
  const double dt = time::to_seconds(t_capture - time_);
  // Adaptive process noise: a detection that the low-noise model cannot explain (collision, wall, a
  // command the robot did not follow) re-runs the prediction with maneuver_noise_scale times the noise.
  const State x_before = filter.state();
  const Filter::StateMatrix p_before = filter.covariance();
  if (dt > 0) predict_to(filter, time_, t_capture, jerk_stddev);
  const double lag = std::min(0.0, dt);  // <= 0: detection older than the state
  Innovation innovation = innovation_of(filter, detection, lag);
  if (dt > 0 && innovation.mahalanobis2 > params_.maneuver_gate) {
    filter.mutable_state() = x_before;
    filter.mutable_covariance() = p_before;
    noise_scale_ = params_.maneuver_noise_scale;
    predict_to(filter, time_, t_capture, jerk_stddev);
    noise_scale_ = 1;
    innovation = innovation_of(filter, detection, lag);
  }
  fuse(filter, innovation);
}

void RobotFilter::update_modes(const RobotDetection& detection, time::Timestamp t_capture) {
  const std::size_t n = mode_count_;
  // The difference of two states, the heading wrapped.
  auto difference = [](const State& a, const State& b) {
    State d = a - b;
    d(2) = wrap(d(2));
    return d;
  };
  if (modes_stale_) {
    for (std::size_t j = 0; j < n; ++j) modes_[j].reset(filter_.state(), filter_.covariance());
    modes_stale_ = false;
  }
  const double dt = time::to_seconds(t_capture - time_);
  const double lag = std::min(0.0, dt);  // <= 0: detection older than the modes' state
  std::array<double, kMaxModes> prior = mode_probability_;  // of each mode after the switches over dt
  if (dt > 0) {
    // Mixing: over dt a robot leaves its mode with rate mode_switch_rate, to each other mode alike; each
    // mode starts from the mixture of the modes it may have come from. With the modes' offsets y_i from a
    // reference and A_i = P_i + y_i y_i^T, mode j starts at m_j = sum_i w_ij y_i with covariance
    // sum_i w_ij A_i - m_j m_j^T (the spread of the means included). As w_ij = (move + (stay - move)
    // [i = j]) mu_i / prior_j, both sums are one shared total plus mode j's own term.
    const double stay = std::exp(-params_.mode_switch_rate * dt);
    const double move = (1 - stay) / static_cast<double>(n - 1);
    const State reference = modes_[0].state();
    std::array<State, kMaxModes> offset;
    State offset_total = State::Zero();
    Filter::StateMatrix moment_total = Filter::StateMatrix::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      offset[i] = difference(modes_[i].state(), reference);
      Filter::StateMatrix& p = modes_[i].mutable_covariance();
      p += offset[i].lazyProduct(offset[i].transpose());  // A_i, in place: P_i is replaced below
      offset_total += mode_probability_[i] * offset[i];
      moment_total += mode_probability_[i] * p;
    }
    for (std::size_t j = 0; j < n; ++j) {
      const double own = (stay - move) * mode_probability_[j];
      prior[j] = move + own;  // sum_i (move + (stay - move) [i = j]) mu_i, the mu_i summing to 1
      const State mean = (move * offset_total + own * offset[j]) / prior[j];
      Filter::StateMatrix& p = modes_[j].mutable_covariance();
      p = (move * moment_total + own * p) / prior[j] - mean.lazyProduct(mean.transpose());
      State x = reference + mean;
      x(2) = wrap(x(2));
      modes_[j].mutable_state() = x;
    }
  }
  // Each mode predicts (one Jacobian and noise shape for all, at the estimate: the modes are close) and
  // fuses; the detection's likelihood under each prediction weighs the modes. Only the loosest mode
  // re-predicts beyond the maneuver gate (a collision): in the others a surprise is what moves the
  // probability to the loosest.
  Filter::StateMatrix jerk_noise;  // the free step's Q with a jerk density of 1, without its heading part
  Filter::StateMatrix angular_noise;  // the heading part with a white angular acceleration of 1 rad/s^2
  // The Jacobian is linear in the acceleration's decay factor (only the acceleration rows depend on it):
  // F(decay) = F(0) + decay (F(1) - F(0)); each mode decays with its own time constant.
  Filter::StateMatrix jacobian_kept;  // decay 1
  Filter::StateMatrix jacobian_lost;  // decay 0
  if (dt > 0) {
    step(filter_.state(), dt, nullptr, 1.0, nullptr, &jerk_noise);
    jerk_noise -= heading_noise(filter_.state(), dt, params_.angular_acceleration_stddev, turn_model_);
    angular_noise = heading_noise(filter_.state(), dt, 1.0, turn_model_);
    free_step(filter_.state(), dt, turn_model_, 1.0, &jacobian_kept);
    free_step(filter_.state(), dt, turn_model_, 0.0, &jacobian_lost);
  }
  std::array<double, kMaxModes> log_likelihood{};
  double best = -std::numeric_limits<double>::infinity();
  const std::size_t first_jerk_mode = params_.stationary_mode ? 1 : 0;
  for (std::size_t j = 0; j < n; ++j) {
    Filter& mode = modes_[j];
    Filter::StateMatrix fpft;
    if (j < first_jerk_mode) {
      // Stationary: the velocity and acceleration are zero (known: a tiny variance keeps S well posed),
      // the position drifts a little, the heading turns as in the others (robots turn on the spot).
      if (dt > 0) {
        State x = mode.state();
        x(2) = wrap(x(2) + dt * x(5));
        x.segment<2>(3).setZero();
        x.segment<2>(6).setZero();
        mode.mutable_state() = x;
        Filter::StateMatrix& p = mode.mutable_covariance();
        p.row(2) += dt * p.row(5);
        p.col(2) += dt * p.col(5);
        for (int k : {3, 4, 6, 7}) {
          p.row(k).setZero();
          p.col(k).setZero();
        }
        p += heading_noise(x, dt, params_.angular_acceleration_stddev, false);  // nothing else moves
        const double drift = params_.stationary_drift_stddev * params_.stationary_drift_stddev * dt;
        p(0, 0) += drift;
        p(1, 1) += drift;
        for (int k : {3, 4, 6, 7}) p(k, k) = 1e-8;
      }
      log_likelihood[j] = fuse(mode, innovation_of(mode, detection, lag));
      best = std::max(best, log_likelihood[j]);
      continue;
    }
    const double jerk = params_.mode_jerk_stddev[j - first_jerk_mode];
    const double angular = params_.mode_angular_acceleration_stddev[j - first_jerk_mode];
    const bool loosest = j + 1 == n;
    if (dt > 0) {
      const double decay = decay_over(dt, params_.mode_acceleration_time_constant[j - first_jerk_mode]);
      State x = free_step(mode.state(), dt, turn_model_, decay, nullptr);
      x(2) = wrap(x(2));
      mode.mutable_state() = x;
      // F = I + E with E non-zero only in columns 3-7 (in the free models nothing depends on position or
      // heading): F P F^T = G + G_{:,3:7} E_{:,3:7}^T with G = P + E_{:,3:7} P_{3:7,:}, 40 % fewer products.
      Filter::StateMatrix& p = mode.mutable_covariance();
      const Eigen::Matrix<double, 8, 5> e = jacobian_lost.rightCols<5>() +
                                            decay * (jacobian_kept.rightCols<5>() - jacobian_lost.rightCols<5>()) -
                                            Filter::StateMatrix::Identity().rightCols<5>();
      const Filter::StateMatrix g = p + e.lazyProduct(p.bottomRows<5>());
      p = g + g.rightCols<5>().lazyProduct(e.transpose());
      if (loosest) fpft = p;  // kept for a re-prediction
      p += jerk * jerk * jerk_noise + angular * angular * angular_noise;
    }
    Innovation innovation = innovation_of(mode, detection, lag);
    if (loosest && dt > 0 && innovation.mahalanobis2 > params_.maneuver_gate) {
      // A collision: the velocity changed at once somewhere in the step (an impulse of spread
      // collision_velocity_stddev at a uniform instant, not a lasting acceleration the velocity would
      // overshoot with), the robot may have been spun.
      Filter::StateMatrix& p = mode.mutable_covariance();
      p = fpft + jerk * jerk * jerk_noise + params_.maneuver_noise_scale * angular * angular * angular_noise;
      const double impulse = params_.collision_velocity_stddev * params_.collision_velocity_stddev;
      for (int i = 0; i < 2; ++i) {
        p(i, i) += dt * dt / 3 * impulse;
        p(i, i + 3) += dt / 2 * impulse;
        p(i + 3, i) += dt / 2 * impulse;
        p(i + 3, i + 3) += impulse;
      }
      innovation = innovation_of(mode, detection, lag);
    }
    log_likelihood[j] = fuse(mode, innovation);
    best = std::max(best, log_likelihood[j]);
  }
  double total = 0;
  for (std::size_t j = 0; j < n; ++j) {
    // A floor keeps every mode alive through out-of-order detections (no mixing when dt <= 0).
    mode_probability_[j] = std::max(1e-9, prior[j] * std::exp(log_likelihood[j] - best));
    total += mode_probability_[j];
  }
  for (std::size_t j = 0; j < n; ++j) mode_probability_[j] /= total;
  // The estimate: the probability-weighted mixture of the modes.
  const State reference = modes_[0].state();
  State mean = State::Zero();
  Filter::StateMatrix moment = Filter::StateMatrix::Zero();
  for (std::size_t j = 0; j < n; ++j) {
    const State d = difference(modes_[j].state(), reference);
    mean += mode_probability_[j] * d;
    moment += mode_probability_[j] * (modes_[j].covariance() + d.lazyProduct(d.transpose()));
  }
  State combined = reference + mean;
  combined(2) = wrap(combined(2));
  filter_.mutable_state() = combined;
  filter_.mutable_covariance() = moment - mean.lazyProduct(mean.transpose());
}

}  // namespace ssl::wm
