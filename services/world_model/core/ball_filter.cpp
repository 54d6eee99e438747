#include "services/world_model/core/ball_filter.h"

#include <algorithm>
#include <cmath>

namespace ssl::wm {

void BallFilter::reset(const Vec2& position, const Vec2& velocity, time::Timestamp t, double velocity_var) {
  State x0;
  x0 << position.x(), position.y(), velocity.x(), velocity.y();
  Filter::StateMatrix p0 = Filter::StateMatrix::Zero();
  const double sp = params_.position_stddev;
  p0.diagonal() << sp * sp, sp * sp, velocity_var, velocity_var;
  filter_.reset(x0, p0);
  time_ = t;
  last_update_ = t;
  initialised_ = true;
  candidate_count_ = 0;
  pending_.active = false;
}

BallFilter::Motion BallFilter::advance(const Vec2& velocity, const Vec2& spin, double dt) const {
  Motion m{Vec2::Zero(), velocity, spin};
  if (dt <= 0) return m;
  const double slide = std::abs(model_.acc_slide);
  const double roll = std::abs(model_.acc_roll);
  // k_switch = 1 / (1 + k): the sliding friction spins the ball up at slide / k.
  const double k_switch = std::clamp(model_.k_switch, 0.05, 1.0);
  const double k = 1 / k_switch - 1;
  double left = dt;
  const Vec2 slip = m.velocity - m.spin;
  const double slip_speed = slip.norm();
  if (slip_speed > 1e-9 && slide > 0 && k > 1e-9) {
    // The slip shrinks along a fixed direction at slide * (1 + 1 / k) until the ball rolls.
    const Vec2 dir = slip / slip_speed;
    const double t_roll = slip_speed / (slide * (1 + 1 / k));
    const double t = std::min(left, t_roll);
    m.displacement += m.velocity * t - dir * (slide * t * t / 2);
    m.velocity -= dir * (slide * t);
    m.spin += dir * (slide / k * t);
    left -= t;
    if (t >= t_roll) m.spin = m.velocity;
  } else {
    m.spin = m.velocity;
  }
  if (left <= 0) return m;
  const double speed = m.velocity.norm();
  if (speed <= 1e-9) {
    m.velocity.setZero();
    m.spin.setZero();
    return m;
  }
  const Vec2 dir = m.velocity / speed;
  const double t = roll > 0 ? std::min(left, speed / roll) : left;
  m.displacement += dir * (speed * t - roll * t * t / 2);
  m.velocity = dir * std::max(0.0, speed - roll * t);
  m.spin = m.velocity;
  return m;
}

Vec2 BallFilter::set_prediction(Filter& filter, double dt) const {
  const State& x = filter.state();
  filter.F.setIdentity();
  filter.F(0, 2) = dt;
  filter.F(1, 3) = dt;
  const Vec2 v(x(2), x(3));
  const Motion m = advance(v, spin_, dt);
  const Vec2 dp = m.displacement - v * dt;
  const Vec2 dv = m.velocity - v;
  filter.u << dp.x(), dp.y(), dv.x(), dv.y();
  const double adt = std::abs(dt);
  const double var = params_.acceleration_stddev * params_.acceleration_stddev;
  filter.Q.setZero();
  for (int i = 0; i < 2; ++i) {
    filter.Q(i, i) = adt * adt * adt * adt / 4 * var;
    filter.Q(i, i + 2) = filter.Q(i + 2, i) = adt * adt * adt / 2 * var;
    filter.Q(i + 2, i + 2) = adt * adt * var;
  }
  return m.spin;
}

void BallFilter::predict_to(time::Timestamp t) {
  const double dt = time::to_seconds(t - time_);
  if (dt <= 0) return;
  spin_ = set_prediction(filter_, dt);
  filter_.predict(true);
  time_ = t;
}

BallFilter::State BallFilter::predict_state(time::Timestamp t) const {
  const double dt = time::to_seconds(t - time_);
  if (dt <= 0) {
    State x = filter_.state();
    x.head<2>() += dt * x.tail<2>();
    return x;
  }
  Filter copy = filter_;
  set_prediction(copy, dt);
  copy.predict(false);
  return copy.predicted_state();
}

double BallFilter::distance2(const Vec2& detection, time::Timestamp t_capture) const {
  if (!initialised_) return 0;
  return (detection - predict_state(t_capture).head<2>()).squaredNorm();
}

void BallFilter::place(const Vec2& position, const Vec2& velocity, time::Timestamp t) {
  reset(position, velocity, t, 0.01);
  spin_ = velocity;
}

void BallFilter::stop_at(const Vec2& position) {
  State& x = filter_.mutable_state();
  x << position.x(), position.y(), 0, 0;
  spin_.setZero();
}

BallFilter::LineFit BallFilter::fit_line(const Candidate* candidates, int n) {
  // Least-squares line p(t) = p0 + v (t - t0) through the candidates, t0 = the newest.
  LineFit fit;
  const time::Timestamp t0 = candidates[n - 1].time;
  double st = 0, stt = 0;
  Vec2 sp = Vec2::Zero(), stp = Vec2::Zero();
  for (int i = 0; i < n; ++i) {
    const double t = time::to_seconds(candidates[i].time - t0);
    st += t;
    stt += t * t;
    sp += candidates[i].position;
    stp += t * candidates[i].position;
  }
  const double denom = n * stt - st * st;
  if (denom > 1e-12) fit.velocity = (n * stp - st * sp) / denom;
  fit.position = (sp - fit.velocity * st) / n;
  // Residual of the line: a chip's projected detections curve away from it.
  for (int i = 0; i < n; ++i) {
    const Vec2 on_line = fit.position + fit.velocity * time::to_seconds(candidates[i].time - t0);
    fit.residual = std::max(fit.residual, (candidates[i].position - on_line).norm());
  }
  return fit;
}

BallFilter::UpdateResult BallFilter::restart_from_candidates() {
  const int n = candidate_count_;
  const LineFit fit = fit_line(candidates_.data(), n);
  const time::Timestamp t0 = candidates_[static_cast<std::size_t>(n - 1)].time;
  const double old_speed = initialised_ ? filter_.state().tail<2>().norm() : 0;
  const Vec2 old_position = filter_.state().head<2>();
  const time::Timestamp first_time = candidates_[0].time;
  const double speed = fit.velocity.norm();
  // Velocity uncertainty of a two-point difference: sqrt(2) sigma / dt.
  const double span = std::max(1e-3, time::to_seconds(t0 - first_time));
  const double sv = 2 * params_.position_stddev / span;
  const Vec2 old_spin = spin_;
  reset(fit.position, fit.velocity, t0, sv * sv + 0.05);
  if (speed - old_speed >= params_.kick_speed_increase) {
    spin_ = old_spin;  // a kick pushes at the equator: the ball slides
    KickEvent kick;
    kick.time = first_time;
    kick.detected_at = t0;
    kick.position = old_position;
    kick.velocity = fit.velocity;
    kick.speed = speed;
    kick.chip_suspected = n >= 3 && fit.residual > 4 * params_.position_stddev + 0.01;
    last_kick_ = kick;
    after_kick_count_ = 0;
    return UpdateResult::kKick;
  }
  spin_ = fit.velocity;  // unknown: assume it rolls
  return UpdateResult::kRestarted;
}

BallFilter::UpdateResult BallFilter::after_update(time::Timestamp t_capture, const Vec2& detection) {
  // Chip check: the detections after a kick should lie on a line (a decelerating one, close enough).
  if (last_kick_ && after_kick_count_ < static_cast<int>(after_kick_.size()) &&
      time::to_seconds(t_capture - last_kick_->detected_at) < 0.2) {
    after_kick_[static_cast<std::size_t>(after_kick_count_++)] = {detection, t_capture};
    if (after_kick_count_ >= 4) {
      const LineFit fit = fit_line(after_kick_.data(), after_kick_count_);
      if (fit.residual > 4 * params_.position_stddev + 0.01) last_kick_->chip_suspected = true;
    }
  }
  if (!pending_.active) return UpdateResult::kFused;
  ++pending_.updates;
  const Vec2 velocity = filter_.state().tail<2>();
  const double speed = velocity.norm();
  if (speed - pending_.speed_before >= params_.kick_speed_increase) {
    KickEvent kick;
    kick.time = pending_.time;
    kick.detected_at = t_capture;
    kick.position = pending_.position;
    kick.velocity = velocity;
    kick.speed = speed;
    last_kick_ = kick;
    after_kick_count_ = 0;
    pending_.active = false;
    return UpdateResult::kKick;
  }
  if (pending_.updates >= 3) pending_.active = false;
  return UpdateResult::kFused;
}

BallFilter::UpdateResult BallFilter::update(const Vec2& detection, time::Timestamp t_capture, bool near_robot) {
  if (!initialised_) {
    reset(detection, Vec2::Zero(), t_capture, 1.0);
    spin_.setZero();
    return UpdateResult::kInitialised;
  }
  const double dt = time::to_seconds(t_capture - time_);
  if (dt > 0) predict_to(t_capture);
  const double lag = std::min(0.0, dt);
  filter_.H.setZero();
  filter_.H(0, 0) = filter_.H(1, 1) = 1;
  filter_.H(0, 2) = filter_.H(1, 3) = lag;
  const double sp = near_robot ? params_.near_robot_position_stddev : params_.position_stddev;
  filter_.R = Filter::MeasurementCovariance::Identity() * (sp * sp);
  const Filter::Measurement y = filter_.innovation(detection);
  const double d2 = filter_.mahalanobis2(y);
  const Vec2 prior_velocity = filter_.state().tail<2>();
  const bool rolling = (prior_velocity - spin_).norm() < 1e-9;
  if (d2 <= params_.maneuver_mahalanobis2) {
    candidate_count_ = 0;
    filter_.update_with_innovation(y);
    // A rolling ball keeps rolling: the correction changes its spin with its velocity.
    if (rolling) spin_ = filter_.state().tail<2>();
    last_update_ = std::max(last_update_, t_capture);
    return after_update(t_capture, detection);
  }
  // Not explained by the model: a kick or a collision if the ball could have got there since it was last
  // seen, an outlier otherwise.
  const double since = std::clamp(time::to_seconds(t_capture - last_update_), 0.0, 0.1);
  const double reach = params_.max_ball_speed * since + params_.gate_min_distance;
  if (y.norm() <= reach || d2 <= params_.gate_mahalanobis2) {
    candidate_count_ = 0;
    if (!pending_.active) {
      pending_ = {.active = true, .time = t_capture, .position = filter_.state().head<2>(),
                  .speed_before = prior_velocity.norm(), .updates = 0};
    }
    // A velocity change dv since the last detection: the position moved by dv * tau, tau <= since.
    const double tau = std::max(since, 1e-3);
    const double sv2 = params_.maneuver_velocity_stddev * params_.maneuver_velocity_stddev;
    Filter::StateMatrix& p = filter_.mutable_covariance();
    for (int i = 0; i < 2; ++i) {
      p(i, i) += tau * tau * sv2;
      p(i, i + 2) += tau * sv2;
      p(i + 2, i) += tau * sv2;
      p(i + 2, i + 2) += sv2;
    }
    filter_.update_with_innovation(y);
    last_update_ = std::max(last_update_, t_capture);
    // tau was the longest lever: the change may be larger, let the next detection measure it.
    const double dv = (filter_.state().tail<2>() - prior_velocity).norm();
    const double extra = dv * dv + params_.maneuver_min_velocity_stddev * params_.maneuver_min_velocity_stddev;
    p(2, 2) += extra;
    p(3, 3) += extra;
    // The spin is kept (pushed at the equator): a kicked or bounced ball slides.
    if (pending_.updates == 0 && pending_.time == t_capture) return UpdateResult::kRestarted;
    const UpdateResult result = after_update(t_capture, detection);
    return result == UpdateResult::kKick ? result : UpdateResult::kRestarted;
  }
  // Beyond reach: an outlier unless it agrees with the previous ones.
  if (candidate_count_ > 0) {
    const Candidate& last = candidates_[static_cast<std::size_t>(candidate_count_ - 1)];
    const double agree = params_.max_ball_speed * std::abs(time::to_seconds(t_capture - last.time)) + 0.03;
    if ((detection - last.position).norm() > agree || t_capture <= last.time) candidate_count_ = 0;
  }
  if (candidate_count_ == static_cast<int>(candidates_.size())) candidate_count_ = 0;
  candidates_[static_cast<std::size_t>(candidate_count_++)] = {detection, t_capture};
  if (candidate_count_ >= params_.reinit_detections) return restart_from_candidates();
  return UpdateResult::kOutlier;
}

}  // namespace ssl::wm
