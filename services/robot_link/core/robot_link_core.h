// ssl::robot_link_core: what robot_link sends to each robot in each packet (a "tick": one step per packet,
// whenever SendSchedule says one is due), as a pure function of its inputs. No DDS, sockets or threads;
// time is an argument (host MONOTONIC clock).
//
// Contract, checked in this order for every robot on every tick (the first that applies wins):
//   1. E-stop engaged (system.estop, latched by EstopLatch): every robot gets a stop.
//   2. Referee HALT: every robot gets a stop, whatever the planner says.
//   3. Watchdog: a robot whose newest command is older than `command_timeout` (default 100 ms; exactly
//      100 ms is still fresh) gets a stop: zero velocity, dribbler and kicker off.
//   4. Startup: for `startup_stop` after the first tick, every robot id 0..15 not yet commanded gets a
//      stop, so robots left moving by a previous robot_link instance halt even if no planner runs.
//   5. Otherwise the robot's newest command, made safe: non-finite values become 0, speeds are scaled
//      down to the robot spec's limits (linear speed keeps its direction), the velocity change per tick
//      is limited by the spec's speed-up / brake accelerations, kick speed, chip angle and dribbler
//      speed are clamped to their limits. Every value changed by clamping is counted.
// A stop is sent as exactly zero (no deceleration ramp: the robot's own controller brakes), and the
// acceleration limiter restarts from zero afterwards. Robots appear in the output once they were
// commanded (or during the startup window) and stay in it, receiving stops while stale.
//
//   RobotLinkCore core(CoreConfig{.limits = limits});
//   CommandTable table;
//   table.update(commands, now_mono);                      // on every robot.commands sample
//   EstopLatch estop;
//   estop.on_sample(true, "console", "robot on fire");    // on every system.estop sample
//   TickOutput out = core.step({.latest = table.latest(), .halt = halt, .estop_engaged = estop.engaged()},
//                              now_mono);                  // per packet (SendSchedule)
//   backend.send(out.commands);
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "libs/common/result.h"
#include "libs/time/time.h"
#include "services/robot_link/core/types.h"

namespace ssl::robot_link {

/// A robot's limits (the simulation protocol's RobotSpecs / RobotLimits names), all positive.
struct RobotLimits {
  double vel_absolute_max = 3;          // m/s, linear speed
  double vel_angular_max = 10;          // rad/s
  double acc_speedup_absolute_max = 3;  // m/s^2
  double acc_brake_absolute_max = 4;    // m/s^2
  double acc_speedup_angular_max = 30;  // rad/s^2
  double acc_brake_angular_max = 30;    // rad/s^2
  double max_linear_kick_speed = 6.5;   // m/s (the rules allow 6.5)
  double max_chip_kick_speed = 6.5;     // m/s
  double max_chip_angle = 1.2;          // rad above the carpet
  double max_dribbler_rpm = 20000;      // rpm
};

struct CoreConfig {
  RobotLimits limits;
  time::Duration command_timeout = std::chrono::milliseconds(100);  // watchdog: older commands stop
  time::Duration send_period = std::chrono::milliseconds(10);       // the radio's period (100 Hz): SendSchedule
  time::Duration startup_stop = std::chrono::milliseconds(500);     // stop uncommanded ids this long
};

/// Checks a config (positive limits and periods); the error names the field.
Status validate(const CoreConfig& config);

/// The newest command per robot with its receive time. Not thread-safe (the adapter guards it).
class CommandTable {
 public:
  /// Stores every command of one robot.commands sample, received at `received_mono`. Ids >= kMaxRobots
  /// are dropped and counted; a robot listed twice keeps its last entry.
  void update(std::span<const RobotCommand> commands, time::Timestamp received_mono);

  /// Newest command of every robot seen so far, ordered by id.
  std::span<const TimedCommand> latest() const noexcept { return entries_; }

  std::uint64_t samples() const noexcept { return samples_; }                // update() calls
  std::uint64_t robot_commands() const noexcept { return robot_commands_; }  // commands stored
  std::uint64_t invalid_ids() const noexcept { return invalid_ids_; }

