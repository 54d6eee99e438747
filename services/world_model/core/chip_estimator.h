// ChipEstimator: reconstructs the 3-D flight of a chip kick from SSL-Vision ball detections (one or several
// cameras), and predicts the ball over its bounces. Pure: no clocks, threads or allocation; time is an
// argument. Not yet wired into BallFilter / WorldModel (the owner of those does that).
//
// UNITS AND FRAMES. SI (m, m/s, m/s^2, s), SSL-Vision global frame, z up from the carpet; "position" and
// "height" are those of the ball's CENTRE, so a ball on the carpet has z = ball_radius.
// CLOCK. Every Timestamp here is on the VISION clock (capture times of detections, Unix ns).
//
// MEASUREMENT MODEL. SSL-Vision reports an airborne ball where the ray from the camera centre c through the
// ball centre b meets the plane z = ball_radius: the detection d = (d.x, d.y, ball_radius). The camera
// centre is the calibration's derived camera position (CameraInfo::position). d, c and b are collinear:
// (d - c) x (b - c) = 0, LINEAR in b. With H = c.z - ball_radius and u = d.xy - c.xy, two independent rows
// (the x and y rows of the cross product divided by -H; the z row is a combination of them) are
//     b.xy + (u / H) b.z = c.xy + (u / H) c.z,
// i.e. "b lies on the ray at its own height". Their residual, scaled by H / (c.z - b.z), is exactly the
// distance on the detection plane between d and the projection of b, where the detection noise lives.
//
// FLIGHT MODEL (no drag, no spin). With s = t - t_ref (seconds; t_ref = the kick time of reset(kick), else
// the first detection's capture time) the centre is
//     b.xy(s) = q + w s,    b.z(s) = a0 + a1 s - g s^2 / 2,
// which is LINEAR in theta = (q.x, q.y, w.x, w.y, a0, a1). Take-off t0 is where b.z rises through
// ball_radius (the earlier root), so t0 is estimated together with the rest, without a 1-D search, and the
// take-off velocity is (w, v_z), v_z = sqrt(a1^2 + 2 g (a0 - ball_radius)). fit() solves the linear
// least-squares problem (fixed-size 6x6 normal equations, Eigen, no allocation) for an initial theta, then
// refines it by Gauss-Newton on the exact detection-plane residuals, each weighted by its noise (so
// detections of several cameras, near and far from their nadir, count as they should).
//
// KICK PRIOR (reset(ChipKick)): soft rows b.xy(t_kick) = position and b.z(t_kick) = ball_radius (standard
// deviations from position_stddev, time_stddev and the current speed estimate); a one-sided row "rising at
// t_kick" (a1 >= 0 within g time_stddev; without it a parabola LANDING at t_kick fits as well); with a
// direction, w perpendicular to it (direction_stddev); with an elevation, v_z^2 = tan^2(elevation) |w|^2
// (a chip-only row: the flat hypothesis of classify() does not pay for it). Without any prior t_ref is the
// first detection and at least min_observations detections are needed.
//
// ONE CAMERA. A ball rising along a camera's ray does not move in its image, so early in the flight one
// camera cannot tell the vertical speed from the horizontal speed towards/away from its nadir; only
// second-order perspective effects separate them, and near the nadir hardly at all. With 3 mm noise at
// 75 Hz, after 10 detections the landing point is off by decimetres (tests: RMS 0.65 m with the ball
// filter's kick, 0.31 m with the kicker's heading, 0.18 m with heading and chip angle; ChipFit's covariance
// says as much), after 30 detections by centimetres. Two cameras (stereo: an overlap, or the real field's
// wider overlaps) give ~7 cm after 10 detections. Real ssl-vision setups differ only in the numbers.
//
// ONE FLIGHT. fit() fits the first flight: when the detections include later hops (the fit over all of them
// does not explain them, or some are after its landing + landing_guard + 3 landing_time_stddev), it finds
// the longest explained prefix in time (bisection) and fits the detections before that fit's landing
// (+ landing_guard); the rest stay stored. To track a later hop, reset() again with the landing as the
// kick. Add only detections captured AFTER the kick: before t0 the model has the ball on the carpet.
//
// CLASSIFICATION. classify() also fits the FLAT hypothesis on the same detections: the ball on the carpet
// (detections = its position) on a straight line, decelerating at a constant rate in
// [flat_min_deceleration, flat_max_deceleration] (sliding/rolling), with the same kick prior. It is a chip
// when the chip model explains the detections better by chip_chi2_margin (chi-square in units of the
// detection noise, divided by the fit's normalised_rms^2 when that is > 1), the take-off has
// min_chip_vz <= v_z and |v| <= max_chip_speed, the chip fit explains the detections (max_normalised_rms)
// and >= min_classify_observations are used. In the tests no flat kick was ever a chip (3 and 5 mm noise,
// up to 60 detections); two cameras classify typical chips after 5 detections, one camera after 7-12
// (median), up to ~28 for a chip flying straight over the camera's nadir (it looks like a sliding ball).
// Near the threshold the decision can flip back once; latch it if that matters.
//
// BOUNCES (ChipFit::state_at). Each touchdown multiplies the vertical speed by damping_z and the horizontal
// speed by damping_xy_first_hop (first touchdown) or damping_xy_other_hops (later ones), as ssl-vision's
// SSL_BallModelChipFixedLoss; a hop slower than min_hop_speed ends the hops and the ball rolls at
// roll_deceleration until it stops. Before t0 the ball lies at the origin, still.
//
// COST AND STATE. fit() is O(n) per Gauss-Newton pass over the n <= kMaxObservations detections (a linear
// solve and 1-4 passes; a retry from the previous fit's parameters when the result does not explain the
// detections; a bisection of ~log2(n) fits when detections after the landing first appear). Results are
// cached until the next add()/reset(); classify() adds an O(n) flat fit. Measured on a loaded 2-core VM:
// add() + classify() 8-12 us per detection at 10-40 detections, ~15-25 us per detection after the landing
// (one fit of all of them). Meant for the flight after a kick: once the chip has landed (or the ball is
// clearly rolling) stop feeding it. Not thread-safe (the cache is mutable).
//
//   ChipEstimator chip;
//   chip.reset(ChipKick{.position = kick.position, .time = kick.time, .direction = kicker_heading});
//   for (each ball detection d of camera c after the kick) chip.add({d, camera_position[c], t_capture});
//   ChipClassification result = chip.classify();
//   if (result.is_chip) { Vec3 p = result.chip->position_at(now_vision); ... }
#pragma once

