// CameraAlignment: online estimate of each camera's systematic calibration error from the objects that two
// cameras see at once (their overlaps), and the correction of detections by it. Pure: no clocks, threads,
// globals or allocation after construction (fixed arrays for up to kMaxAlignmentCameras cameras); time is
// the capture time passed in, on the vision clock.
//
// Model. Camera a reports an object at true position p as d = p + e_a(p) + noise, with the error field
//   e_a(p) = t_a + s_a (p - c_a) + r_a perp(p - c_a)
// t_a: translation (m) at the camera centre c_a (the calibration's derived_world, x/y); s_a: scale about the
// centre; r_a: small rotation about it (rad). A camera believed `delta` away from where it hangs shifts its
// detections by about delta_xy (t) and scales them by about delta_z / (height - object height) (s): with
// 2 cm errors and 4 m high cameras the scale alone moves a detection at the overlap (3 m from the centre)
// by up to 1.5 cm, so scale is on by default. Without a camera centre (set_camera_centers not called),
// that camera is modelled by t only.
//
// Pairs. Each observation of an object (team + id, or the ball) by camera a is compared with the latest
// detection of the same object by every other camera b at a different capture time by linear interpolation
// in time between two consecutive detections of one camera (a's previous and current one when b's lies in
// between, or b's two when a's lies between them; gaps <= max_gap), so moving objects pair without lag.
// The pair difference z = d_a - d_b = e_a(p) - e_b(p) + noise is linear in the parameters.
//
// Estimator. One joint Kalman filter over all cameras' parameters (8 x 4 = 32 states; a pair couples two
// cameras, so per-camera filters would be inconsistent). Each parameter follows a slow random walk
// (`*_drift`, the Kalman form of a forgetting factor: old pairs weigh less, slow drift is followed), made
// mean-reverting to the prior with a time constant of 2 prior^2 / drift^2 (~15 h for translations) so
// that the directions the pairs cannot see stay bounded. With the defaults a 15 mm jump is followed in
// ~3 s and a 1 mm/s drift with < 1 mm lag (camera_alignment_test). A pair whose innovation fails a
// chi-square gate is rejected; `reset_after_rejections` rejected pairs in a row of one camera (a bumped
// camera) restart its estimate from the prior. Cost: ~1k flops per observation (prediction), ~5k more
// per pair; nothing allocated.
//
// Frame (gauge). Pairs only see differences between cameras, so a common similarity (translation, scale,
// rotation) of all cameras is unobservable: the absolute frame is the cameras' consensus. Reported
// offsets are relative to it: over the cameras of the consensus set, the mean scale, the mean rotation and
// the mean translation at the camera centres are zero (the common similarity with those means is
// subtracted from every camera's estimate; only the mean translation when a member has no centre). The
// set holds every camera that has reached `min_pairs` pairs once (sticky, so a bumped or vanished camera
// does not shift the frame twice). With 2 cm errors in random directions the consensus is thus the mean of the cameras'
// errors (~1 cm / sqrt(cameras) from the true field frame), not the field lines, which no camera reports.
//
//   CameraAlignment align({});
//   align.set_camera_centers(geometry.cameras);                       // on each geometry (optional)
//   for (each robot detection d of frame f) align.observe(f.camera_id, ObjectKey::robot(team, d.id),
//                                                          d.position, f.capture_time);
//   Vec2 fixed = align.correct(f.camera_id, d.position);              // identity until calibrated
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include <Eigen/Core>

#include "libs/common/team.h"
#include "libs/domain/world.h"

namespace ssl::wm {

inline constexpr std::uint32_t kMaxAlignmentCameras = 8;  // camera ids 0..7; others are ignored (counted)

/// What was detected: a robot (team + pattern id) or the ball. Only detections of the same key are paired.
struct ObjectKey {
  enum class Kind : std::uint8_t { kBlueRobot, kYellowRobot, kBall };
  Kind kind = Kind::kBall;
  std::uint32_t id = 0;  // robot pattern id 0..kMaxRobotsPerTeam-1; 0 for the ball

