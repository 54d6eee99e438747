// VisionModel: turns the simulator's world snapshots into what SSL-Vision would send, camera by camera, in SI
// units on the SIMULATED clock. Pure: no sockets, threads, logging, globals or wall clock; time comes only
// from the snapshots and randomness only from one generator seeded in the constructor, so the same seed,
// config and snapshots always give the same frames (on this machine: libm's log/sin/cos could differ in the
// last bit elsewhere).
//
// Cameras. make_camera_layout() (camera.h) tiles the field incl. boundary; camera i captures at
// t0 + i / (rate * count) + k / rate (k = 0, 1, ...), where t0 is the first snapshot's time, so cameras are
// staggered evenly. A capture uses the first snapshot at or after its slot, and its capture_time is that
// snapshot's time (the instant the reported world really existed). If a step skips whole slots, the camera
// captures once and the skipped slots are counted (stats().capture_slots_skipped); frame numbers still
// increase by exactly 1 per frame.
//
// What a camera reports (see RealismConfig for the imperfections, applied in this order per detection:
// view check, occlusion, miss, position noise, orientation noise, confidence, then one false ball per frame,
// then the frame's delay jitter; random numbers are drawn only for enabled effects):
//   - robots whose centre lies in its view (tile + overlap): id, centre, orientation, the team's height;
//   - the ball, if in view: an airborne ball (z > radius) is projected along the camera ray onto the plane
//     z = ball radius, as ssl-vision does, and has no height (VisionConfig::report_ball_height to change);
//   - pixel coordinates: the reported point projected through the calibration this model publishes
//     (geometry()), so pixel_to_world(calibration, pixel, height) gives the reported position back.
//
// Time. A frame's sent_time = capture_time + vision_delay + U(0, processing_time_jitter), never earlier than
// the camera's previous frame (ssl-vision handles each camera in order). update() returns the frames whose
// sent_time <= snapshot.time, in send order. Snapshot times must not decrease; if they do (a simulator
// reset), pending frames are discarded and the camera schedule restarts at the new time.
//
//   VisionModel vision(FieldGeometry::division_a(), config, /*seed=*/7);
//   vision.set_robot_spec(TeamColor::kBlue, blue_spec);
//   for (each physics step) {
//     VisionOutput out = vision.update(physics.snapshot());
//     if (out.geometry_due) send(vision.geometry());
//     for (const DetectionFrame& frame : out.frames) send(frame);
//   }
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "libs/common/team.h"
#include "libs/time/time.h"
#include "services/simulator/core/types.h"
#include "services/simulator/core/vision/camera.h"
#include "services/simulator/core/vision/detection.h"
#include "services/simulator/core/vision/geometry.h"
#include "services/simulator/core/vision/random.h"
#include "services/simulator/core/vision/vision_config.h"

namespace ssl::sim {

/// Counters since construction (never reset).
struct VisionStats {
  std::uint64_t frames_captured = 0;
  std::uint64_t frames_sent = 0;            // returned by update()
  std::uint64_t frames_discarded = 0;       // pending when the snapshot time went backwards
  std::uint64_t capture_slots_skipped = 0;  // frame slots that passed within one physics step
  std::uint64_t ball_detections = 0;        // true ball detections in captured frames
  std::uint64_t robot_detections = 0;
  std::uint64_t balls_missed = 0;    // in view but dropped by ball_missing_probability
  std::uint64_t robots_missed = 0;   // in view but dropped by robot_missing_probability
  std::uint64_t balls_occluded = 0;  // in view but hidden by robots
  std::uint64_t false_balls = 0;     // spurious ball detections added

  friend bool operator==(const VisionStats&, const VisionStats&) = default;
};

/// The result of one update().
struct VisionOutput {
  std::vector<DetectionFrame> frames;  // send time has come; in send order
  // Send geometry() along with these frames: true with the first frames ever, after a change of field or
  // calibration, and after every config.geometry_every_frames sent frames. Never true without frames.
  bool geometry_due = false;
};

class VisionModel {
 public:
  /// Throws std::invalid_argument for an invalid config (VisionConfig::validate). Both teams start with the
  /// default RobotSpec. The per-camera calibration error directions are the first draws from `seed`.
  VisionModel(const FieldGeometry& field, const VisionConfig& config, std::uint64_t seed);

