// RobotFilter: one robot's track, a Kalman filter over [x, y, theta, vx, vy, omega] (m, rad, m/s, rad/s;
// VISION frame, vision clock) fed with that robot's detections from every camera. Like ER-Force's
// robotfilter, the velocity we COMMANDED (robot.commands, local frame) is the control input: the
// prediction ramps the velocity towards the commanded one at the robot's acceleration limit, so the
// filter follows turns without lag and can trust the model more (lower process noise) while commands
// are fresh. Without a command (enemy robots) it is a constant-velocity model with more process noise.
//
// Out-of-order measurements (cameras are staggered and their delays jitter) are fused without rewinding:
// a detection captured dt before the filter time is modelled as z = p - v dt (H = [I, -dt I]).
// Detections that fail the gate are outliers; two consecutive far detections that agree re-initialise the
// track (a teleport: robot placed by hand or by the simulator).
#pragma once

#include <optional>

#include "services/world_model/core/kalman_filter.h"
#include "services/world_model/core/types.h"

namespace ssl::wm {

struct RobotFilterParams {
  double position_stddev = 0.002;         // m, detection noise assumed (per axis)
  double orientation_stddev = 0.01;      // rad
  double acceleration_stddev = 2.0;       // m/s^2, process noise without a command
  double commanded_acceleration_stddev = 1.5;  // m/s^2, process noise while following a command
  double angular_acceleration_stddev = 10;     // rad/s^2
  double commanded_angular_acceleration_stddev = 20;  // rad/s^2
  double max_acceleration = 3.0;          // m/s^2, ramp towards the commanded velocity
  double max_angular_acceleration = 30;   // rad/s^2
  double command_timeout = 0.2;           // s, older commands are ignored
  double gate_distance = 0.3;             // m, beyond prediction + max speed * dt: teleport candidate
  double max_speed = 5.0;                 // m/s, physical limit used by the gate
  double maneuver_gate = 16;              // chi-square (3 dof): beyond it the step is re-predicted ...
  double maneuver_noise_scale = 50;       // ... with this many times the process noise variance
};

class RobotFilter {
 public:
  using Filter = KalmanFilter<6, 3>;
  using State = Filter::State;

  enum class UpdateResult { kFused, kOutlier, kTeleported };

  RobotFilter(const RobotFilterParams& params, const RobotDetection& detection, time::Timestamp t_capture);

  /// Sets the command we sent (vision-clock time it took effect) for this robot.
  void set_command(const RobotCommand& command, time::Timestamp t_vision) {
    command_ = command;
    command_time_ = t_vision;
  }

  /// Fuses one detection captured at t_capture (vision clock).
  UpdateResult update(const RobotDetection& detection, time::Timestamp t_capture);

  /// State predicted to t (vision clock) without changing the track.
  State predict_state(time::Timestamp t) const;

  time::Timestamp last_update() const { return last_update_; }
  time::Timestamp time() const { return time_; }
  const Filter& filter() const { return filter_; }

 private:
  void predict_to(Filter& filter, time::Timestamp from, time::Timestamp to) const;
  void set_prediction(Filter& filter, double dt) const;
  void reset(const RobotDetection& detection, time::Timestamp t_capture);
  void set_measurement(const RobotDetection& detection, double lag);
  Filter::Measurement measurement_innovation(const RobotDetection& detection) const;

  RobotFilterParams params_;
  Filter filter_;
  double noise_scale_ = 1;       // process noise variance factor of the current prediction
  time::Timestamp time_;         // vision clock of the filter state
  time::Timestamp last_update_;  // capture time of the last fused detection
  std::optional<RobotCommand> command_;
  time::Timestamp command_time_;
  std::optional<Vec2> teleport_candidate_;
  time::Timestamp teleport_candidate_time_;
};

}  // namespace ssl::wm
