// RobotFilter: one robot's track, an extended Kalman filter over [x, y, theta, vx, vy, omega, ax, ay] (m,
// rad, m/s, rad/s, m/s^2; VISION frame, vision clock) fed with that robot's detections from every camera.
//
// Motion models (the prediction is an EKF step: F is the Jacobian of the model at the state):
//  * COMMANDED (our robots): the velocities we sent (robot.commands, local frame) are the control input.
//    The robot ramps its velocity towards the command turned by its heading, at its acceleration limit;
//    a reached command makes the old velocity irrelevant, so the filter trusts the model (low process
//    noise). Commands are kept with their times (a short history): a prediction over an interval uses,
//    piece by piece, the command that was in force, not the newest one (detections are ~15 ms older
//    than the newest command). The acceleration (ax, ay) is not part of this model (kept at 0, unknown).
//  * UNCOMMANDED (enemies, or no fresh command): a Singer model, the field acceleration (ax, ay) is a
//    state driven by white jerk that decays with acceleration_time_constant (accelerations do not last).
//    The acceleration either stays in the field (a controller that re-aims the robot's velocity) or, once
//    its centripetal part omega x v is taken off, turns with the robot (it holds or smoothly changes a
//    LOCAL velocity command: then the velocity itself turns with the robot); the one whose one-step
//    predictions recently matched the detections better is used. Both mean the same state, so switching
//    needs no conversion.
//  * CONTACT (the world model says the robot touches another robot or a wall): forces we do not know
//    act on it, so commands are ignored, the velocity is constant and the process noise is higher.
//
// Out-of-order measurements (cameras are staggered and their delays jitter) are fused without rewinding:
// a detection captured dt before the filter time is modelled as z = p - v dt + a dt^2 / 2.
// Detections that fail the gate are outliers; two consecutive far detections that agree re-initialise the
// track (a teleport: robot placed by hand or by the simulator).
#pragma once

#include <array>
#include <optional>

#include "services/world_model/core/kalman_filter.h"
#include "services/world_model/core/types.h"

namespace ssl::wm {

struct RobotFilterParams {
  double position_stddev = 0.002;         // m, detection noise assumed (per axis)
  double orientation_stddev = 0.01;      // rad
  double acceleration_stddev = 2.0;       // m/s^2, prior spread of the acceleration (ax, ay) when the
                                          // uncommanded model takes over (new track, after contact/commands)
  double commanded_acceleration_stddev = 1.5;  // m/s^2, process noise while following a command
  double angular_acceleration_stddev = 10;     // rad/s^2
  double commanded_angular_acceleration_stddev = 20;  // rad/s^2
  double max_acceleration = 3.0;          // m/s^2, ramp towards the commanded velocity
  double max_angular_acceleration = 30;   // rad/s^2
  double command_timeout = 0.2;           // s, a command is in force this long after it was sent
  double command_delay = 0;               // s, sent -> executed by the robot (radio + robot latency)
  double gate_distance = 0.3;             // m, beyond prediction + max speed * dt: teleport candidate
  double max_speed = 5.0;                 // m/s, physical limit used by the gate
  double maneuver_gate = 16;              // chi-square (3 dof): beyond it the step is re-predicted ...
  double maneuver_noise_scale = 50;       // ... with this many times the process noise variance
  bool velocity_turns_with_robot = true;  // without a command, choose between a velocity (and acceleration)
                                          // that turns with the robot and a field one by their recent errors
  double motion_model_memory = 0.95;      // per detection: weight of the past in that choice
  double contact_acceleration_stddev = 4.0;  // m/s^2, process noise while touching a robot or a wall
  double contact_angular_acceleration_stddev = 30;  // rad/s^2
  double jerk_stddev = 2.0;                 // m/s^3 per sqrt(Hz): white jerk density without a command
  double acceleration_time_constant = 0.5;  // s, without a command the acceleration decays so (0: held)
};

class RobotFilter {
 public:
  using Filter = KalmanFilter<8, 3>;
  using State = Filter::State;

  enum class UpdateResult { kFused, kOutlier, kTeleported };

  RobotFilter(const RobotFilterParams& params, const RobotDetection& detection, time::Timestamp t_capture);

  /// Records a command we sent to this robot at t_vision (vision clock). The robot executes it from
  /// t_vision + command_delay until the next one; predictions over an interval use the commands in force
  /// piece by piece (a detection is captured ~15 ms before the newest command was sent).
  void set_command(const RobotCommand& command, time::Timestamp t_vision);

  /// Fuses one detection captured at t_capture (vision clock). `in_contact`: the robot touches another
  /// robot or a wall, so forces we do not know act on it: the commanded velocity is not trusted for this
  /// step and the process noise is contact_*.
  UpdateResult update(const RobotDetection& detection, time::Timestamp t_capture, bool in_contact = false);

  /// State predicted to t (vision clock) without changing the track.
  State predict_state(time::Timestamp t) const;

  time::Timestamp last_update() const { return last_update_; }
  time::Timestamp time() const { return time_; }
  const Filter& filter() const { return filter_; }
  /// Uncommanded steps currently use the model whose velocity turns with the robot (else constant).
  bool uses_turning_model() const { return turn_model_; }

 private:
  struct TimedCommand {
    RobotCommand command;
    time::Timestamp effective;  // vision clock: sent + command_delay
  };

  /// Commits the prediction of `filter` (whose state is at `from`) to `to`, command piece by piece.
  void predict_to(Filter& filter, time::Timestamp from, time::Timestamp to) const;
  /// One prediction step of the motion model over dt > 0 with `command` (nullptr: none): returns f(x);
  /// its Jacobian and process noise into `jacobian` and `noise` when given.
  State step(const State& x, double dt, const RobotCommand* command, Filter::StateMatrix* jacobian,
             Filter::StateMatrix* noise) const;
  /// The uncommanded (Singer) step over dt > 0, the acceleration held in the field or, without its
  /// centripetal part, turning with the robot; its Jacobian into `jacobian` when given.
  State free_step(const State& x, double dt, bool turning, Filter::StateMatrix* jacobian) const;
  /// The command in force at t, nullptr when none (never sent, expired, or in contact).
  const RobotCommand* command_at(time::Timestamp t) const;
  /// The first command change strictly inside (from, to), or `to`.
  time::Timestamp next_command_change(time::Timestamp from, time::Timestamp to) const;
  void reset(const RobotDetection& detection, time::Timestamp t_capture);
  void score_motion_models(const RobotDetection& detection, double dt);
  void set_measurement(const RobotDetection& detection, double lag);
  Filter::Measurement measurement_innovation(const RobotDetection& detection) const;

  RobotFilterParams params_;
  Filter filter_;
  double noise_scale_ = 1;       // process noise variance factor of the current prediction
  bool in_contact_ = false;      // touching a robot or a wall: commands are not trusted (see update())
  double turn_score_ = 0;        // > 0: the constant-velocity model explained recent detections better
  bool turn_model_ = false;      // predict uncommanded steps with the turning-velocity model
  time::Timestamp time_;         // vision clock of the filter state
  time::Timestamp last_update_;  // capture time of the last fused detection
  static constexpr std::size_t kCommandHistory = 8;  // 80 ms at 100 Hz: covers the vision delay
  std::array<TimedCommand, kCommandHistory> commands_{};  // ring, oldest overwritten
  std::size_t command_count_ = 0;                        // commands ever recorded
  std::optional<Vec2> teleport_candidate_;
  time::Timestamp teleport_candidate_time_;
};

}  // namespace ssl::wm
