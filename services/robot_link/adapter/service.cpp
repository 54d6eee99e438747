#include "services/robot_link/adapter/service.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>

#include "libs/common/percentile.h"
#include "libs/dds/health.h"
#include "libs/dds/participant.h"
#include "libs/service/parameters.h"
#include "libs/time/clock.h"
#include "services/robot_link/adapter/convert.h"
#include "services/robot_link/adapter/estop_inputs.h"
#include "services/robot_link/adapter/link_runner.h"
#include "services/robot_link/backend/backend.h"

namespace ssl::robot_link {
namespace {

using namespace std::chrono_literals;

std::int64_t wall_clock_unix_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

/// Builds the system.health report from totals; rates and "in the last second" from differences.
class HealthTracker {
 public:
  HealthTracker(std::string backend, time::Timestamp start_mono)
      : backend_(std::move(backend)), last_mono_(start_mono) {}

  /// `out_latencies`: s from robot.commands reception to the packet that first carried the sample, this
  /// period (reordered).
  dds::HealthReport report(const TickResult& tick, const RobotLinkCore& core, const BackendCounters& backend,
                           std::vector<double>& out_latencies, std::uint64_t heartbeats_sent,
                           std::uint64_t robot_sent_write_failures, std::uint64_t feedback_published,
                           std::uint64_t feedback_write_failures, const SerialEstop* device,
                           const std::vector<std::pair<std::uint32_t, double>>& link_quality,
                           const dds::ReaderCounters& commands_reader) {
    const CoreCounters& c = core.counters();
    const auto& in = tick.inputs;
    const double elapsed = std::max(1e-3, time::to_seconds(tick.now_mono - last_mono_));
    const double rate = static_cast<double>(backend.packets_sent - last_packets_) / elapsed;
    const bool new_send_errors = backend.send_errors > last_send_errors_;
    const bool commands_flowing = in.command_samples > last_samples_;
    last_mono_ = tick.now_mono;
    last_packets_ = backend.packets_sent;
    last_send_errors_ = backend.send_errors;
    last_samples_ = in.command_samples;

    dds::HealthReport report;
    std::string status = backend_ + ", " + std::to_string(c.fresh_robots) + " robot(s) commanded";
    if (c.stale_robots > 0) status += ", " + std::to_string(c.stale_robots) + " stale (stopped)";
    if (in.halt) status += ", HALT";
    if (!commands_flowing) status += ", no commands";
    if (new_send_errors) status += ", send errors";
    if (in.estop_engaged) {
      status = "E-STOP ENGAGED (" + in.estop_source + ": " + in.estop_reason + "); " + status;
    }
    report.level = in.estop_engaged || !commands_flowing || new_send_errors ? dds::HealthLevel::kWarn
                                                                            : dds::HealthLevel::kOk;
    report.status = status;
    report.rate_hz = rate;
    report.latency_p50 = percentile(out_latencies, 0.5);
    report.latency_p99 = percentile(out_latencies, 0.99);
    report.errors = backend.send_errors + feedback_write_failures + robot_sent_write_failures;
    report.dropped = in.invalid_ids + in.wrong_team + backend.feedback_errors;
    report.counters = {
        {"commands_received", in.command_samples},
        {"robot_commands_received", in.robot_commands},
        {"commands_sent", c.commands_sent},
        {"packets_sent", backend.packets_sent},
        {"heartbeats_sent", heartbeats_sent},
        {"stops_sent", c.stops_sent},
        {"stale_stopped_robots", c.stale_robots},
        {"stale_events", c.stale_events},
        {"stale_robot_ticks", c.stale_robot_ticks},
        {"halted_ticks", c.halted_ticks},
        {"estop_engaged", in.estop_engaged ? 1u : 0u},
        {"estop_ticks", c.estop_ticks},
        {"estop_engagements", in.estop_engagements},
        {"estop_writers_lost_while_engaged", in.estop_writers_lost_while_engaged},
        {"clamped_values", c.clamped_values},
        {"non_finite_values", c.non_finite_values},
        {"accel_limited", c.accel_limited},
        {"invalid_robot_ids", in.invalid_ids},
        {"wrong_team_samples", in.wrong_team},
        {"send_errors", backend.send_errors},
        {"robot_sent_write_failures", robot_sent_write_failures},
        {"feedback_received", backend.feedback_received},
        {"feedback_errors", backend.feedback_errors},
        {"feedback_published", feedback_published},
        {"simulator_errors", backend.remote_errors},
        {"radio_frames_lost", backend.frames_lost},
        {"commands_deadlines_missed", commands_reader.deadlines_missed},
        {"commands_samples_lost", commands_reader.samples_lost},
    };
    if (device != nullptr) {
      report.counters.emplace_back("estop_device_connected", device->connected() ? 1u : 0u);
      report.counters.emplace_back("estop_device_losses", device->device_losses());
      report.counters.emplace_back("estop_device_garbage_bytes", device->garbage_bytes());
    }
    for (const auto& [id, quality] : link_quality) {
      report.counters.emplace_back("link_quality_pct_robot_" + std::to_string(id),
                                   static_cast<std::uint64_t>(std::lround(quality * 100.0)));
    }
    return report;
  }

