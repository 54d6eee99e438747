// DetectionNoiseEstimator: how noisy each camera's robot detections really are, estimated from the
// detections alone (no ground truth), so that the robot filters weigh a detection by the noise its camera
// has rather than by the value the config assumes. Lighting, lens, height and calibration differ between
// fields and cameras; a filter told 2 mm that gets 4 mm follows the noise, one told 4 mm that gets 2 mm lags.
//
// Method: three consecutive detections of one robot by one camera (capture times t0 < t1 < t2, at most
// max_span apart). The middle one minus the straight line through the outer two at t1,
//   r = z1 - ((1 - f) z0 + f z2),  f = (t1 - t0) / (t2 - t0),
// has variance sigma^2 (1 + (1 - f)^2 + f^2) plus the motion the line does not follow: a / 2 (t1 - t0)
// (t2 - t1), 0.27 mm at 3 m/s^2 and 75 Hz, against sigma = 2 mm (1.6 % of the variance). The orientation
// alike, wrapped. Per axis, r / sqrt(1 + (1 - f)^2 + f^2) is then ~ N(0, sigma^2); sigma is estimated as
// sqrt(pi / 2) times an exponentially weighted mean of its absolute value, each sample clipped at
// clip_sigmas current sigmas (the configured noise before the first; a collision, a teleport or a mix-up
// is not noise). Clock: vision (capture).
//
// Pure: no clocks, threads or I/O. Units: m, rad, s.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "libs/domain/world.h"
#include "libs/time/time.h"

namespace ssl::wm {

/// The detection noise a filter assumes for one detection (standard deviations per axis).
struct DetectionNoise {
  double position_stddev = 0.002;   // m
  double orientation_stddev = 0.01;  // rad
};

struct DetectionNoiseParams {
  bool estimate = true;           // false: always the configured noise
  std::uint32_t min_samples = 100;  // residuals a camera needs before its estimate replaces the config's
  double memory = 0.998;          // per residual: weight of the past (~500 residuals, 1-3 s of one camera)
  double max_span = 0.05;         // s, the three detections of a residual lie within this
  double clip_sigmas = 4;         // a residual beyond this many current sigmas counts as this many
  double min_factor = 0.25;       // the estimate stays within these multiples of the configured noise
  double max_factor = 4;
};

class DetectionNoiseEstimator {
 public:
  DetectionNoiseEstimator(const DetectionNoiseParams& params, const DetectionNoise& configured);

  /// One robot detection of camera `camera_id` (before any calibration correction), capture time t.
  void observe(std::uint32_t camera_id, TeamColor team, const RobotDetection& detection, time::Timestamp t);

  /// The noise to assume for camera `camera_id`'s robot detections: its estimate once it has min_samples
  /// residuals (and estimation is on), else the configured noise.
  DetectionNoise noise(std::uint32_t camera_id) const;

  struct CameraEstimate {
    std::uint32_t camera_id = 0;
    std::uint64_t samples = 0;  // position residuals so far
    DetectionNoise noise;       // as noise() returns it
  };
  /// Every camera seen so far, by id.
  std::vector<CameraEstimate> estimates() const;

 private:
  struct Sample {
    time::Timestamp t;
    Vec2 position = Vec2::Zero();
    double orientation = 0;
    bool has_orientation = false;
  };
  struct History {  // one robot's last two detections by one camera, newest last
    std::array<Sample, 2> samples;
    std::uint32_t count = 0;
  };
  /// Exponentially weighted mean absolute normalised residual of one quantity (normalised by its weights,
  /// so the first samples are not pulled towards a start value); `fallback` until the first sample.
  struct Average {
    double weighted_sum = 0;
    double weight = 0;
    std::uint64_t samples = 0;
    double sigma(double fallback) const;
    void add(double normalised, double memory, double clip_sigmas, double fallback);
  };
  struct Camera {
    std::array<History, 2 * kMaxRobotsPerTeam> robots;  // blue ids, then yellow ids
    Average position;
    Average orientation;
  };

  DetectionNoiseParams params_;
  DetectionNoise configured_;
  std::map<std::uint32_t, Camera> cameras_;
};

}  // namespace ssl::wm
