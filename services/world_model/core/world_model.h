// WorldModel: the pure core of the world_model service. It fuses SSL-Vision detections of every camera
// into one track per robot (team + id) and one ball, keeps the referee's game state, the field, robot
// feedback and the commands we sent, and answers state(now): the world predicted to `now`, in the TEAM
// frame. No DDS, sockets, threads or clocks: every input carries its time and `now` is an argument, so
// the same inputs give the same outputs (replays, tests).
//
// Clocks. Detection times are on the vision clock; `now` is this host's wall clock. The offset
// (host - vision) is estimated as the smallest (now - sent_time) seen (the network delay is the only part
// not stamped by SSL-Vision), rising by offset_drift per frame, and by the rate at which the smallest sample
// of each second rose over the last one beyond 1 ms (up to vision_clock_slowness): a vision clock slower than
// this host's is followed (grSim stamps its simulated time, which falls behind the wall clock when grSim
// cannot keep real time: 2 % on a loaded 2-core machine), while a steady one keeps the smallest sample
// (the delivery jitter above it is not followed). state(now)
// predicts every track to now - offset: latency compensation of the vision processing delay and our own.
//
//   WorldModel model({.team = TeamColor::kBlue});
//   model.on_geometry(geometry);
//   model.on_referee(referee, now);
//   model.on_detection(frame, now);        // per camera frame
//   WorldState world = model.state(now);   // team frame, predicted to now
//
// Cost: on_detection allocates nothing (fixed arrays of filters); state() allocates its output vectors.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "services/world_model/core/ball_filter.h"
#include "services/world_model/core/camera_alignment.h"
#include "services/world_model/core/chip_estimator.h"
#include "services/world_model/core/command_delay.h"
#include "services/world_model/core/detection_noise.h"
#include "libs/domain/team_field.h"
#include "libs/domain/game_state.h"
#include "services/world_model/core/robot_filter.h"
#include "libs/domain/team_frame.h"
#include "libs/domain/world.h"

namespace ssl::wm {

struct WorldModelConfig {
  TeamColor team = TeamColor::kBlue;
  RobotFilterParams robot;
  BallFilterParams ball;
  BallModel ball_model;                 // replaced by the geometry's when it sends one
  double min_confidence = 0.1;          // detections below are ignored (counted)
  double robot_lost_timeout = 1.0;      // s without a detection: the track is dropped
  double ball_lost_timeout = 5.0;       // s without a detection: no ball
  double visible_timeout = 0.1;         // s: visible when seen this recently
  double feedback_timeout = 0.2;        // s: robot.feedback older than this is ignored
  double center_to_dribbler = 0.078;    // m, robot centre to its flat front
  double robot_radius = 0.09;           // m
  double possession_distance = 0.03;    // m, ball surface to dribbler: touching
  double near_robot_distance = 0.14;    // m, ball centre to robot centre: detection noise inflated
  double contact_margin = 0.03;         // m: robots closer than two radii plus this (or this close to a
                                        // wall) may be pushed: their filters do not trust the commands
  double dribbler_capture_distance = 0.1;  // m: a detection this close to a holding dribbler is used
  double offset_drift = 1e-5;           // s per frame the clock offset estimate may rise ...
  double vision_clock_slowness = 0.05;  // s per s ... and at most this fast with the measured rise (header)
  double carried_ball_after = 0.03;     // s without a ball detection (two camera frames): hidden ...
  double carried_ball_timeout = 1.0;    // s ... right after touching a dribbler: it moves with that robot
                                        // until this long without a detection
  double chip_window = 1.5;             // s after a kick during which a chip flight is looked for/tracked
  // Each camera's robot detection noise, estimated from its detections; the robot filters assume it
  // instead of robot.position_stddev / orientation_stddev once a camera has enough residuals.
  DetectionNoiseParams detection_noise;
  // Our robots' delay from command to motion, measured; once known it replaces robot.command_delay in the
  // filters and goes out with the state (the planner compensates it).
  CommandDelayParams command_delay;
  bool align_cameras = true;            // estimate and correct each camera's calibration error
  // Translation only by default: with well calibrated cameras the scale and rotation estimates add about
  // 1 mm of wandering correction (measured), more than they remove; enable them for a field whose camera
  // heights are off (a height error scales that camera's detections).
  CameraAlignmentParams camera_alignment = [] {
    CameraAlignmentParams params;
    params.estimate_scale = false;
    params.estimate_rotation = false;
    return params;
  }();
};

/// Counters since construction, for system.health.
struct WorldModelCounters {
  std::uint64_t frames = 0;
  std::uint64_t robot_detections = 0;
  std::uint64_t ball_detections = 0;
  std::uint64_t low_confidence = 0;
  std::uint64_t outliers_rejected = 0;
  std::uint64_t tracks_created = 0;
  std::uint64_t tracks_lost = 0;
  std::uint64_t teleports = 0;
  std::uint64_t kicks_detected = 0;
  std::uint64_t ball_restarts = 0;
  std::uint64_t dribbler_placements = 0;
  std::uint64_t chips_detected = 0;
};

class WorldModel {
 public:
  explicit WorldModel(const WorldModelConfig& config);

  /// One camera frame (vision frame, vision clock); `now` = host wall clock when it is processed.
  void on_detection(const DetectionFrame& frame, time::Timestamp now);
  void on_geometry(const Geometry& geometry);
  void on_referee(const RefereeInfo& referee, time::Timestamp now);
  /// Feedback of one of OUR robots.
  void on_feedback(const RobotFeedback& feedback, time::Timestamp now);
  /// The commands we sent to OUR robots (local frame), taken as in force from `now`.
  void on_commands(std::span<const RobotCommand> commands, time::Timestamp now);

