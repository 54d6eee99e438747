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
//    state driven by white jerk that decays with a time constant (accelerations do not last).
//    The acceleration either stays in the field (a controller that re-aims the robot's velocity) or, once
//    its centripetal part omega x v is taken off, turns with the robot (it holds or smoothly changes a
//    LOCAL velocity command: then the velocity itself turns with the robot, and a heading that turns
//    unexpectedly turns the velocity with it, so the heading detections steer the velocity's direction).
//    The one under which the robot accelerates less (over motion_model_time_constant) is used: holding a
//    local velocity while turning at omega, a robot's field acceleration is omega |v| and nothing is left
//    in its own frame; driving straight while turning, it is the other way round. Both mean the same
//    state, so switching needs no conversion.
//    How hard the robot manoeuvres is not known either: an interacting multiple model (IMM) runs one
//    filter per jerk density (mode_jerk_stddev: e.g. cruising, steering, sprinting and braking; each
//    with its own angular acceleration and acceleration time constant), mixes them before each step
//    (Markov switching at mode_switch_rate) and weighs them by how well each predicted the detection.
//    A stationary mode (velocity zero, the position drifting a little) comes first: robots stand a lot
//    in a match. A robot that stands or glides gets the smoothing of a
//    near-constant model, one that brakes hard the agility of a loose one, without a compromise for both.
//  * CONTACT (the world model says a commanded robot touches another robot or a wall): forces we do not
//    know act on it, so commands are ignored, the velocity is constant and the process noise is higher.
//    Without a command contact changes nothing: the IMM's loose modes take the push.
//
// Out-of-order measurements (cameras are staggered and their delays jitter) are fused without rewinding:
// a detection captured dt before the filter time is modelled as z = p - v dt + a dt^2 / 2.
// Detections that fail the gate are outliers; two consecutive far detections that agree re-initialise the
// track (a teleport: robot placed by hand or by the simulator). Each detection is weighed with the noise of
// the camera that made it (DetectionNoise; default: position_stddev / orientation_stddev).
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "services/world_model/core/detection_noise.h"
#include "services/world_model/core/kalman_filter.h"
#include "libs/domain/world.h"

namespace ssl::wm {

struct RobotFilterParams {
  double position_stddev = 0.002;         // m, detection noise assumed (per axis) when update() is given none
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
  double maneuver_noise_scale = 50;       // ... with this many times the process noise variance (IMM:
                                          // the loosest mode's angular part) ...
  double collision_velocity_stddev = 0.6;  // m/s ... (IMM: the loosest mode) with a velocity impulse
  bool velocity_turns_with_robot = true;  // without a command, choose between a velocity (and acceleration)
                                          // that turns with the robot and a field one: the one under which
                                          // the robot recently accelerated less
  double motion_model_time_constant = 0.3;  // s, that comparison's memory
  double contact_acceleration_stddev = 4.0;  // m/s^2, process noise while touching a robot or a wall
  double contact_angular_acceleration_stddev = 30;  // rad/s^2
  // m/s^3 per sqrt(Hz): white jerk densities of the uncommanded model, one IMM mode each (1 to
  // kMaxJerkModes, ascending; one value and no stationary mode: a single filter).
  std::vector<double> mode_jerk_stddev = {0.3, 1.5, 12.0};
  // rad/s^2: each of those modes' white angular acceleration (as many values; a robot that drives smoothly
  // mostly turns smoothly too). The stationary mode and a single filter use angular_acceleration_stddev.
  std::vector<double> mode_angular_acceleration_stddev = {5, 10, 20};
  // s: each of those modes' acceleration time constant (as many values; 0: held): a cruising robot's
  // acceleration lasts, a braking or bumped one's does not. A single filter uses acceleration_time_constant.
  std::vector<double> mode_acceleration_time_constant = {1.0, 0.5, 0.3};
  bool stationary_mode = true;              // one more IMM mode: the robot stands (velocity zero) ...
  double stationary_drift_stddev = 0.0005;  // m per sqrt(s) ... its position drifts this much (pushed)
  double mode_switch_rate = 0.2;            // 1/s: expected switches between the modes
  double acceleration_time_constant = 0.5;  // s, without a command the acceleration decays so (0: held;
                                            // a single filter, the published prediction)
};

class RobotFilter {
 public:
  using Filter = KalmanFilter<8, 3>;
  using State = Filter::State;
  static constexpr std::size_t kMaxJerkModes = 4;              // IMM modes of the uncommanded model ...
  static constexpr std::size_t kMaxModes = kMaxJerkModes + 1;  // ... and the stationary one

  enum class UpdateResult { kFused, kOutlier, kTeleported };

  /// A new track at `detection`; `noise`: its camera's detection noise (default: the params').
  RobotFilter(const RobotFilterParams& params, const RobotDetection& detection, time::Timestamp t_capture,
              std::optional<DetectionNoise> noise = std::nullopt);

  /// Records a command we sent to this robot at t_vision (vision clock). The robot executes it from
  /// t_vision + command_delay until the next one; predictions over an interval use the commands in force
  /// piece by piece (a detection is captured ~15 ms before the newest command was sent).
  void set_command(const RobotCommand& command, time::Timestamp t_vision);
  /// The delay from sending to executing for commands recorded from now on (s >= 0; the measured one).
  void set_command_delay(double delay) { params_.command_delay = delay; }

