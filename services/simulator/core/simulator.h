// Simulator: a whole simulated SSL match as one pure, deterministic object: Bullet physics of the field,
// ball and robots (PhysicsWorld) plus the SSL-Vision model (VisionModel). No sockets, no threads, no wall
// clock: the caller feeds commands and steps simulated time, and gets back the vision frames that became
// due. The network server (services/simulator/adapter) and the in-process test harness both drive it.
//
//   ssl::sim::Simulator sim(options);                       // options.seed fixes every random draw
//   sim.set_commands(TeamColor::kBlue, {{3, command}});
//   auto out = sim.step(std::chrono::milliseconds(10));     // simulated time
//   for (const auto& frame : out.frames) publish(frame);    // metres, simulated clock
//
// Same options, same seed and the same calls in the same order give identical output.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "services/simulator/core/physics/physics_world.h"
#include "services/simulator/core/robot_response.h"
#include "services/simulator/core/types.h"
#include "services/simulator/core/vision/random.h"
#include "services/simulator/core/vision/vision_model.h"

namespace ssl::sim {

struct SimulatorOptions {
  FieldGeometry field = FieldGeometry::division_a();
  PhysicsParams physics;
  VisionConfig vision;
  RobotSpec blue_spec;
  RobotSpec yellow_spec;
  std::uint32_t robots_per_team = 11;  // placed in a kickoff formation at start, 0..16
  std::uint64_t seed = 1;
  // A robot whose last command is older than this (simulated time) is commanded to stop (no motion, no
  // dribbler, kicker disarmed), as real firmware stops a robot whose radio goes quiet; nullopt: never.
  std::optional<time::Duration> command_timeout;
  // How robots answer their commands: delay, loss, velocity lag, per-robot limits (robot_response.h).
  RobotResponse response;
};

/// An error answered to a simulation-protocol client: a machine-readable code and a message.
struct SimError {
  std::string code;
  std::string message;
};

/// Teleport of the ball; unset fields keep their current value (velocities default to 0 when the
/// position is set, as the protocol says).
struct BallTeleport {
  std::optional<double> x, y, z;       // m
  std::optional<double> vx, vy, vz;    // m/s
  bool teleport_safely = false;        // push robots out of the way
  bool roll = false;                   // start rolling (spin matched), not sliding
  bool by_force = false;               // unsupported: answered with an error
};

struct RobotTeleport {
  RobotKey key;
  std::optional<double> x, y;          // m
  std::optional<double> orientation;   // rad
  std::optional<double> vx, vy;        // m/s, global
  std::optional<double> angular;       // rad/s
  std::optional<bool> present;         // true: add the robot; false: remove it
  bool by_force = false;               // unsupported: answered with an error
};

/// One simulation-control request (the protocol's SimulatorCommand), converted from the wire.
struct ControlRequest {
  std::optional<BallTeleport> ball;
  std::vector<RobotTeleport> robots;
  std::optional<double> simulation_speed;        // factor of real time, for the real-time loop
  std::vector<std::pair<RobotKey, RobotSpec>> robot_specs;
  std::optional<RealismConfig> realism;
  std::optional<FieldGeometry> field;            // a new field: the world is rebuilt, robots kept
};

struct RobotCommandFor {
  std::uint32_t id = 0;
  RobotCommand command;
};

struct RobotFeedback {
  std::uint32_t id = 0;
  bool dribbler_ball_contact = false;
};

struct StepOutput {
  std::vector<DetectionFrame> frames;  // became due during the step, in send order
  bool geometry_due = false;           // a geometry packet should go out with these frames
};

class Simulator {
 public:
  explicit Simulator(const SimulatorOptions& options);

  /// Applies a control request; returns one error per part that could not be applied (the rest is).
  std::vector<SimError> apply(const ControlRequest& request);

  /// Sets the commands of some robots of `team`; errors name robots that are not on the field or
  /// commands with non-finite values (those are ignored).
  std::vector<SimError> set_commands(TeamColor team, const std::vector<RobotCommandFor>& commands);

  /// Changes how robots answer their commands from now on (commands in flight arrive as sent; each robot's
  /// limits are drawn again). Throws std::invalid_argument when the response is invalid.
  void set_response(const RobotResponse& response);

  /// Advances simulated time by `dt` (> 0) and returns the vision output that became due.
  StepOutput step(time::Duration dt);

  std::vector<RobotFeedback> feedback(TeamColor team) const;
  /// How many times a robot was stopped because its commands stopped (options.command_timeout).
  std::uint64_t command_timeouts() const { return command_timeouts_; }
  /// Commands lost on the way (options.response.command_loss).
  std::uint64_t commands_lost() const { return commands_lost_; }
  /// The world now; time on the simulated clock (continuous across field rebuilds).
  WorldSnapshot snapshot() const;
  /// The simulated clock alone (snapshot().time without building the snapshot).
  time::Timestamp time() const;
  const GeometryData& geometry() const { return vision_->geometry(); }
  const SimulatorOptions& options() const { return options_; }
  double simulation_speed() const { return simulation_speed_; }

 private:
  void place_initial_robots();
  void push_robots_away_from_ball();
  std::optional<SimError> apply_ball(const BallTeleport& teleport);
  std::optional<SimError> apply_robot(const RobotTeleport& teleport);
  void rebuild(const FieldGeometry& field);
  void stop_robots_without_commands();
  /// Gives `key` a command that reached it: at once, or as the set point its velocity lags behind.
  void act(RobotKey key, const RobotCommand& command);
  /// A command that keeps `key` moving as it does now (the start of a lagged set point).
  RobotCommand current_motion(RobotKey key, RobotCommand::Move move) const;
  /// Commands whose delay is over act; lagged set points move one sub-step of `h` seconds.
  void deliver_commands(double h);
  /// Scales the limits of a robot just added by its own factors (options.response.limit_spread).
  void vary_limits(RobotKey key);

  SimulatorOptions options_;
  // Held by pointer so that a new field geometry can rebuild them.
  std::unique_ptr<PhysicsWorld> physics_;
  std::unique_ptr<VisionModel> vision_;
  double simulation_speed_ = 1.0;
  time::Duration time_offset_{0};  // simulated time before the current physics world was built
  struct LastCommand {
    time::Timestamp at;    // simulated clock
    bool stopped = false;  // the timeout already stopped the robot
  };
  std::map<RobotKey, LastCommand> last_command_;
  std::uint64_t command_timeouts_ = 0;
  struct Responding {
    std::deque<std::pair<time::Timestamp, RobotCommand>> in_flight;  // sent; acts at the simulated time
    std::optional<RobotCommand> set_point;  // the last one that arrived (with a velocity lag)
    RobotCommand aimed;                     // set_point with the lagged velocities the motors aim for
  };
  std::map<RobotKey, Responding> responding_;
  VisionRandom response_random_;  // command loss: its own stream, so vision's draws do not change
  std::uint64_t commands_lost_ = 0;
};

}  // namespace ssl::sim