  /// A run-time parameter change (same team): the thresholds read at every frame (confidence, possession,
  /// timeouts, distances) apply from the next frame; the filters' noise models stay as they started.
  void reconfigure(const WorldModelConfig& config);

  /// The world predicted to `now` (host wall clock), in the team frame.
  WorldState state(time::Timestamp now) const;
  /// The same, predicted to a vision-clock instant (tests, replays).
  WorldState state_at_vision_time(time::Timestamp t_vision) const;

  const WorldModelCounters& counters() const { return counters_; }
  const GameState& game_state() const { return game_; }
  const Field& field() const { return field_; }
  const TeamFrame& team_frame() const { return frame_; }
  /// Per-camera calibration error estimates (vision frame).
  const CameraAlignment& camera_alignment() const { return alignment_; }
  /// Per-camera robot detection noise estimates.
  const DetectionNoiseEstimator& detection_noise() const { return noise_; }
  /// The last kick, in the TEAM frame.
  std::optional<KickEvent> last_kick() const;
  /// Our robots' measured delay from command to motion (s), once known.
  std::optional<double> command_delay() const { return delays_.delay(); }
  /// Host wall clock minus vision clock, s (nullopt before the first frame).
  std::optional<double> clock_offset() const { return offset_; }
  /// Vision-clock capture time of the newest frame.
  time::Timestamp newest_capture() const { return stamp_.capture_time; }

 private:
  using Track = std::optional<RobotFilter>;
  using TeamTracks = std::array<Track, kMaxRobotsPerTeam>;

  static std::size_t team_index(TeamColor team) { return team == TeamColor::kBlue ? 0 : 1; }
  TeamTracks& tracks(TeamColor team) { return tracks_[team_index(team)]; }
  const TeamTracks& tracks(TeamColor team) const { return tracks_[team_index(team)]; }

  void update_robots(TeamColor team, std::uint32_t camera_id, std::span<const RobotDetection> detections,
                     time::Timestamp t);
  void update_ball(std::uint32_t camera_id, std::span<const BallDetection> detections, time::Timestamp t);
  void update_possession(time::Timestamp t);
  bool in_contact(TeamColor team, std::uint32_t id, const Vec2& position) const;
  void drop_lost_tracks(time::Timestamp t);
  std::optional<Vec2> held_ball_position(time::Timestamp t, std::uint32_t* holder, Vec2* velocity) const;
  Vec2 dribbler_point(const RobotFilter::State& x) const;
  struct RobotKey {
    TeamColor team = TeamColor::kBlue;
    std::uint32_t id = 0;
  };
  /// Every robot's dribbler point at the frame's capture instant t, once its robots are updated: the
  /// frame's ball checks below share them.
  void predict_dribblers(time::Timestamp t);
  /// The robot (either team) whose dribbler the ball at `ball` touches, if any (predict_dribblers first).
  std::optional<RobotKey> dribbler_touching(const Vec2& ball) const;
  void start_chip_tracking();
  /// Feeds a ball detection to the chip reconstruction; true while the ball is airborne (the ground
  /// filter must not take it), false otherwise.
  bool track_chip(std::uint32_t camera_id, const Vec2& detection, time::Timestamp t);
  /// Where camera `camera_id` sees the reconstructed flying ball at t, when one is in the air.
  std::optional<Vec2> chip_projection(std::uint32_t camera_id, time::Timestamp t) const;
  const Vec3* camera_position(std::uint32_t camera_id) const;

  // A chip flight after a kick: detections after the kick go to the estimator; once it says "chip" the
  // flight (3D) is the ball until it lands, then the ground filter continues from the landing.
  struct ChipTrack {
    ChipEstimator estimator;
    bool active = false;   // within chip_window after a kick
    bool latched = false;  // classified as a chip
    std::optional<ChipFit> fit;
    time::Timestamp kick_time;
    time::Timestamp last_update;
  };
  time::Timestamp to_vision(time::Timestamp now) const;
  /// One sample of (host - vision) clock, now - sent_time, at host time now (see the header's Clocks).
  void update_offset(double sample, time::Timestamp now);

  WorldModelConfig config_;
  Field field_;
  TeamFrame frame_;
  GameState game_;
  std::array<TeamTracks, 2> tracks_;  // blue, yellow
  std::array<std::array<std::optional<Vec2>, kMaxRobotsPerTeam>, 2> dribblers_;  // see predict_dribblers
  BallFilter ball_;
  CameraAlignment alignment_;
  DetectionNoiseEstimator noise_;
  CommandDelayEstimator delays_;
  std::optional<double> delay_in_filters_;  // the measured delay our filters were last given
  ChipTrack chip_;
  std::optional<RobotKey> carrier_;  // touching the ball at its last detection
  std::vector<CameraInfo> cameras_;  // from the geometry: camera centres for the chip reconstruction
  std::array<bool, kMaxRobotsPerTeam> ball_in_dribbler_{};
  std::array<time::Timestamp, kMaxRobotsPerTeam> feedback_time_{};                        // host clock
  std::optional<double> offset_;
  time::Timestamp offset_updated_;  // host clock of the frame that last updated offset_
  // The smallest sample of the current second and of the one before (host clock of their starts), and the
  // rate at which the offset rose between them (s/s, 0..vision_clock_slowness).
  struct OffsetWindow {
    time::Timestamp start;
    double smallest = 0;
  };
  OffsetWindow offset_window_;
  std::optional<OffsetWindow> last_offset_window_;
  double offset_rise_rate_ = 0;
  VisionStamp stamp_;
  Possession possession_ = Possession::kNone;
  std::optional<std::uint32_t> possessing_robot_;
  WorldModelCounters counters_;
};

}  // namespace ssl::wm
