// BallFilter: the ball on the carpet, a Kalman filter over [x, y, vx, vy] (m, m/s; VISION frame, vision
// clock) whose prediction follows the physics behind the ssl-vision two-phase model. Besides its velocity
// v the ball has a spin, kept as the velocity s its rotation would give it on the carpet. While they differ
// the ball SLIDES: friction pulls v towards s at acc_slide and spins the ball up at acc_slide / k
// (k = 1 / k_switch - 1, the inertia factor); once they agree the ball ROLLS at acc_roll until it stops. A
// ball kicked from rest thus rolls from k_switch times the kick speed, as in ssl-vision; a ball kicked while
// rolling, or bounced off a robot against its own spin, follows the same law. The deceleration enters as a
// control input; the process noise is what the model does not explain, small because a ball on its own is
// very predictable.
//
// Kicks and collisions (no rewinding, fixed-size buffers, no allocation):
//  * a detection the model explains (Mahalanobis distance within maneuver_mahalanobis2) is fused;
//  * one it does not explain but that the ball could have reached (max_ball_speed since the last update)
//    is a MANEUVER: a velocity change of unknown size at an unknown instant since the last detection (its
//    covariance is added) and the detection is fused; the spin is kept (kicks and robot hulls push at the
//    ball's equator). If the speed after the next detection exceeds the speed before by kick_speed_increase,
//    it is a KICK: its time, place, speed and direction are reported (last_kick()).
//  * one beyond reach is an OUTLIER candidate (a false detection, a reflection, ...): it does not move the
//    ball. When the next failing detections agree with the candidates (reachable at max_ball_speed), the
//    ball really moved (teleported, put down by hand, lost track): the filter restarts from a straight-line
//    fit of those detections.
//  * near a robot the detection noise is inflated (the simulator and real cameras report a partly hidden
//    ball shifted).
// Occlusion: with no detection the state is simply predicted with the model (WorldModel stops it at robots).
// Chip kicks are flagged (not reconstructed) when the detections after a kick do not lie on a line; see
// README.
#pragma once

#include <array>
#include <optional>

#include "services/world_model/core/kalman_filter.h"
#include "libs/domain/world.h"

namespace ssl::wm {

struct BallFilterParams {
  double position_stddev = 0.003;            // m, detection noise assumed per axis
  double near_robot_position_stddev = 0.004; // m, when the ball is within near_robot_distance of a robot
  double acceleration_stddev = 0.1;          // m/s^2, process noise (unmodelled forces)
  double maneuver_mahalanobis2 = 16;         // chi-square (2 dof): beyond, a kick or collision
  double maneuver_velocity_stddev = 4.0;     // m/s, velocity change assumed at a maneuver
  double maneuver_min_velocity_stddev = 0.5; // m/s, velocity uncertainty left after a maneuver
  double gate_mahalanobis2 = 25;             // chi-square (2 dof): within, never an outlier
  double gate_min_distance = 0.02;           // m, margin of the reach beyond which detections are outliers
  double max_ball_speed = 10;                // m/s, bounds the reach and the candidates' agreement
  int reinit_detections = 2;                 // agreeing outliers that restart the filter
  double kick_speed_increase = 1.0;          // m/s, a maneuver that gains this much speed is a kick
  double stopped_speed = 0.02;               // m/s, below this the ball is at rest
};

struct KickEvent {
  time::Timestamp time;          // vision clock: capture time of the first detection after the kick
  time::Timestamp detected_at;   // vision clock: capture time of the detection that confirmed it
  Vec2 position = Vec2::Zero();  // m, vision frame, where the ball was when kicked
  Vec2 velocity = Vec2::Zero();  // m/s, vision frame, estimated kick velocity
  double speed = 0;              // m/s
  bool chip_suspected = false;   // the post-kick detections did not lie on a straight line
};

class BallFilter {
 public:
  using Filter = KalmanFilter<4, 2>;
  using State = Filter::State;

  enum class UpdateResult { kInitialised, kFused, kOutlier, kRestarted, kKick };

  BallFilter(const BallFilterParams& params, const BallModel& model) : params_(params), model_(model) {}

  void set_model(const BallModel& model) { model_ = model; }
  bool initialised() const { return initialised_; }

  /// Gate statistic of a detection against the prediction at t_capture (lower is better).
  double distance2(const Vec2& detection, time::Timestamp t_capture) const;

  /// Fuses one detection captured at t_capture (vision clock).
  UpdateResult update(const Vec2& detection, time::Timestamp t_capture, bool near_robot);

  /// Puts the ball somewhere (in a robot's dribbler), at t (vision clock).
  void place(const Vec2& position, const Vec2& velocity, time::Timestamp t);

  /// Stops the ball at a position (it ran into a robot while hidden).
  void stop_at(const Vec2& position);

  /// State predicted to t without changing the filter.
  State predict_state(time::Timestamp t) const;

  time::Timestamp time() const { return time_; }
  time::Timestamp last_update() const { return last_update_; }
  const std::optional<KickEvent>& last_kick() const { return last_kick_; }
  const Filter& filter() const { return filter_; }
  /// Rolling velocity of the ball's spin (equal to the velocity while it rolls), m/s.
  const Vec2& spin() const { return spin_; }

 private:
  struct Candidate {
    Vec2 position = Vec2::Zero();
    time::Timestamp time;
  };
  struct LineFit {
    Vec2 position = Vec2::Zero();  // at the newest candidate's time
    Vec2 velocity = Vec2::Zero();
    double residual = 0;           // m, largest distance of a candidate from the line
  };
  // Motion over dt under the carpet friction model, from velocity v and spin s.
  struct Motion {
    Vec2 displacement = Vec2::Zero();
    Vec2 velocity = Vec2::Zero();
    Vec2 spin = Vec2::Zero();
  };

  Motion advance(const Vec2& velocity, const Vec2& spin, double dt) const;
  Vec2 set_prediction(Filter& filter, double dt) const;  // returns the spin at the end
  void predict_to(time::Timestamp t);
  void reset(const Vec2& position, const Vec2& velocity, time::Timestamp t, double velocity_var);
  static LineFit fit_line(const Candidate* candidates, int n);
  UpdateResult restart_from_candidates();
  UpdateResult after_update(time::Timestamp t_capture, const Vec2& detection);

  BallFilterParams params_;
  BallModel model_;
  Filter filter_;
  bool initialised_ = false;
  time::Timestamp time_;
  time::Timestamp last_update_;
  Vec2 spin_ = Vec2::Zero();
  std::array<Candidate, 8> candidates_{};
  int candidate_count_ = 0;
  // A maneuver waiting for the next detection to tell whether it was a kick.
  struct PendingKick {
    bool active = false;
    time::Timestamp time;
    Vec2 position = Vec2::Zero();
    double speed_before = 0;
    int updates = 0;
  } pending_;
  // Detections since the last kick, for the chip check.
  std::array<Candidate, 8> after_kick_{};
  int after_kick_count_ = 0;
  std::optional<KickEvent> last_kick_;
};

}  // namespace ssl::wm
