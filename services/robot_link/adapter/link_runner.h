// The send loop of robot_link, without DDS: InputMailbox collects inputs (polled DDS samples, e-stop
// devices; thread-safe) and LinkRunner sends what the core decides whenever the SendSchedule says a packet
// is due: a new robot.commands sample at once while the radio's token bucket allows (else at its next
// token), a new safety stop at once, and otherwise the last commands again as a heartbeat; then it
// collects the backend's feedback. Between packets the loop blocks in the given wait (robot_link waits on
// its robot.commands reader), never spinning. Time comes from an injected ssl::time::Clock (host MONOTONIC
// in production, a SimulatedClock in tests); receive times given to the mailbox must come from the same
// clock.
//
//   InputMailbox mailbox;
//   LinkRunner runner(core_config, *backend, mailbox);
//   runner.run(clock, [&] { return !shutdown.requested(); },
//              [&](time::Timestamp now) { mailbox.on_commands(take_new_commands(), now); },  // inputs
//              [&](time::Timestamp deadline) { return wait_for_commands_until(deadline); },  // wait
//              [&](const TickResult& r) { publish(r.feedback); });                          // each packet
//   runner.send_final_stop(clock.now());                    // on shutdown: every robot stops
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "libs/time/clock.h"
#include "services/robot_link/backend/backend.h"
#include "services/robot_link/core/robot_link_core.h"
#include "services/robot_link/core/send_schedule.h"

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

/// One packet sent.
struct TickResult {
  time::Timestamp now_mono;              // when it was decided and sent
  SendSchedule::Waiting cause;           // kStop, kInput (something new) or kNothing (the heartbeat)
  TickOutput output;
  Status sent;                           // the backend's send result
  std::vector<FeedbackReport> feedback;  // arrived since the last packet
  InputMailbox::Snapshot inputs;         // what the core saw
};

class LinkRunner {
 public:
  /// `backend` and `mailbox` must outlive the runner. @throws std::invalid_argument on a bad config.
  LinkRunner(const CoreConfig& config, Backend& backend, InputMailbox& mailbox);

  /// At `now_mono`: looks at the mailbox and sends if a packet is due (SendSchedule, at the config's
  /// send period); the first call always sends. nullopt when nothing was due.
  std::optional<TickResult> poll(time::Timestamp now_mono);

  /// When poll() next sends if no input arrives before: the loop's wake-up deadline.
  time::Timestamp next_send() const;

  /// Sends one packet at `now_mono` whatever the schedule: snapshot the mailbox, collect feedback, step the
  /// core, send.
  TickResult send(time::Timestamp now_mono);

  /// Until `keep_running()` is false or `wait_until` returns false: `take_inputs(now)` feeds the mailbox,
  /// poll() sends what is due and `after_send` sees each packet's result; then `wait_until(deadline)`
  /// blocks until next_send() on `clock` or until an input may have arrived (returning early is fine: the
  /// loop looks again). `take_inputs` and `after_send` may be empty.
  void run(time::Clock& clock, const std::function<bool()>& keep_running,
           const std::function<void(time::Timestamp)>& take_inputs,
           const std::function<bool(time::Timestamp)>& wait_until,
           const std::function<void(const TickResult&)>& after_send);

  /// Sends one packet in which every known robot gets a stop (used on shutdown).
  Status send_final_stop(time::Timestamp now_mono);

  const RobotLinkCore& core() const noexcept { return core_; }
  /// See RobotLinkCore::reconfigure; the send period stays as started.
  Status reconfigure(const CoreConfig& config) { return core_.reconfigure(config); }

 private:
  /// What waits to be sent, comparing the mailbox with the last packet.
  SendSchedule::Waiting waiting(const InputMailbox::Snapshot& inputs) const;

  RobotLinkCore core_;
  Backend& backend_;
  InputMailbox& mailbox_;
  std::optional<SendSchedule> schedule_;  // from the first poll()
  SendSchedule::Waiting waiting_ = SendSchedule::Waiting::kNothing;  // as of the last poll()
  // What the last packet carried.
  std::uint64_t sent_command_samples_ = 0;
  bool sent_halt_ = false;
  bool sent_estop_ = false;
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