  /// Fuses one detection captured at t_capture (vision clock). `in_contact`: the robot touches another
  /// robot or a wall, so forces we do not know act on it: the commanded velocity is not trusted for this
  /// step and the process noise is contact_*. `noise`: the detection's camera's noise (default: the params').
  UpdateResult update(const RobotDetection& detection, time::Timestamp t_capture, bool in_contact = false,
                      std::optional<DetectionNoise> noise = std::nullopt);

  /// State predicted to t (vision clock) without changing the track.
  State predict_state(time::Timestamp t) const;

  time::Timestamp last_update() const { return last_update_; }
  time::Timestamp time() const { return time_; }
  const Filter& filter() const { return filter_; }
  /// Uncommanded steps currently use the model whose velocity turns with the robot (else constant).
  bool uses_turning_model() const { return turn_model_; }
  /// IMM modes: the stationary one first (when enabled), then one per mode_jerk_stddev, ascending.
  std::size_t mode_count() const { return mode_count_; }
  /// Probability of IMM mode `mode` after the last uncommanded update.
  double mode_probability(std::size_t mode) const { return mode < mode_count_ ? mode_probability_[mode] : 0; }

 private:
  struct TimedCommand {
    RobotCommand command;
    time::Timestamp effective;  // vision clock: sent + command_delay
  };

  /// Commits the prediction of `filter` (whose state is at `from`) to `to`, command piece by piece;
  /// uncommanded pieces with white jerk density `jerk_stddev` (m/s^3/sqrt(Hz)).
  void predict_to(Filter& filter, time::Timestamp from, time::Timestamp to, double jerk_stddev) const;
  /// One prediction step of the motion model over dt > 0 with `command` (nullptr: none): returns f(x);
  /// its Jacobian and process noise (uncommanded: jerk density `jerk_stddev`) into `jacobian` and
  /// `noise` when given.
  State step(const State& x, double dt, const RobotCommand* command, double jerk_stddev,
             Filter::StateMatrix* jacobian, Filter::StateMatrix* noise) const;
  /// A detection against a filter's prediction: y, P H^T, S, S^-1 and y^T S^-1 y.
  struct Innovation {
    Filter::Measurement y;
    Eigen::Matrix<double, 8, 3> pht;
    Filter::MeasurementCovariance s;
    Filter::MeasurementCovariance s_inv;
    double mahalanobis2 = 0;
  };
  /// The detection against `filter`'s state `lag` (<= 0) seconds back.
  Innovation innovation_of(const Filter& filter, const RobotDetection& detection, double lag) const;
  /// The Kalman update with `innovation`; returns the log-likelihood of the detection (up to a constant).
  static double fuse(Filter& filter, const Innovation& innovation);
  /// Predicts `filter` from time_ to t_capture (when later) and fuses the detection; beyond maneuver_gate
  /// the prediction is redone with maneuver_noise_scale times the process noise.
  void predict_and_fuse(Filter& filter, const RobotDetection& detection, time::Timestamp t_capture,
                        double jerk_stddev);
  /// The IMM cycle over the uncommanded modes: mixing, each mode's prediction (one Jacobian for all) and
  /// update, the mode probabilities, and the combined estimate into filter_.
  void update_modes(const RobotDetection& detection, time::Timestamp t_capture);
  /// The uncommanded (Singer) step over dt > 0, the acceleration held in the field or, without its
  /// centripetal part, turning with the robot, `decay` of it left after dt; its Jacobian into `jacobian`
  /// when given.
  static State free_step(const State& x, double dt, bool turning, double decay, Filter::StateMatrix* jacobian);
  /// Process noise of a white angular acceleration (rad/s^2) over dt at state x, on the heading and turn
  /// rate; with `turning` also on what turns with them: the velocity and the acceleration.
  static Filter::StateMatrix heading_noise(const State& x, double dt, double angular_stddev, bool turning);
  /// The command in force at t, nullptr when none (never sent, expired, or in contact).
  const RobotCommand* command_at(time::Timestamp t) const;
  /// The first command change strictly inside (from, to), or `to`.
  time::Timestamp next_command_change(time::Timestamp from, time::Timestamp to) const;
  void reset(const RobotDetection& detection, time::Timestamp t_capture);
  /// Before an uncommanded step to t_capture: which of the two models the robot follows (see the header).
  void score_motion_models(time::Timestamp t_capture);

  RobotFilterParams params_;
  DetectionNoise noise_;         // of the detection being fused
  Filter filter_;                // the estimate (uncommanded: the IMM's combination of the modes)
  std::array<Filter, kMaxModes> modes_;               // uncommanded: one filter per mode
  std::array<double, kMaxModes> mode_probability_{};  // sums to 1 over the first mode_count_
  std::size_t mode_count_ = 1;
  bool modes_stale_ = true;      // filter_ moved without the modes (commanded step, reset): restart them
  double noise_scale_ = 1;       // process noise variance factor of the current prediction
  bool in_contact_ = false;      // touching a robot or a wall: commands are not trusted (see update())
  double turn_score_ = 0;        // smoothed |a - w J v|^2 - |a|^2 (m^2/s^4); < 0: turning model
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