  /// Captures a frame for each camera whose slot has come (at most one per camera) from `snapshot`, and
  /// returns every frame whose send time is <= snapshot.time.
  VisionOutput update(const WorldSnapshot& snapshot);

  /// The published geometry: field, markings, the calibrations as the vision system believes them (with
  /// the drawn camera errors of the current realism) and the ball models.
  const GeometryData& geometry() const { return geometry_; }

  /// Replaces the realism at run time (effective from the next capture; frames already captured keep their
  /// send times). Throws std::invalid_argument for an invalid config and then changes nothing.
  void set_realism(const RealismConfig& realism);
  const RealismConfig& realism() const { return config_.realism; }

  /// Height (reported and used for occlusion), radius and dribbler distance (occlusion) of a team's robots.
  void set_robot_spec(TeamColor team, const RobotSpec& spec);

  /// Replaces the field (new tiling and geometry; camera schedules, frame numbers and errors are kept).
  void set_field(const FieldGeometry& field);

  const VisionConfig& config() const { return config_; }
  /// The cameras where they really hang, with their nominal calibrations, by camera id.
  std::vector<CameraView> cameras() const;
  const VisionStats& stats() const { return stats_; }
  /// Frames captured but not yet sent.
  std::size_t pending_frames() const { return pending_.size(); }
  /// The earliest simulated time at which update() will produce something (a capture or a send); the epoch
  /// before the first update().
  time::Timestamp next_event_time() const;

 private:
  struct Camera {
    CameraView view;                                         // true position, nominal calibration
    Vec3 error_direction = Vec3::UnitX();                    // unit, drawn once
    Vec3 believed_position = Vec3::Zero();                   // view.position + error
    CameraCalibration published;                             // calibration at believed_position
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // world -> camera
    time::Duration phase{0};                                 // offset of slot 0 from the anchor
    std::uint64_t next_slot = 0;                             // index k of the next capture slot
    std::uint32_t next_frame_number = 0;
    time::Timestamp last_sent;
  };
  struct TeamBody {
    double height = 0;
    double radius = 0;
    double center_to_dribbler = 0;
  };
  struct Occluder {
    Vec2 center = Vec2::Zero();
    Vec2 heading = Vec2::UnitX();
    double radius = 0;
    double height = 0;
    double front = 0;
  };
  struct Pending {
    DetectionFrame frame;
    std::uint64_t sequence = 0;  // capture order, breaks ties of equal send times
  };

  static TeamBody body_of(const RobotSpec& spec);
  void rebuild_cameras();
  void rebuild_geometry();
  time::Timestamp slot_time(const Camera& camera, std::uint64_t slot) const;
  void restart_schedule(time::Timestamp now);
  void capture(Camera& camera, const WorldSnapshot& snapshot);
  void detect_ball(const Camera& camera, const WorldSnapshot& snapshot, DetectionFrame& frame);
  void detect_robot(const Camera& camera, const RobotState& robot, DetectionFrame& frame);
  void add_false_ball(const Camera& camera, DetectionFrame& frame);
  // Fraction of the ball (a disc facing the camera) that robots leave visible, and the centre of the visible
  // part. Deterministic (no random draws).
  double ball_visibility(const Camera& camera, const Vec3& ball, const std::vector<RobotState>& robots,
                         Vec3& visible_center);
  // The point the camera's (mis)calibration reports for `point` on the plane z = plane_z.
  Vec3 believed_point(const Camera& camera, const Vec3& point, double plane_z) const;
  Eigen::Vector2d pixel_of(const Camera& camera, const Vec3& reported) const;
  float draw_confidence();
  const TeamBody& body(TeamColor team) const { return team == TeamColor::kBlue ? bodies_[0] : bodies_[1]; }

  FieldGeometry field_;
  VisionConfig config_;
  VisionRandom random_;
  std::vector<Camera> cameras_;
  std::array<TeamBody, 2> bodies_;  // blue, yellow
  GeometryData geometry_;
  std::vector<Pending> pending_;     // sorted by (sent_time, sequence)
  std::vector<Occluder> occluders_;  // scratch space of ball_visibility(), kept to avoid allocations
  VisionStats stats_;
  time::Timestamp anchor_;
  time::Timestamp last_time_;
  bool started_ = false;
  bool geometry_changed_ = true;  // geometry not yet sent since it last changed
  std::uint64_t frames_since_geometry_ = 0;
  std::uint64_t next_sequence_ = 0;
};

}  // namespace ssl::sim