 private:
  std::string backend_;
  time::Timestamp last_mono_;
  std::uint64_t last_packets_ = 0;
  std::uint64_t last_send_errors_ = 0;
  std::uint64_t last_samples_ = 0;
};

/// When a polled sample arrived, on the monotonic clock: its DDS reception time (host wall clock) mapped
/// onto `now_mono`. The age is bounded to [0, 2 send periods] (the loop takes a sample when it arrives, or
/// within a period at most), so a wall-clock step cannot make a command look older or newer than that.
time::Timestamp received_mono(time::Timestamp now_mono, std::int64_t now_unix_ns,
                              std::int64_t reception_unix_ns, time::Duration send_period) {
  const time::Duration age =
      std::clamp(time::Duration(now_unix_ns - reception_unix_ns), time::Duration::zero(), 2 * send_period);
  return now_mono - age;
}

}  // namespace

Status run_robot_link(const ServiceOptions& options, ShutdownSignal& shutdown,
                      const std::shared_ptr<spdlog::logger>& logger) {
  const RobotLinkConfig& config = options.config;
  const TeamColor team = options.team;
  const std::string instance = "robot_link/" + std::string(to_string(team));

  auto backend = make_backend(backend_options(config, team));
  if (!backend) return backend.error();

  time::MonotonicClock clock;
  InputMailbox mailbox;
  LinkRunner runner(core_config(config), **backend, mailbox);

  // Local e-stop inputs first: a missing e-stop device engages the e-stop before anything moves.
  std::optional<SerialEstop> estop_device;
  if (!config.estop_device.empty()) estop_device.emplace(config.estop_device, config.estop_device_baud);
  std::optional<KeyboardEstop> keyboard;
  if (config.keyboard_estop) {
    keyboard.emplace();
    if (keyboard->active()) {
      logger->info("keyboard e-stop: press SPACE to engage / release");
    } else {
      logger->warn("--keyboard-estop: stdin is not a terminal; keyboard e-stop disabled");
      keyboard.reset();
    }
  }

  const std::string identity = dds::identity::team_stack(team);
  auto participant = dds::Participant::create({.domain_id = options.domain_id, .name = instance,
                                               .discovery = options.discovery, .security = options.security,
                                               .identity = identity});
  if (!participant) return participant.error();
  // Readers are polled from the loop (no middleware callbacks: nothing of ours runs on Fast DDS threads,
  // and no callback can run before a reader is fully created).
  auto commands_reader = participant->make_reader(dds::topics::kRobotCommands, team);
  if (!commands_reader) return commands_reader.error();
  auto referee_reader = participant->make_reader(dds::topics::kRefereeState);
  if (!referee_reader) return referee_reader.error();
  // E-stops for our team: addressed to it, or to every team. With DDS Security only our own operators and
  // stack may write them (deploy/dds-certs.sh), so no other team can release ours.
  auto estop_reader = participant->make_reader(dds::topics::kSystemEstop, team);
  if (!estop_reader) return estop_reader.error();
  auto feedback_writer = participant->make_writer(dds::topics::kRobotFeedback, team);
  if (!feedback_writer) return feedback_writer.error();
  auto sent_writer = participant->make_writer(dds::topics::kRobotSent, team);
  if (!sent_writer) return sent_writer.error();
  // The local e-stop inputs publish on system.estop through a participant of their own: Fast DDS does not
  // keep a writer's liveliness asserted towards readers of its own participant, so our reader would
  // see our own writer "lost" a second after each write. They address our team only: our button never
  // commands the other team's robots.
  std::optional<dds::Participant> estop_participant;
  std::optional<dds::Writer<idl::system::Estop>> estop_writer;
  if (estop_device || keyboard) {
    auto created = dds::Participant::create({.domain_id = options.domain_id, .name = instance + "/estop",
                                             .discovery = options.discovery, .security = options.security,
                                             .identity = identity});
    if (!created) return created.error();
    estop_participant.emplace(std::move(*created));
    auto writer = estop_participant->make_writer(dds::topics::kSystemEstop, team);
    if (!writer) return writer.error();
    estop_writer.emplace(std::move(*writer));
  }
  auto health = dds::HealthReporter::create(*participant, instance);
  if (!health) return health.error();
  // Up (READY) once it hears its team's planner.
  health->ready_when([reader = *commands_reader] { return reader.counters().matched_writers > 0; });
  health->exit_when_stalled();
  // Run-time parameters (the robots' limits): applied to the core between two ticks.
  auto params = robot_link_runtime_parameters(config);
  if (!params) return params.error();
  auto parameters = service::LiveConfig<RobotLinkConfig>::create(*participant, instance, std::move(*params),
                                                                  options.saved_parameters);
  if (!parameters) return parameters.error();

  logger->info("{}: robot.commands on domain {} -> {}: new commands at once, at most {} Hz (heartbeat every "
               "{} ms), watchdog {} ms",
               instance, options.domain_id, (*backend)->description(), config.send_rate,
               std::lround(1000 / config.send_rate), std::lround(config.command_timeout * 1000));

  // A local e-stop input: latch here at once, and tell the rest of our team's stack (and the console)
  // through system.estop.
  const auto local_estop = [&](bool engaged, const std::string& source, const std::string& reason) {
    mailbox.on_estop(engaged, source, reason);
    if (estop_writer) {
      idl::system::Estop sample;
      sample.engaged(engaged);
      sample.source(source);
      sample.reason(reason);
      sample.stamp_unix_ns(wall_clock_unix_ns());
      if (Status written = estop_writer->write(sample); !written)
        logger->error("{}", written.error().message);
    }
  };

  FeedbackThrottle throttle(time::duration_from_seconds(config.feedback_heartbeat));
  HealthTracker health_tracker((*backend)->description(), clock.now());
  time::Timestamp next_health = clock.now() + health->period();
  std::uint64_t feedback_published = 0;
  std::uint64_t feedback_write_failures = 0;
  // The newest robot.commands sample taken, and the one the last packet carried (robot.sent).
  idl::robot::CommandsSent newest;
  newest.team(team_to_idl(team));
  std::int64_t newest_reception_unix_ns = 0;
  std::uint64_t last_sent_sequence = 0;
  std::vector<double> out_latencies;  // s, this health period
  std::uint64_t heartbeats_sent = 0;
  std::uint64_t robot_sent_write_failures = 0;
  std::int32_t alive_estop_writers = 0;
  bool was_engaged = false;
  bool was_halted = false;
  std::string last_backend_error;
  std::optional<time::Timestamp> last_send_error_log_mono;

  // Everything that arrived since the loop last looked, into the mailbox.
  const auto take_inputs = [&](time::Timestamp now_mono) {
    if (std::optional<RobotLinkConfig> next = (*parameters)->poll()) {
      if (Status applied = runner.reconfigure(core_config(*next)); !applied) {
        logger->error("run-time parameters: {}", applied.error().message);
      } else {
        logger->info("run-time parameters changed");
      }
    }
    const std::int64_t now_unix_ns = wall_clock_unix_ns();
    if (auto sample = commands_reader->take_latest()) {
      if (team_matches(sample->data, team)) {
        const std::vector<RobotCommand> commands = commands_from_idl(sample->data);
        mailbox.on_commands(commands, received_mono(now_mono, now_unix_ns, sample->reception_unix_ns,
                                                    runner.core().config().send_period));
        newest.sequence_number(sample->data.sequence_number());
        newest.stamp(sample->data.stamp());
        newest_reception_unix_ns = sample->reception_unix_ns;
      } else {
        mailbox.on_wrong_team();
      }
    }
    if (auto sample = referee_reader->take_latest()) mailbox.on_referee(is_halt(sample->data));
    for (const auto& sample : estop_reader->take()) {
      mailbox.on_estop(sample.data.engaged(), sample.data.source(), sample.data.reason());
    }
    // Liveliness of the system.estop writers: losing one keeps a latched e-stop engaged (counted).
    const std::int32_t alive = estop_reader->counters().alive_writers;
    for (std::int32_t lost = alive_estop_writers - alive; lost > 0; --lost) {
      mailbox.on_estop_writer_lost();
      if (mailbox.estop_engaged())
        logger->warn("an e-stop writer is gone; the e-stop stays ENGAGED until released");
    }
    alive_estop_writers = alive;
    // Local e-stop inputs.
    if (estop_device) {
      const bool was_connected = estop_device->connected();
      if (auto event = estop_device->poll(now_mono)) {
        local_estop(event->engaged, instance + " estop_device " + config.estop_device, event->reason);
      }
      if (was_connected != estop_device->connected()) {
        if (estop_device->connected()) {
          logger->info("e-stop device {} connected", config.estop_device);
        } else {
          logger->warn("e-stop device {} lost ({}): e-stop engaged", config.estop_device,
                       estop_device->last_error());
        }
      }
    }
    if (keyboard) {
      for (int presses = keyboard->poll(); presses > 0; --presses) {
        const bool engage = !mailbox.estop_engaged();
        local_estop(engage, instance + " keyboard", engage ? "space bar" : "space bar (release)");
      }
    }
  };

  // Between packets: until the next one is due, woken at once by a robot.commands sample. At most one send
  // period, so that referee.state, system.estop, the local e-stop inputs and shutdown are looked at as
  // often as before.
  const time::Duration send_period = runner.core().config().send_period;
  const auto wait_until = [&](time::Timestamp deadline) {
    commands_reader->wait_for_data(std::clamp(deadline - clock.now(), time::Duration::zero(), send_period));
    return true;
  };

  const auto after_send = [&](const TickResult& tick) {
    // The end of the vision -> radio path: which sample this packet carried and when it left (the clock is
    // read first: the send has just returned).
    const std::int64_t sent_unix_ns = wall_clock_unix_ns();
    if (!tick.output.commands.empty() && tick.sent) {
      newest.sent_unix_ns(sent_unix_ns);
      newest.resend(newest.sequence_number() == last_sent_sequence);
      if (!sent_writer->write(newest)) ++robot_sent_write_failures;
      if (!newest.resend() && newest_reception_unix_ns > 0) {
        out_latencies.push_back(static_cast<double>(sent_unix_ns - newest_reception_unix_ns) * 1e-9);
      }
      last_sent_sequence = newest.sequence_number();
      if (tick.cause == SendSchedule::Waiting::kNothing) ++heartbeats_sent;
    }

    if (tick.inputs.estop_engaged != was_engaged) {
      if (tick.inputs.estop_engaged) {
        logger->warn("E-STOP ENGAGED by {}: {}", tick.inputs.estop_source, tick.inputs.estop_reason);
      } else {
        logger->info("e-stop released by {}: {}", tick.inputs.estop_source, tick.inputs.estop_reason);
      }
      was_engaged = tick.inputs.estop_engaged;
    }
    if (tick.inputs.halt != was_halted) {
      logger->info(tick.inputs.halt ? "referee HALT: every robot stopped" : "referee HALT lifted");
      was_halted = tick.inputs.halt;
    }
    if (!tick.sent && (!last_send_error_log_mono || tick.now_mono - *last_send_error_log_mono >= 1s)) {
      logger->error("send failed: {} ({} failures so far)", tick.sent.error().message,
                    (*backend)->counters().send_errors);
      last_send_error_log_mono = tick.now_mono;
    }
    if (const std::string error = (*backend)->last_error(); error != last_backend_error) {
      if (!error.empty()) logger->warn("{}", error);
      last_backend_error = error;
    }

    // Feedback, changes at once and a heartbeat otherwise.
    const std::int64_t now_unix_ns = wall_clock_unix_ns();
    for (const FeedbackReport& report : throttle.update(tick.feedback, tick.now_mono)) {
      if (feedback_writer->write(feedback_to_idl(report, team, now_unix_ns))) {
        ++feedback_published;
      } else {
        ++feedback_write_failures;
      }
    }

    if (tick.now_mono >= next_health) {
      const dds::HealthReport report = health_tracker.report(
          tick, runner.core(), (*backend)->counters(), out_latencies, heartbeats_sent, robot_sent_write_failures,
          feedback_published, feedback_write_failures, estop_device ? &*estop_device : nullptr, throttle.link_quality(),
          commands_reader->counters());
      if (Status published = health->publish(report); !published)
        logger->debug("{}", published.error().message);
      out_latencies.clear();
      next_health = tick.now_mono + health->period();
      logger->debug("{}", report.status);
    }
  };

  runner.run(
      clock, [&] { return !shutdown.requested(); }, take_inputs, wait_until, after_send);

  // Leave every robot standing: a simulator keeps executing the last command it got.
  for (int i = 0; i < 3; ++i) (void)runner.send_final_stop(clock.now());
  logger->info("stopping: every robot was sent a stop");
  return {};
}

}  // namespace ssl::robot_link