 private:
  std::vector<TimedCommand> entries_;  // sorted by command.id, unique
  std::uint64_t samples_ = 0;
  std::uint64_t robot_commands_ = 0;
  std::uint64_t invalid_ids_ = 0;
};

/// The e-stop state, latched: once engaged it stays engaged until an explicit release (a sample with
/// engaged = false, from any source). Losing every e-stop writer (DDS liveliness) while engaged keeps it
/// engaged; new robot commands never release it. Initially released (no e-stop source at all must not
/// prevent a match from running).
class EstopLatch {
 public:
  /// A system.estop sample or a reading of a local e-stop device.
  void on_sample(bool engaged, std::string source, std::string reason);

  /// An e-stop writer lost its liveliness (crashed, unplugged, network cut). The state is kept; counted
  /// when engaged.
  void on_writer_lost();

  bool engaged() const noexcept { return engaged_; }
  /// Source and reason of the sample that set the current state ("" before any sample).
  const std::string& source() const noexcept { return source_; }
  const std::string& reason() const noexcept { return reason_; }

  std::uint64_t engagements() const noexcept { return engagements_; }  // released -> engaged
  std::uint64_t releases() const noexcept { return releases_; }        // engaged -> released
  std::uint64_t writers_lost_while_engaged() const noexcept { return writers_lost_while_engaged_; }

 private:
  bool engaged_ = false;
  std::string source_;
  std::string reason_;
  std::uint64_t engagements_ = 0;
  std::uint64_t releases_ = 0;
  std::uint64_t writers_lost_while_engaged_ = 0;
};

struct TickInputs {
  std::span<const TimedCommand> latest;  // newest command per robot (CommandTable::latest()), unique ids
  bool halt = false;                     // the referee command is HALT
  bool estop_engaged = false;            // EstopLatch::engaged()
};

struct TickOutput {
  std::vector<OutgoingCommand> commands;  // one per robot, ordered by id
};

/// Totals since construction, plus gauges of the last tick. Published in system.health.
struct CoreCounters {
  std::uint64_t ticks = 0;
  std::uint64_t commands_sent = 0;       // robot commands output (stops included)
  std::uint64_t stops_sent = 0;          // of which stops (any reason)
  std::uint64_t stale_events = 0;        // a robot went from fresh to stale
  std::uint64_t stale_robot_ticks = 0;   // robot-ticks stopped by the watchdog
  std::uint64_t halted_ticks = 0;        // ticks stopped by HALT (and not by e-stop)
  std::uint64_t estop_ticks = 0;         // ticks stopped by the e-stop
  std::uint64_t startup_stop_ticks = 0;  // robot-ticks stopped in the startup window
  std::uint64_t clamped_values = 0;      // values changed by clamping (non-finite included)
  std::uint64_t non_finite_values = 0;   // NaN or infinite values replaced by 0
  std::uint64_t accel_limited = 0;       // robot-ticks whose velocity change was limited
  std::uint32_t stale_robots = 0;        // gauge: robots stopped by the watchdog on the last tick
  std::uint32_t fresh_robots = 0;        // gauge: robots with a fresh command on the last tick
};

class RobotLinkCore {
 public:
  /// @throws std::invalid_argument when validate(config) fails.
  explicit RobotLinkCore(const CoreConfig& config);

  /// One send tick at `now_mono` (host monotonic clock; the watchdog compares it with receive times).
  TickOutput step(const TickInputs& inputs, time::Timestamp now_mono);

  const CoreCounters& counters() const noexcept { return counters_; }
  const CoreConfig& config() const noexcept { return config_; }

  /// A run-time parameter change: from the next step on, `config` (validated first: an invalid one is
  /// refused and the current one kept). What each robot was last sent is kept, so the acceleration limits
  /// go on from it.
  Status reconfigure(const CoreConfig& config);

 private:
  /// Per robot state between ticks: the velocity sent last (for the acceleration limiter).
  struct RobotState {
    bool known = false;  // appeared in the output before
    bool stale = false;  // stopped by the watchdog on the last tick
    double forward = 0;  // m/s, last sent
    double left = 0;     // m/s
    double angular = 0;  // rad/s
  };

  RobotCommand make_safe(const RobotCommand& wanted, RobotState& state, time::Duration dt);

  CoreConfig config_;
  std::array<RobotState, kMaxRobots> robots_{};
  bool started_ = false;
  time::Timestamp first_tick_mono_;
  time::Timestamp last_tick_mono_;
  CoreCounters counters_;
};

}  // namespace ssl::robot_link
