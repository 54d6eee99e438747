#include "services/world_model/core/camera_alignment.h"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

namespace ssl::wm {
namespace {

constexpr int kP = CameraAlignment::kParams;
constexpr std::uint64_t kSymmetrizeEvery = 64;  // accepted pairs

Vec2 perp(const Vec2& v) { return {-v.y(), v.x()}; }

bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

}  // namespace

Vec2 CameraOffset::error_at(const Vec2& p) const {
  const Vec2 lever = has_center ? Vec2(p - center) : Vec2::Zero();
  return translation + scale * lever + rotation * perp(lever);
}

CameraAlignment::CameraAlignment(const CameraAlignmentParams& params) : params_(params) { reset(); }

void CameraAlignment::reset() {
  x_.setZero();
  p_.setZero();
  for (int i = 0; i < kStates; ++i) p_(i, i) = prior_variance(i % kP);
  t_filter_ = {};
  started_ = false;
  history_ = {};
  pairs_ = {};
  rejections_in_row_ = {};
  in_consensus_ = {};
  for (auto& r : relative_) r.setZero();
  consensus_dirty_ = true;
  counters_ = {};
  rebuild_consensus();
}

double CameraAlignment::prior_variance(int param) const {
  switch (param) {
    case 0:
    case 1: return params_.offset_prior * params_.offset_prior;
    case 2: return params_.estimate_scale ? params_.scale_prior * params_.scale_prior : 0.0;
    default: return params_.estimate_rotation ? params_.rotation_prior * params_.rotation_prior : 0.0;
  }
}

double CameraAlignment::drift_variance(int param) const {
  switch (param) {
    case 0:
    case 1: return params_.offset_drift * params_.offset_drift;
    case 2: return params_.scale_drift * params_.scale_drift;
    default: return params_.rotation_drift * params_.rotation_drift;
  }
}

void CameraAlignment::set_camera_centers(std::span<const CameraInfo> cameras) {
  for (const CameraInfo& c : cameras) set_camera_center(c.camera_id, Vec2(c.position.x(), c.position.y()));
}

void CameraAlignment::set_camera_center(std::uint32_t camera_id, const Vec2& center) {
  if (camera_id >= kMaxAlignmentCameras || !finite(center)) return;
  if (has_center_[camera_id] && (center - center_[camera_id]).norm() <= 1e-3) return;
  const bool moved = has_center_[camera_id];
  center_[camera_id] = center;
  has_center_[camera_id] = true;
  if (moved) {
    restart_camera(camera_id);
    ++counters_.camera_restarts;
  }
  consensus_dirty_ = true;
  update_consensus();
}

void CameraAlignment::restart_camera(std::uint32_t camera_id) {
  if (camera_id >= kMaxAlignmentCameras) return;
  const int i0 = static_cast<int>(camera_id) * kP;
  x_.segment<kP>(i0).setZero();
  p_.middleRows<kP>(i0).setZero();
  p_.middleCols<kP>(i0).setZero();
  for (int k = 0; k < kP; ++k) p_(i0 + k, i0 + k) = prior_variance(k);
  pairs_[camera_id] = 0;
  rejections_in_row_[camera_id] = 0;
  update_consensus();
}

std::size_t CameraAlignment::key_index(ObjectKey key) {
  switch (key.kind) {
    case ObjectKey::Kind::kBlueRobot: return key.id;
    case ObjectKey::Kind::kYellowRobot: return kMaxRobotsPerTeam + key.id;
    case ObjectKey::Kind::kBall: return 2 * kMaxRobotsPerTeam;
  }
  return kKeys;
}

void CameraAlignment::observe(std::uint32_t camera_id, ObjectKey key, const Vec2& position,
                              time::Timestamp t_capture) {
  ++counters_.observations;
  if (camera_id >= kMaxAlignmentCameras) {
    ++counters_.ignored_camera;
    return;
  }
  if (!finite(position)) {
    ++counters_.non_finite;
    return;
  }
  if (key.kind != ObjectKey::Kind::kBall && key.id >= kMaxRobotsPerTeam) {
    ++counters_.ignored_key;
    return;
  }
  const std::size_t k = key_index(key);
  History& own = history_[camera_id][k];
  if (own.count > 0 && t_capture < own.s[1].t) {
    ++counters_.out_of_order;
    return;
  }
  if (own.count > 0 && t_capture == own.s[1].t) {
    ++counters_.duplicates;  // two detections of one key in one frame: neither can be trusted
    own.count = 0;
    return;
  }
  const double stddev = key.kind == ObjectKey::Kind::kBall ? params_.ball_stddev : params_.robot_stddev;
  const double max_gap = params_.max_gap;
  if (!started_) {
    started_ = true;
    t_filter_ = t_capture;
  } else if (t_capture > t_filter_) {
    predict(t_capture);  // the filter's time is the newest capture time seen
  }

  for (std::uint32_t b = 0; b < kMaxAlignmentCameras; ++b) {
    if (b == camera_id) continue;
    const History& other = history_[b][k];
    if (other.count == 0) continue;
    const Sample& b1 = other.s[1];
    if (own.count > 0 && own.s[1].t <= b1.t && b1.t < t_capture &&
        time::to_seconds(t_capture - own.s[1].t) <= max_gap) {
      // b's detection lies between our previous and this one: interpolate ours to its time.
      const Sample& a1 = own.s[1];
      const double span = time::to_seconds(t_capture - a1.t);
      const double f = time::to_seconds(b1.t - a1.t) / span;
      const Vec2 pa = a1.p + f * (position - a1.p);
      pair(camera_id, b, pa, b1.p, (position - a1.p).norm() / span, stddev);
    } else if (b1.t == t_capture) {
      pair(camera_id, b, position, b1.p, 0.0, stddev);
    } else if (other.count == 2 && other.s[0].t < t_capture && t_capture < b1.t &&
               time::to_seconds(b1.t - other.s[0].t) <= max_gap) {
      // This detection lies between b's last two (b's frame came first): interpolate b's to our time.
      const Sample& b0 = other.s[0];
      const double span = time::to_seconds(b1.t - b0.t);
      const double f = time::to_seconds(t_capture - b0.t) / span;
      const Vec2 pb = b0.p + f * (b1.p - b0.p);
      pair(camera_id, b, position, pb, (b1.p - b0.p).norm() / span, stddev);
    }
  }
  if (own.count > 0) own.s[0] = own.s[1];
  own.s[1] = {t_capture, position};
  own.count = std::min(own.count + 1, 2);
}

void CameraAlignment::predict(time::Timestamp t) {
  const double dt = time::to_seconds(t - t_filter_);
  t_filter_ = t;
  if (!(dt > 0)) return;
  // Random walk, mean-reverting to the prior over 2 prior^2 / drift^2: x *= phi, P = Phi P Phi + Q.
  Eigen::Matrix<double, kP, 1> phi_param, q_param;
  for (int k = 0; k < kP; ++k) {
    const double prior = prior_variance(k);
    const double q = drift_variance(k) * dt;
    if (prior <= 0) {
      phi_param(k) = 0;
      q_param(k) = 0;
      continue;
    }
    phi_param(k) = std::exp(-0.5 * q / prior);
    q_param(k) = (1 - phi_param(k) * phi_param(k)) * prior;
  }
  State phi;
  for (int i = 0; i < kStates; ++i) phi(i) = phi_param(i % kP);
  x_.array() *= phi.array();
  p_ = phi.asDiagonal() * p_ * phi.asDiagonal();
  for (int i = 0; i < kStates; ++i) p_(i, i) += q_param(i % kP);
}

Eigen::Matrix<double, 2, CameraAlignment::kParams> CameraAlignment::jacobian(std::uint32_t camera,
                                                                              const Vec2& p) const {
  const Vec2 l = has_center_[camera] ? Vec2(p - center_[camera]) : Vec2::Zero();
  Eigen::Matrix<double, 2, kP> h;
  h << 1, 0, l.x(), -l.y(),  //
      0, 1, l.y(), l.x();
  return h;
}

void CameraAlignment::pair(std::uint32_t a, std::uint32_t b, const Vec2& pa, const Vec2& pb, double speed,
                           double stddev) {
  if (speed > params_.max_speed) {
    ++counters_.pairs_too_fast;
    return;
  }
  const int ia = static_cast<int>(a) * kP;
  const int ib = static_cast<int>(b) * kP;
  const Vec2 p = 0.5 * (pa + pb);
  const Eigen::Matrix<double, 2, kP> ha = jacobian(a, p);
  const Eigen::Matrix<double, 2, kP> hb = -jacobian(b, p);

  const Eigen::Matrix<double, kStates, 2> pht =
      p_.middleCols<kP>(ia) * ha.transpose() + p_.middleCols<kP>(ib) * hb.transpose();
  const double timing = speed * params_.time_stddev;
  const double r = 2 * (stddev * stddev + timing * timing);
  Eigen::Matrix2d s = ha * pht.middleRows<kP>(ia) + hb * pht.middleRows<kP>(ib);
  s(0, 0) += r;
  s(1, 1) += r;
  const Vec2 y = (pa - pb) - (ha * x_.segment<kP>(ia) + hb * x_.segment<kP>(ib));
  const Eigen::Matrix2d s_inv = s.inverse();
  const double chi2 = y.dot(s_inv * y);
  if (!(chi2 <= params_.gate_chi2)) {
    ++counters_.pairs_rejected;
    rejected(a);
    rejected(b);
    return;
  }
  const Eigen::Matrix<double, kStates, 2> gain = pht * s_inv;
  x_ += gain * y;
  p_.noalias() -= gain.lazyProduct(pht.transpose());  // rank 2: coefficient-wise, not a blocked gemm
  ++counters_.pairs_accepted;
  // The update keeps P symmetric up to rounding; restoring it exactly now and then is enough (a full
  // 32 x 32 pass per pair was a tenth of a whole lockstep match's time).
  if (counters_.pairs_accepted % kSymmetrizeEvery == 0) p_ = 0.5 * (p_ + p_.transpose()).eval();

  for (std::uint32_t c : {a, b}) {
    ++pairs_[c];
    rejections_in_row_[c] = 0;
    if (!in_consensus_[c] && pairs_[c] >= params_.min_pairs) {
      in_consensus_[c] = true;
      consensus_dirty_ = true;
    }
  }
  update_consensus();
}

void CameraAlignment::rejected(std::uint32_t camera) {
  if (++rejections_in_row_[camera] < params_.reset_after_rejections) return;
  restart_camera(camera);
  ++counters_.camera_restarts;
}

void CameraAlignment::rebuild_consensus() {
  consensus_dirty_ = false;
  int members = 0;
  bool centers = true;
  Vec2 mean_center = Vec2::Zero();
  for (std::uint32_t c = 0; c < kMaxAlignmentCameras; ++c) {
    if (!in_consensus_[c]) continue;
    ++members;
    centers = centers && has_center_[c];
    if (has_center_[c]) mean_center += center_[c];
  }
  const bool use_s = members > 0 && centers && params_.estimate_scale;
  const bool use_r = members > 0 && centers && params_.estimate_rotation;

  // The common similarity g = (T, S, R) with: S = mean scale, R = mean rotation, and T such that the mean
  // translation at the centres is zero after subtracting T + S c + R perp(c).
  consensus_a_.setZero();
  if (members > 0) {
    const double w = 1.0 / members;
    mean_center *= w;
    for (std::uint32_t c = 0; c < kMaxAlignmentCameras; ++c) {
      if (!in_consensus_[c]) continue;
      const int i0 = static_cast<int>(c) * kP;
      consensus_a_(0, i0) = w;
      consensus_a_(1, i0 + 1) = w;
      if (use_s) consensus_a_(2, i0 + 2) = w;
      if (use_r) consensus_a_(3, i0 + 3) = w;
    }
    // T = mean(t) - S mean(c) - R perp(mean(c)).
    consensus_a_.row(0) -= mean_center.x() * consensus_a_.row(2) - mean_center.y() * consensus_a_.row(3);
    consensus_a_.row(1) -= mean_center.y() * consensus_a_.row(2) + mean_center.x() * consensus_a_.row(3);
  }

  consensus_d_.setZero();
  for (std::uint32_t c = 0; c < kMaxAlignmentCameras; ++c) {
    const int i0 = static_cast<int>(c) * kP;
    const Vec2 cc = has_center_[c] ? center_[c] : Vec2::Zero();
    consensus_d_.block<4, 4>(i0, 0) << 1, 0, use_s ? cc.x() : 0, use_r ? -cc.y() : 0,  //
        0, 1, use_s ? cc.y() : 0, use_r ? cc.x() : 0,                                  //
        0, 0, (use_s && has_center_[c]) ? 1 : 0, 0,                                    //
        0, 0, 0, (use_r && has_center_[c]) ? 1 : 0;
  }
}

void CameraAlignment::update_consensus() {
  if (consensus_dirty_) rebuild_consensus();
  const Eigen::Vector4d common = consensus_a_ * x_;
  const State relative = x_ - consensus_d_ * common;
  for (std::uint32_t c = 0; c < kMaxAlignmentCameras; ++c) {
    relative_[c] = relative.segment<kP>(static_cast<int>(c) * kP);
  }
}

bool CameraAlignment::calibrated(std::uint32_t camera_id) const {
  return camera_id < kMaxAlignmentCameras && pairs_[camera_id] >= params_.min_pairs;
}

Vec2 CameraAlignment::correct(std::uint32_t camera_id, const Vec2& position) const {
  if (!calibrated(camera_id) || !finite(position)) return position;
  const Eigen::Vector4d& o = relative_[camera_id];
  const Vec2 l = has_center_[camera_id] ? Vec2(position - center_[camera_id]) : Vec2::Zero();
  return position - (Vec2(o(0), o(1)) + o(2) * l + o(3) * perp(l));
}

CameraOffset CameraAlignment::offset(std::uint32_t camera_id) const {
  CameraOffset out;
  if (camera_id >= kMaxAlignmentCameras) return out;
  const int i0 = static_cast<int>(camera_id) * kP;
  const Eigen::Vector4d& o = relative_[camera_id];
  out.calibrated = calibrated(camera_id);
  out.has_center = has_center_[camera_id];
  out.center = center_[camera_id];
  out.translation = Vec2(o(0), o(1));
  out.scale = o(2);
  out.rotation = o(3);
  out.pairs = pairs_[camera_id];
  // Covariance of relative = (E_c - D_c A) x.
  Eigen::Matrix<double, kP, kStates> m = -consensus_d_.middleRows<kP>(i0) * consensus_a_;
  m.middleCols<kP>(i0) += Eigen::Matrix4d::Identity();
  const Eigen::Matrix4d cov = m * p_ * m.transpose();
  out.translation_covariance = cov.topLeftCorner<2, 2>();
  const Eigen::Matrix2d& tc = out.translation_covariance;
  const double mean = 0.5 * (tc(0, 0) + tc(1, 1));
  const double half_diff = 0.5 * (tc(0, 0) - tc(1, 1));
  const double largest = mean + std::sqrt(half_diff * half_diff + tc(0, 1) * tc(0, 1));
  out.translation_stddev = std::sqrt(std::max(0.0, largest));
  out.scale_stddev = std::sqrt(std::max(0.0, cov(2, 2)));
  out.rotation_stddev = std::sqrt(std::max(0.0, cov(3, 3)));
  return out;
}

}  // namespace ssl::wm
