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
}

void BallFilter::set_prediction(Filter& filter, double dt) const {
  const State& x = filter.state();
  filter.F.setIdentity();
  filter.F(0, 2) = dt;
  filter.F(1, 3) = dt;
  filter.u.setZero();
  const Vec2 v(x(2), x(3));
  const double speed = v.norm();
  if (speed > 1e-6 && dt > 0) {
    const double decel = speed > slide_until_speed_ ? -model_.acc_roll : -model_.acc_slide;
    const Vec2 dir = v / speed;
    const double t_stop = speed / decel;
    // Displacement along dir under constant deceleration, clipped where the ball stops.
    const double t_move = std::min(dt, t_stop);
    const double displacement = speed * t_move - decel * t_move * t_move / 2;
    const double speed_loss = decel * t_move;
    const Vec2 du = dir * (displacement - speed * dt);
    filter.u << du.x(), du.y(), -dir.x() * speed_loss, -dir.y() * speed_loss;
  }
  const double adt = std::abs(dt);
  const double var = params_.acceleration_stddev * params_.acceleration_stddev;
  filter.Q.setZero();
  for (int i = 0; i < 2; ++i) {
    filter.Q(i, i) = adt * adt * adt * adt / 4 * var;
    filter.Q(i, i + 2) = filter.Q(i + 2, i) = adt * adt * adt / 2 * var;
    filter.Q(i + 2, i + 2) = adt * adt * var;
  }
}

void BallFilter::predict_to(time::Timestamp t) {
  const double dt = time::to_seconds(t - time_);
  if (dt <= 0) return;
  set_prediction(filter_, dt);
  filter_.predict(true);
  time_ = t;
  // The sliding phase ends at k_switch of the kick speed; a stopped ball stays stopped.
  if (filter_.state().tail<2>().norm() <= slide_until_speed_) slide_until_speed_ = 0;
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
  slide_until_speed_ = 0;
}

void BallFilter::stop_at(const Vec2& position) {
  State& x = filter_.mutable_state();
  x << position.x(), position.y(), 0, 0;
}

BallFilter::UpdateResult BallFilter::restart_from_candidates() {
  // Least-squares line p(t) = p0 + v (t - t0) through the candidates.
  const int n = candidate_count_;
  const time::Timestamp t0 = candidates_[static_cast<std::size_t>(n - 1)].time;
  double st = 0, stt = 0;
  Vec2 sp = Vec2::Zero(), stp = Vec2::Zero();
  for (int i = 0; i < n; ++i) {
    const Candidate& c = candidates_[static_cast<std::size_t>(i)];
    const double t = time::to_seconds(c.time - t0);
    st += t;
    stt += t * t;
    sp += c.position;
    stp += t * c.position;
  }
  const double denom = n * stt - st * st;
  Vec2 velocity = Vec2::Zero();
  if (denom > 1e-12) velocity = (n * stp - st * sp) / denom;
  const Vec2 p0 = (sp - velocity * st) / n;
  // Residual of the line: a chip's projected detections curve away from it.
  double residual = 0;
  for (int i = 0; i < n; ++i) {
    const Candidate& c = candidates_[static_cast<std::size_t>(i)];
    residual = std::max(residual, (c.position - (p0 + velocity * time::to_seconds(c.time - t0))).norm());
  }
  const double old_speed = initialised_ ? filter_.state().tail<2>().norm() : 0;
  const time::Timestamp first_time = candidates_[0].time;
  const double speed = velocity.norm();
  // Velocity uncertainty of a two-point difference: sqrt(2) sigma / dt.
  const double span = std::max(1e-3, time::to_seconds(t0 - first_time));
  const double sv = 2 * params_.position_stddev / span;
  reset(p0, velocity, t0, sv * sv + 0.05);
  if (speed - old_speed >= params_.kick_speed_increase) {
    slide_until_speed_ = model_.k_switch * speed;
    KickEvent kick;
    kick.time = first_time;
    kick.detected_at = t0;
    kick.position = candidates_[0].position;
    kick.velocity = velocity;
    kick.speed = speed;
    kick.chip_suspected = n >= 3 && residual > 4 * params_.position_stddev + 0.01;
    last_kick_ = kick;
    return UpdateResult::kKick;
  }
  slide_until_speed_ = 0;
  return UpdateResult::kRestarted;
}

BallFilter::UpdateResult BallFilter::update(const Vec2& detection, time::Timestamp t_capture, bool near_robot) {
  if (!initialised_) {
    reset(detection, Vec2::Zero(), t_capture, 1.0);
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
  const bool in_gate =
      y.norm() <= params_.gate_min_distance || filter_.mahalanobis2(y) <= params_.gate_mahalanobis2;
  if (in_gate) {
    candidate_count_ = 0;
    filter_.update_with_innovation(y);
    last_update_ = std::max(last_update_, t_capture);
    return UpdateResult::kFused;
  }
  // Outside the gate: an outlier unless it agrees with the previous failures.
  if (candidate_count_ > 0) {
    const Candidate& last = candidates_[static_cast<std::size_t>(candidate_count_ - 1)];
    const double reach = params_.max_ball_speed * std::abs(time::to_seconds(t_capture - last.time)) + 0.03;
    if ((detection - last.position).norm() > reach || t_capture <= last.time) candidate_count_ = 0;
  }
  if (candidate_count_ == static_cast<int>(candidates_.size())) candidate_count_ = 0;
  candidates_[static_cast<std::size_t>(candidate_count_++)] = {detection, t_capture};
  if (candidate_count_ >= params_.reinit_detections) return restart_from_candidates();
  return UpdateResult::kOutlier;
}

}  // namespace ssl::wm
