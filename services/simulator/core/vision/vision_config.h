// Configuration of the simulated SSL-Vision: the camera setup (VisionConfig) and the imperfections it adds
// to the true world (RealismConfig), with three named realism profiles. SI units throughout (m, rad, s);
// every field states its unit. Plain values: copy them, compare them, change them at run time through
// VisionModel::set_realism. validate() throws std::invalid_argument naming the first bad field.
//
//   VisionConfig config;                                 // 4 cameras at 75 Hz, 4 m high, no realism
//   config.realism = RealismConfig::realistic();
//   VisionModel vision(FieldGeometry::division_a(), config, /*seed=*/42);
//
// What a profile means and why its numbers were chosen is written next to each factory in vision_config.cpp
// and summarised here:
//
//   profile      noise ball/robot  heading   missed ball/robot  delay+jitter  occlusion  cam error  fake ball
//   none         0 / 0 mm          0 rad     0 / 0 %            0 + 0 ms      off        0 cm       0
//   realistic    3 / 2 mm          0.01 rad  3 / 2 %            12 + 3 ms     on (0.4)   0 cm       0
//   competition  5 / 4 mm          0.02 rad  8 / 5 %            20 + 8 ms     on (0.5)   2 cm       1 %/frame
#pragma once

#include <cstdint>

namespace ssl::sim {

/// What the simulated vision gets wrong. All zero / false = perfect vision (RealismConfig::none()).
/// Random quantities are drawn from the VisionModel's one seeded generator.
struct RealismConfig {
  double ball_position_stddev = 0;       // m, Gaussian noise added to the ball's x and y independently
  double robot_position_stddev = 0;      // m, Gaussian noise added to a robot's x and y independently
  double robot_orientation_stddev = 0;   // rad, Gaussian noise added to a robot's orientation
  double ball_missing_probability = 0;   // 0..1, chance that one camera's ball detection is dropped
  double robot_missing_probability = 0;  // 0..1, chance that one camera's robot detection is dropped
  double vision_delay = 0;               // s, t_sent - t_capture of every frame (processing time)
  double processing_time_jitter = 0;     // s, extra delay drawn uniformly from [0, this) per frame
  // Occlusion: the ball is sampled as a disc facing the camera; a sample is hidden when its sight line to
  // the camera passes through a robot's body (a cylinder of the team's radius and height, cut flat at the
  // dribbler). With less than `ball_visibility_threshold` of the disc visible the ball is not detected;
  // otherwise its position is the centre of the visible part (a partly hidden ball appears shifted).
  bool ball_occlusion = false;
  double ball_visibility_threshold = 0.4;  // 0..1, fraction of the ball that must be visible (ER-Force: 0.4)
  // Calibration error: each camera believes it hangs `camera_position_error` metres away from where it
  // really is (a fixed direction per camera, drawn once from the seed). Detections are computed with the
  // believed camera, so they shift by up to this much and objects in overlaps disagree between cameras.
  // NOTE: ER-Force's field of the same name moves only the camera used to project airborne balls, hence
  // its 0.25 m; ours moves every detection, so realistic values are centimetres.
  double camera_position_error = 0;        // m
  double false_ball_probability = 0;       // 0..1 per camera frame: one spurious ball somewhere in its view
  double false_ball_max_confidence = 0.5;  // 0..1, a false ball's confidence is uniform in [0, this)
  double confidence_spread = 0;            // 0..1, a true detection's confidence is uniform in (1 - this, 1]
  double ball_area_stddev = 0;             // px, Gaussian noise on the ball blob's pixel area

  /// Perfect vision: exact positions, every detection, no delay.
  static RealismConfig none();
  /// A good, well-calibrated lab setup (close to ER-Force's "Realistic" profile, delay as ssl-vision).
  static RealismConfig realistic();
  /// A real competition field: worse lighting and calibration, reflections, a loaded vision PC.
  static RealismConfig competition();

  /// Throws std::invalid_argument if a field is negative, NaN, or a probability is above 1.
  void validate() const;

  friend bool operator==(const RealismConfig&, const RealismConfig&) = default;
};

/// Ball motion models published with the geometry (SSL_GeometryModels), SI units. The defaults are the
/// ssl-vision defaults for the straight model and grSim's for the chip model; the physics owner should
/// set them to what its ball actually does.
struct BallModels {
  double acc_slide = -3.0;              // m/s^2, deceleration while sliding (negative)
  double acc_roll = -0.4;               // m/s^2, deceleration while rolling (negative)
  double k_switch = 0.7;                // fraction of the kick speed at which rolling starts
  double damping_xy_first_hop = 0.6;    // chip: horizontal speed factor at the first bounce
  double damping_xy_other_hops = 0.96;  // chip: horizontal speed factor at later bounces
  double damping_z = 0.42;              // chip: vertical speed factor at each bounce

  friend bool operator==(const BallModels&, const BallModels&) = default;
};

/// The camera installation. Cameras hang `camera_height` above the centres of an even grid of tiles that
/// covers the field including its boundary (1 = 1x1, 2 = 2x1, 4 = 2x2, 6 = 3x2, 8 = 4x2 tiles, columns along
/// x). Camera ids count along x first, from -x, then along y from -y. Each camera reports what lies in its
/// tile grown by `camera_overlap` on every side.
struct VisionConfig {
  int camera_count = 4;                      // 1, 2, 4, 6 or 8
  double frame_rate = 75;                    // Hz per camera; cameras are staggered by 1 / (rate * count)
  double camera_overlap = 0.3;               // m each camera sees beyond its tile
  double camera_height = 4.0;                // m above the carpet
  std::uint32_t geometry_every_frames = 75;  // geometry is due with the first frames and then after this
                                             // many sent frames (all cameras); 0 = only with the first
  std::uint32_t image_width = 2448;          // px (Basler acA2440-75uc, a common SSL camera at 75 Hz)
  std::uint32_t image_height = 2048;         // px
  double ball_radius = 0.0215;               // m, published and used for projection and occlusion
  double max_robot_radius = 0.09;            // m, published (rules: robots fit in a 0.18 m cylinder)
  // Ball detections carry no height, like real ssl-vision: an airborne ball is reported where the camera
  // ray through it meets the plane z = ball_radius. true: report the true x, y and z instead (has_z set).
  bool report_ball_height = false;
  BallModels ball_models;
  RealismConfig realism;

  /// Throws std::invalid_argument for an unsupported camera count, a non-positive frame rate, image size or
  /// ball radius, a negative overlap, a camera lower than 0.5 m, or an invalid realism config.
  void validate() const;
};

}  // namespace ssl::sim
