// BallFilter: the ball on the carpet, a Kalman filter over [x, y, vx, vy] (m, m/s; VISION frame, vision
// clock) whose prediction follows the ssl-vision straight two-phase model: a kicked ball SLIDES at
// acc_slide until its speed falls to k_switch times the kick speed, then ROLLS at acc_roll until it stops
// (the deceleration enters as a control input; the process noise is what the model does not explain).
//
// Gating and re-initialisation (no rewinding, fixed-size buffers, no allocation):
//  * the detection closest to the prediction is fused when its Mahalanobis distance passes the gate;
//  * one that fails is an OUTLIER candidate (a false detection, a reflection, ...): it does not move the
//    ball. When the next failing detections agree with the candidates (reachable at max_ball_speed), the
//    ball really changed its motion: the filter restarts from a straight-line fit of those detections
//    (positions, velocity). If the new speed exceeds the old by kick_speed_increase, it is a KICK: its time,
//    place, speed and direction are reported (last_kick()).
//  * near a robot the detection noise is inflated (the simulator and real cameras report a partly hidden
//    ball shifted).
// Occlusion: with no detection the state is simply predicted with the model (WorldModel stops it at robots).
// Chip kicks are flagged (not reconstructed) when the candidates do not lie on a line; see README.
#pragma once

#include <array>
#include <optional>

#include "services/world_model/core/kalman_filter.h"
#include "services/world_model/core/types.h"

namespace ssl::wm {

struct BallFilterParams {
  double position_stddev = 0.003;          // m, detection noise assumed per axis
  double near_robot_position_stddev = 0.02;  // m, when the ball is within near_robot_distance of a robot
  double acceleration_stddev = 0.3;        // m/s^2, process noise (unmodelled forces)
  double gate_mahalanobis2 = 25;           // chi-square (2 dof): ~5 sigma
  double gate_min_distance = 0.02;         // m, never gate closer than this
  double max_ball_speed = 10;              // m/s, candidates must be reachable from each other
  int reinit_detections = 2;               // agreeing gate failures that restart the filter
  double kick_speed_increase = 1.0;        // m/s, a restart that gains this much speed is a kick
  double stopped_speed = 0.02;             // m/s, below this the ball is at rest
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

 private:
  struct Candidate {
    Vec2 position = Vec2::Zero();
    time::Timestamp time;
  };

  void set_prediction(Filter& filter, double dt) const;
  void predict_to(time::Timestamp t);
  void reset(const Vec2& position, const Vec2& velocity, time::Timestamp t, double velocity_var);
  UpdateResult restart_from_candidates();

  BallFilterParams params_;
  BallModel model_;
  Filter filter_;
  bool initialised_ = false;
  time::Timestamp time_;
  time::Timestamp last_update_;
  double slide_until_speed_ = 0;  // m/s: slides while faster (k_switch * kick speed), 0 = rolling
  std::array<Candidate, 8> candidates_{};
  int candidate_count_ = 0;
  std::optional<KickEvent> last_kick_;
};

}  // namespace ssl::wm