  static constexpr ObjectKey robot(TeamColor team, std::uint32_t robot_id) {
    return {team == TeamColor::kBlue ? Kind::kBlueRobot : Kind::kYellowRobot, robot_id};
  }
  static constexpr ObjectKey ball() { return {Kind::kBall, 0}; }
};

struct CameraAlignmentParams {
  double robot_stddev = 0.004;        // m, robot detection noise per axis
  double ball_stddev = 0.006;         // m, ball detection noise per axis (occlusion shifts too)
  double time_stddev = 0.0005;        // s, capture-time uncertainty; adds speed * this to the noise
  double max_gap = 0.05;              // s, longest span between two detections interpolated between
  double max_speed = 3.0;             // m/s, faster objects are not paired (kicks, collisions)
  double gate_chi2 = 25.0;            // chi-square (2 dof) above which a pair is rejected
  std::uint32_t min_pairs = 150;      // pairs a camera needs (since its last restart) before correct()
                                      // applies its estimate
  std::uint32_t reset_after_rejections = 30;  // rejected pairs in a row: the camera's estimate restarts
  bool estimate_scale = true;         // per-camera scale about its centre (needs the centre)
  bool estimate_rotation = true;      // per-camera rotation about its centre (needs the centre)
  double offset_prior = 0.05;         // m, prior stddev of a translation
  double scale_prior = 0.01;          // prior stddev of a scale
  double rotation_prior = 0.01;       // rad, prior stddev of a rotation
  double offset_drift = 3e-4;         // m / sqrt(s): random walk of a translation
  double scale_drift = 1e-4;          // 1 / sqrt(s)
  double rotation_drift = 1e-4;       // rad / sqrt(s)
};

/// A camera's estimated error relative to the consensus frame: detection minus consensus position.
struct CameraOffset {
  bool calibrated = false;              // min_pairs reached since the last restart: correct() applies it
  bool has_center = false;              // scale / rotation are modelled
  Vec2 center = Vec2::Zero();           // m, camera centre (x, y) the scale / rotation turn about
  Vec2 translation = Vec2::Zero();      // m, error at the camera centre
  double scale = 0;                     // error = translation + scale (p - c) + rotation perp(p - c)
  double rotation = 0;                  // rad
  Eigen::Matrix2d translation_covariance = Eigen::Matrix2d::Zero();  // m^2, relative to the consensus
  double translation_stddev = 0;        // m, sqrt of the larger eigenvalue of the covariance
  double scale_stddev = 0;
  double rotation_stddev = 0;           // rad
  std::uint64_t pairs = 0;              // accepted pairs since the last restart

  /// The error at a point p (vision frame): subtract it from a detection at p to correct it.
  Vec2 error_at(const Vec2& p) const;
};

/// Counters since construction (or reset()).
struct CameraAlignmentCounters {
  std::uint64_t observations = 0;        // observe() calls
  std::uint64_t ignored_camera = 0;      // camera id >= kMaxAlignmentCameras
  std::uint64_t ignored_key = 0;         // robot id >= kMaxRobotsPerTeam
  std::uint64_t non_finite = 0;          // NaN / infinite position
  std::uint64_t out_of_order = 0;        // older than this camera's last detection of the object
  std::uint64_t duplicates = 0;          // same camera, object and capture time twice: both dropped
  std::uint64_t pairs_accepted = 0;
  std::uint64_t pairs_rejected = 0;      // failed the chi-square gate
  std::uint64_t pairs_too_fast = 0;      // object faster than max_speed
  std::uint64_t camera_restarts = 0;     // estimates restarted (rejections in a row, or a moved centre)
};

class CameraAlignment {
 public:
  static constexpr int kParams = 4;  // per camera: tx, ty, scale, rotation
  static constexpr int kStates = static_cast<int>(kMaxAlignmentCameras) * kParams;