#include <algorithm>
#include <array>
#include <optional>

#include <Eigen/Core>

#include "libs/domain/world.h"

namespace ssl::wm {

/// Bounce and roll model after the first touchdown (ssl-vision SSL_BallModelChipFixedLoss + rolling).
/// Defaults: the simulator's physics (ball_restitution_ground 0.5; a non-spinning ball loses 2/7 of its
/// horizontal speed at the first touchdown, then rolls).
struct ChipBounceModel {
  double gravity = 9.81;                  // m/s^2
  double ball_radius = 0.0215;            // m
  double damping_z = 0.5;                 // vertical speed factor at each touchdown, 0..1
  double damping_xy_first_hop = 0.71;     // horizontal speed factor at the first touchdown, 0..1
  double damping_xy_other_hops = 0.96;    // at later touchdowns, 0..1
  double min_hop_speed = 0.3;             // m/s: a hop leaving slower than this ends the hops (rolls)
  double roll_deceleration = 0.35;        // m/s^2 (positive) while rolling after the hops
  int max_hops = 16;                      // hops predicted at most
};

struct ChipParams {
  ChipBounceModel bounce;                  // also gives gravity and ball_radius to the fit
  double detection_stddev = 0.003;         // m, per axis on the detection plane (ChipObservation::stddev = 0)
  double prior_nominal_speed = 3.0;        // m/s, per component, to weight the prior before a first estimate
  double min_camera_height = 0.5;          // m above the ball plane; lower cameras are refused by add()
  int min_observations = 4;                // detections needed by fit(), with or without a prior
  double min_reciprocal_condition = 1e-13; // of the scaled normal matrix; below: degenerate, fit() = nullopt
  double landing_guard = 0.0;              // s: once later hops are seen, detections after landing + this
                                           // are not fitted
  int gauss_newton_iterations = 4;         // at most, after the linear solve
  // A fit explains its detections when sqrt(chi2 of the detections / (2 n)) <= this (1 = exactly the noise).
  double max_normalised_rms = 3.0;
  // Classification (classify()).
  double flat_min_deceleration = 0.0;      // m/s^2, flat hypothesis: deceleration along the line, >= this
  double flat_max_deceleration = 4.0;      // m/s^2, ... and <= this (sliding: ~3, rolling: ~0.35)
  // chi2(flat) - chi2(chip) needed to call it a chip, divided by the chip fit's normalised_rms^2 when that
  // is > 1 (noisier detections than assumed). Flat kicks at the assumed noise stay below ~9 (tests).
  double chip_chi2_margin = 16.0;
  double min_chip_vz = 0.8;                // m/s take-off vertical speed (apex >= ~3 cm above resting)
  double max_chip_speed = 8.0;             // m/s take-off speed; faster fits are noise (rules: 6.5 m/s)
  int min_classify_observations = 5;       // detections needed to call anything a chip
};

/// What is known about the kick that started the flight: a soft prior (see the header). The ball filter's
/// KickEvent gives position and time (its first post-kick detection: late by up to a frame). The kicking
/// robot's heading gives the direction, and for our own robots the commanded chip angle gives the
/// elevation: with one camera these make the early fit well-conditioned.
struct ChipKick {
  Vec2 position = Vec2::Zero();           // m, vision frame: where the ball left the carpet
  time::Timestamp time;                   // vision clock: when
  std::optional<Vec2> direction;          // horizontal kick direction (any length > 0), e.g. robot heading
  std::optional<double> elevation;        // rad above the carpet, in (0, pi/2): atan(v_z / |v_xy|)
  double position_stddev = 0.03;          // m per axis
  double time_stddev = 0.01;              // s
  double direction_stddev = 0.05;         // rad
  double elevation_stddev = 0.05;         // rad
};

/// One ball detection of one camera.
struct ChipObservation {
  Vec2 detection = Vec2::Zero();  // m, vision frame, on the plane z = ball_radius (as SSL-Vision reports)
  Vec3 camera = Vec3::Zero();     // m, vision frame: the centre of the camera that saw it
  time::Timestamp t_capture;      // vision clock
  double stddev = 0;              // m per axis on the detection plane; <= 0: ChipParams::detection_stddev
};

/// The ball along a reconstructed chip at one instant.
struct ChipState {
  enum class Phase { kBeforeKick, kAirborne, kRolling, kStopped };
  Vec3 position = Vec3::Zero();  // m, centre
  Vec3 velocity = Vec3::Zero();  // m/s
  Phase phase = Phase::kBeforeKick;
  int hop = 0;                   // 0: the kicked flight, 1: the first bounce, ...; hops made when rolling
};

/// A reconstructed flight: the kick and what follows from it.
struct ChipFit {
  Vec3 origin = Vec3::Zero();      // m, take-off point (z = ball_radius)
  Vec3 velocity = Vec3::Zero();    // m/s, take-off velocity (v.z >= 0)
  time::Timestamp t0;              // vision clock, take-off
  time::Timestamp apex_time;       // vision clock
  double apex_height = 0;          // m, highest centre height above the carpet (>= ball_radius)
  time::Timestamp landing_time;    // vision clock, first touchdown (== t0 when v.z == 0)
  Vec2 landing_point = Vec2::Zero();  // m, first touchdown
  double rms_residual_m = 0;       // m, RMS distance on the detection plane: detections vs fitted projection
  double normalised_rms = 0;       // sqrt(chi2 of the detections / (2 observations)); ~1: within the noise
  double chi2 = 0;                 // sum of squared normalised residuals, detections and prior rows
  int observations = 0;            // detections used (the first flight's), the earliest ones
  // Uncertainty from the assumed detection noise (not scaled by the residual), linearised.
  Eigen::Matrix3d velocity_covariance = Eigen::Matrix3d::Zero();  // (m/s)^2
  Eigen::Matrix2d landing_covariance = Eigen::Matrix2d::Zero();   // m^2
  double t0_stddev = 0;            // s
  double landing_time_stddev = 0;  // s
  ChipBounceModel bounce;          // used by state_at

