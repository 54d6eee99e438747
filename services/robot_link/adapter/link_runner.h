// The fixed-rate loop of robot_link, without DDS: InputMailbox collects inputs (polled DDS samples,
// e-stop devices; thread-safe) and LinkRunner sends, on every tick of a drift-free PeriodicTimer at the
// configured rate, what the core decides, whatever the timing of incoming commands; then it collects the
// backend's feedback. Time comes from an injected ssl::time::Clock (host MONOTONIC in production, a
// SimulatedClock in tests); receive times given to the mailbox must come from the same clock.
//
//   InputMailbox mailbox;
//   LinkRunner runner(core_config, *backend, mailbox);
//   runner.run(clock, [&] { return !shutdown.requested(); },
//              [&](time::Timestamp now) { mailbox.on_commands(take_new_commands(), now); },  // before
//              [&](const TickResult& r) { publish(r.feedback); });                          // after
//   runner.send_final_stop(clock.now());                    // on shutdown: every robot stops
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "libs/time/clock.h"
#include "services/robot_link/backend/backend.h"
#include "services/robot_link/core/robot_link_core.h"

namespace ssl::robot_link {

/// Thread-safe holder of the newest inputs: commands per robot, referee HALT, the e-stop latch.
class InputMailbox {
 public:
  /// The commands of one robot.commands sample, received at `received_mono`.
  void on_commands(std::span<const RobotCommand> commands, time::Timestamp received_mono);
  /// A robot.commands sample for the other team (dropped, counted).
  void on_wrong_team();
  void on_referee(bool halt);
  void on_estop(bool engaged, std::string source, std::string reason);
  void on_estop_writer_lost();

  struct Snapshot {
    std::vector<TimedCommand> latest;
    bool halt = false;
    bool estop_engaged = false;
    std::string estop_source;
    std::string estop_reason;
    std::uint64_t command_samples = 0;  // robot.commands samples accepted
    std::uint64_t robot_commands = 0;   // robot commands in them (valid ids)
    std::uint64_t invalid_ids = 0;
    std::uint64_t wrong_team = 0;
    std::uint64_t estop_engagements = 0;
    std::uint64_t estop_writers_lost_while_engaged = 0;
  };
  Snapshot snapshot() const;

  bool estop_engaged() const;

 private:
  mutable std::mutex mutex_;
  CommandTable table_;
  bool halt_ = false;
  EstopLatch estop_;
  std::uint64_t wrong_team_ = 0;
};

struct TickResult {
  time::Timestamp now_mono;
  TickOutput output;
  Status sent;                           // the backend's send result
  std::vector<FeedbackReport> feedback;  // arrived since the last tick
  InputMailbox::Snapshot inputs;         // what the core saw
};

class LinkRunner {
 public:
  /// `backend` and `mailbox` must outlive the runner. @throws std::invalid_argument on a bad config.
  LinkRunner(const CoreConfig& config, Backend& backend, InputMailbox& mailbox);

  /// One tick at `now_mono`: snapshot the mailbox, step the core, send, collect feedback.
  TickResult tick(time::Timestamp now_mono);

  /// Ticks at the config's send period on `clock` until `keep_running()` is false or the clock stops.
  /// `before_tick(now)` runs first on every tick (feed the mailbox with what arrived), `after_tick` sees
  /// every tick's result (publish feedback, health); either may be empty. Missed deadlines are skipped,
  /// never sent in a burst.
  void run(time::Clock& clock, const std::function<bool()>& keep_running,
           const std::function<void(time::Timestamp)>& before_tick,
           const std::function<void(const TickResult&)>& after_tick);

  /// Sends one tick in which every known robot gets a stop (used on shutdown).
  Status send_final_stop(time::Timestamp now_mono);

  const RobotLinkCore& core() const noexcept { return core_; }
  /// See RobotLinkCore::reconfigure; the send period stays as started.
  Status reconfigure(const CoreConfig& config) { return core_.reconfigure(config); }
  std::uint64_t missed_ticks() const noexcept { return missed_ticks_; }

 private:
  RobotLinkCore core_;
  Backend& backend_;
  InputMailbox& mailbox_;
  std::uint64_t missed_ticks_ = 0;
};

/// Decides which feedback to publish: a robot's report goes out when it differs from the last one
/// published for that robot, or when `heartbeat` passed since then. Values the report leaves unset keep
/// the robot's previous ones (the simulator reports contact only; a radio may skip fields).
class FeedbackThrottle {
 public:
  explicit FeedbackThrottle(time::Duration heartbeat) : heartbeat_(heartbeat) {}

  /// The merged reports to publish now, at most one per robot.
  std::vector<FeedbackReport> update(std::span<const FeedbackReport> reports, time::Timestamp now_mono);

  /// Link quality of each robot that reported one (for health), by id.
  std::vector<std::pair<std::uint32_t, double>> link_quality() const;

 private:
  struct Entry {
    bool seen = false;
    FeedbackReport merged;
    bool published = false;
    FeedbackReport last_published;
    time::Timestamp published_mono;
  };
  time::Duration heartbeat_;
  std::array<Entry, kMaxRobots> robots_{};
};

}  // namespace ssl::robot_link
