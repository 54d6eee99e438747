// CommandDelayEstimator: how long OUR robots take from a command being sent to moving by it, measured
// online from the commands we fuse and the motion vision shows (radio, firmware, motor response: what the
// robots of a real field, grSim or the simulator's robot response add).
//
// Model. A robot aims for the LOCAL velocity of the command sent `delay` seconds earlier, turned by its
// heading at that moment, and ramps towards it at max_acceleration (max_deceleration braking; a command older than command_timeout
// counts as stop). Every evaluation_period the last `window` seconds of each robot are replayed under every
// candidate delay on a grid (min_delay..max_delay by resolution), starting from the velocity vision
// measured at the window's start; the cost of a delay is the squared difference between the replayed
// velocity and the measured one (a least-squares line through the detections within velocity_span around
// each instant, every 10 ms), truncated at outlier_velocity so that a robot pushing a wall or another robot
// weighs the same under every delay. Robots whose motion hardly changed in the window tell nothing and are
// left out. Costs are summed over robots and kept with an exponential memory of `memory` seconds, so a
// changed delay is followed within a few seconds; the estimate is the minimum of the summed cost (refined
// between grid points by a parabola).
//
// A velocity that lags its set point (a first-order motor response) shows up as extra delay: the estimate
// is the one pure delay that best explains the motion, which is what the filter's command model and the
// planner's latency compensation need.
//
// Clock: the vision clock throughout (commands are stamped when sent, converted by the caller). Pure:
// no clocks or threads; allocates only when a robot appears.
//
//   CommandDelayEstimator delays(params);
//   delays.on_command(id, local_velocity, t_sent_vision);      // {forward, left}
//   delays.on_position(id, detection_position, heading, t_capture);
//   delays.update(t_capture);                        // evaluates when a period has passed
//   if (auto d = delays.delay()) use(*d);
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "libs/domain/world.h"
#include "libs/geometry/vec2.h"
#include "libs/time/time.h"

namespace ssl::wm {

struct CommandDelayParams {
  bool estimate = true;              // false: delay() stays nullopt (the configured delay is used)
  double min_delay = 0.0;            // s, candidate grid
  double max_delay = 0.2;            // s
  double resolution = 0.005;         // s between candidates
  double window = 1.0;               // s of motion replayed per evaluation
  double evaluation_period = 0.25;   // s between evaluations
  double memory = 3.0;               // s, time constant of the cost's exponential memory
  double velocity_span = 0.05;       // s of detections around an instant for its measured velocity
  double max_acceleration = 3.0;     // m/s^2, the replayed robot's ramp while its speed rises ...
  double max_deceleration = 4.0;     // m/s^2 ... and while it falls (the robots' limits)
  double command_timeout = 0.2;      // s: an older command counts as stop
  double min_excitation = 0.3;       // m/s: the measured velocity must change this much in a window
  double outlier_velocity = 0.5;     // m/s: a sample's error counts at most this much
  double min_weight = 50;            // samples (decayed) before an estimate is given
};

class CommandDelayEstimator {
 public:
  explicit CommandDelayEstimator(const CommandDelayParams& params = {});

  /// A command sent to robot `id` at t (vision clock): its linear velocity in the robot's frame (m/s,
  /// forward and left).
  void on_command(std::uint32_t id, const geom::Vec2& local_velocity, time::Timestamp t);
  /// Where vision saw robot `id` at its capture instant t, and its heading (rad, vision frame).
  void on_position(std::uint32_t id, const geom::Vec2& position, double heading, time::Timestamp t);
  /// Evaluates the window ending a little before t (the newest capture) when evaluation_period has passed.
  void update(time::Timestamp t);

  /// The estimated delay (s), once enough motion was seen.
  std::optional<double> delay() const { return delay_; }

 private:
  /// The delay of candidate i of the grid (s).
  double candidate(std::size_t i) const { return params_.min_delay + params_.resolution * static_cast<double>(i); }
  struct Command {
    time::Timestamp at;
    geom::Vec2 velocity;
  };
  struct Position {
    time::Timestamp at;
    geom::Vec2 position;
    double heading = 0;
  };
  struct Measured {
    geom::Vec2 velocity;
    double heading = 0;  // rad, of the detection nearest the instant
  };
  struct Robot {
    std::deque<Command> commands;
    std::deque<Position> positions;
  };

  /// Velocity measured around t (least squares over velocity_span), or nullopt with fewer than 3 detections.
  std::optional<Measured> measured(const Robot& robot, time::Timestamp t) const;
  /// The command in force at t (stop when none or too old); `next` carries the search between calls
  /// with rising t (start at 0).
  geom::Vec2 commanded(const Robot& robot, time::Timestamp t, std::size_t& next) const;
  /// Adds robot's window ending at `end` to `window_cost` (per candidate); returns the samples used.
  std::size_t evaluate(const Robot& robot, time::Timestamp end, std::vector<double>& window_cost) const;
  void forget_before(Robot& robot, time::Timestamp t) const;

  CommandDelayParams params_;
  std::array<Robot, kMaxRobotsPerTeam> robots_;
  std::vector<double> cost_;     // decayed sum per candidate
  double weight_ = 0;            // decayed samples
  std::optional<time::Timestamp> last_evaluation_;
  std::optional<double> delay_;
};

}  // namespace ssl::wm