  /// Position, velocity and phase at t (vision clock), over the bounces and the roll (see the header).
  ChipState state_at(time::Timestamp t) const;
  Vec3 position_at(time::Timestamp t) const { return state_at(t).position; }
  Vec3 velocity_at(time::Timestamp t) const { return state_at(t).velocity; }
};

/// The flat (ground) hypothesis of classify(): p(t) = origin + direction (speed s - deceleration s^2 / 2),
/// s = t - t_ref (not stopped at zero speed: the windows are short).
struct FlatFit {
  Vec2 origin = Vec2::Zero();     // m, at t_ref
  Vec2 direction = Vec2::UnitX();
  double speed = 0;               // m/s at t_ref
  double deceleration = 0;        // m/s^2, clamped to [flat_min_deceleration, flat_max_deceleration]
  double chi2 = 0;                // as ChipFit::chi2, with the xy and direction prior rows
  double rms_residual_m = 0;
};

struct ChipClassification {
  bool is_chip = false;
  std::optional<ChipFit> chip;    // nullopt: too few or degenerate detections
  std::optional<FlatFit> flat;    // on the same detections as `chip`
  double chi2_margin = 0;         // flat->chi2 - chip->chi2 (0 when either is missing)
};

class ChipEstimator {
 public:
  /// Detections kept per flight: 128 covers 0.85 s of flight seen by two cameras at 75 Hz; add() refuses
  /// more (the first flight is long determined by then).
  static constexpr int kMaxObservations = 128;