  explicit CameraAlignment(const CameraAlignmentParams& params);

  /// Camera centres (x, y of CameraInfo::position) from the geometry. A camera whose centre moves by more
  /// than 1 mm (recalibrated) restarts its estimate. Cameras not listed keep what they had.
  void set_camera_centers(std::span<const CameraInfo> cameras);
  void set_camera_center(std::uint32_t camera_id, const Vec2& center);

  /// One detection of `key` by `camera_id` at `position` (vision frame, uncorrected), captured at
  /// `t_capture` (vision clock). Pass at most one detection per key and camera frame (for the ball: the
  /// one associated with the ball track, or none). Frames of one camera must come in capture order;
  /// cameras may interleave and be late relative to each other.
  void observe(std::uint32_t camera_id, ObjectKey key, const Vec2& position, time::Timestamp t_capture);

  /// The detection corrected to the consensus frame; unchanged until the camera is calibrated, for unknown
  /// cameras and for non-finite input.
  Vec2 correct(std::uint32_t camera_id, const Vec2& position) const;

  /// The camera's estimate (relative to the consensus); a default CameraOffset for unknown cameras.
  CameraOffset offset(std::uint32_t camera_id) const;
  bool calibrated(std::uint32_t camera_id) const;

  const CameraAlignmentCounters& counters() const { return counters_; }
  const CameraAlignmentParams& params() const { return params_; }

  /// Forgets everything but the parameters and the camera centres.
  void reset();
  /// Restarts one camera's estimate from the prior (e.g. after it was moved).
  void restart_camera(std::uint32_t camera_id);

 private:
  using State = Eigen::Matrix<double, kStates, 1>;
  using Covariance = Eigen::Matrix<double, kStates, kStates>;

  struct Sample {
    time::Timestamp t;
    Vec2 p = Vec2::Zero();
  };
  // The last two detections of one object by one camera (newest in [1]); count = how many are valid.
  struct History {
    std::array<Sample, 2> s;
    int count = 0;
  };
  static constexpr std::size_t kKeys = 2 * kMaxRobotsPerTeam + 1;

  static std::size_t key_index(ObjectKey key);
  void predict(time::Timestamp t);
  void pair(std::uint32_t a, std::uint32_t b, const Vec2& pa, const Vec2& pb, double speed, double stddev);
  void rejected(std::uint32_t camera);
  void update_consensus();
  void rebuild_consensus();
  Eigen::Matrix<double, 2, kParams> jacobian(std::uint32_t camera, const Vec2& p) const;
  double prior_variance(int param) const;
  double drift_variance(int param) const;

  CameraAlignmentParams params_;
  State x_;
  Covariance p_;
  time::Timestamp t_filter_;
  bool started_ = false;
  std::array<std::array<History, kKeys>, kMaxAlignmentCameras> history_{};
  std::array<Vec2, kMaxAlignmentCameras> center_{};
  std::array<bool, kMaxAlignmentCameras> has_center_{};
  std::array<std::uint64_t, kMaxAlignmentCameras> pairs_{};
  std::array<std::uint32_t, kMaxAlignmentCameras> rejections_in_row_{};
  std::array<bool, kMaxAlignmentCameras> in_consensus_{};
  // Estimates relative to the consensus (tx, ty, s, r per camera), refreshed after every accepted pair:
  // relative = x - consensus_d_ * (consensus_a_ * x), the common similarity (T, S, R) fitted to the
  // consensus cameras (consensus_a_, 4 x 32) turned into each camera's parameters (consensus_d_, 32 x 4).
  std::array<Eigen::Vector4d, kMaxAlignmentCameras> relative_{};
  Eigen::Matrix<double, kParams, kStates> consensus_a_;
  Eigen::Matrix<double, kStates, kParams> consensus_d_;
  bool consensus_dirty_ = true;
  CameraAlignmentCounters counters_;
};

}  // namespace ssl::wm