  explicit ChipEstimator(const ChipParams& params = {}) : params_(params) {}

  const ChipParams& params() const { return params_; }
  void set_params(const ChipParams& params) {
    params_ = params;
    cache_.valid = false;
  }

  /// Forgets every detection; no kick prior (t_ref = the first detection's capture time).
  void reset();
  /// Forgets every detection and sets the kick prior. Non-finite or non-positive values give no prior
  /// (position, stddevs) or no direction prior (direction).
  void reset(const ChipKick& kick);
  /// reset({.position = kick_position, .time = t_kick}) with the default stddevs.
  void reset(const Vec2& kick_position, time::Timestamp t_kick);

  /// Stores a detection (kept in capture-time order). false (and counted in refused()): non-finite values,
  /// a camera less than min_camera_height above the ball plane, or kMaxObservations already stored.
  bool add(const ChipObservation& observation);

  int size() const { return count_; }
  int refused() const { return refused_; }
  bool has_prior() const { return has_prior_; }

  /// The ballistic flight that best explains the stored detections (see the header), or nullopt when
  /// there are too few detections, they are degenerate (e.g. all at one instant without a prior, all at a
  /// camera's nadir), or the fitted ball would reach a camera's height. The result is cached until add()
  /// or reset(); detections appended after a segmented fit's landing leave it unchanged (cheap).
  std::optional<ChipFit> fit() const;

  /// fit() plus the flat hypothesis on the same detections and the decision.
  ChipClassification classify() const;
  bool is_chip() const { return classify().is_chip; }

 private:
  using Theta = Eigen::Matrix<double, 6, 1>;
  using Matrix6 = Eigen::Matrix<double, 6, 6>;

  struct Solution {
    Theta theta = Theta::Zero();
    Matrix6 covariance = Matrix6::Zero();
    double chi2 = 0;                 // detections and prior rows
    double chi2_detections = 0;
    double sum_squared_residual_m2 = 0;
    int used = 0;
  };
  struct PriorStddevs {
    double xy = 0;         // m, b.xy(t_kick)
    double z = 0;          // m, b.z(t_kick)
    double direction = 0;  // m/s, component of w across the kick direction
    double elevation = 0;  // (m/s)^2, of v_z^2 - tan^2(elevation) |w|^2
  };

  // The last fit_impl() result: valid for the first `count` detections as they were then.
  struct Cache {
    bool valid = false;
    int count = 0;
    int used = 0;
    std::optional<ChipFit> fit;
    bool has_flat = false;  // `flat` was computed for `fit`
    std::optional<FlatFit> flat;
    bool has_theta = false;  // the parameters of the last fit (a warm start), kept across add()
    Theta theta = Theta::Zero();
  };
  struct Fitted {
    ChipFit fit;
    Theta theta = Theta::Zero();
  };

  time::Timestamp t_ref() const { return has_prior_ ? kick_.time : t_first_; }
  double stddev_of(const ChipObservation& o) const {
    return o.stddev > 0 ? o.stddev : params_.detection_stddev;
  }
  PriorStddevs prior_stddevs(const Vec2& w, double a1, double vz2) const;
  // m/s: how far below 0 the vertical speed at the kick time may be (gravity over the time uncertainty).
  double vertical_speed_stddev() const { return params_.bounce.gravity * std::max(kick_.time_stddev, 1e-3); }
  // Least squares over the first n detections (capture-time order): a linear solve for a start, then
  // Gauss-Newton from a start.
  bool linear_init(int n, Theta& theta) const;
  std::optional<Solution> refine(int n, Theta theta) const;
  std::optional<Fitted> fit_first(int n, bool warm_start = true) const;
  time::Timestamp landed_after(const ChipFit& fit) const;
  bool consistent(const ChipFit& fit, int n) const;
  std::optional<ChipFit> fit_impl(int& used) const;  // cached
  std::optional<Fitted> fit_uncached(int& used) const;
  ChipFit make_fit(const Solution& solution) const;
  std::optional<FlatFit> fit_flat(int n, const PriorStddevs& prior) const;

  ChipParams params_;
  mutable Cache cache_;
  std::array<ChipObservation, kMaxObservations> observations_{};
  int count_ = 0;
  int refused_ = 0;
  bool has_prior_ = false;
  bool has_direction_ = false;
  bool has_elevation_ = false;
  double tan2_elevation_ = 0;
  ChipKick kick_;
  Vec2 kick_direction_ = Vec2::UnitX();  // unit
  Vec2 kick_normal_ = Vec2::Zero();      // unit, perpendicular to the kick direction
  time::Timestamp t_first_ = time::Timestamp::max();
};

}  // namespace ssl::wm
