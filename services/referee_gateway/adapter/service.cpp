#include "services/referee_gateway/adapter/service.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <optional>
#include <utility>
#include <vector>

#include "libs/dds/health.h"
#include "libs/net/multicast.h"
#include "services/referee_gateway/adapter/convert.h"
#include "services/referee_gateway/adapter/ingest.h"

namespace ssl::referee {
namespace {

using namespace std::chrono_literals;

/// Lets one message of a kind through per interval and counts the ones held back.
class Throttle {
 public:
  explicit Throttle(time::Duration interval) : interval_(interval) {}

  /// True when a message may be logged now; `suppressed` then holds how many were held back before it.
  bool allow(time::Timestamp now, std::uint64_t& suppressed) {
    if (last_ && now - *last_ < interval_) {
      ++held_back_;
      return false;
    }
    last_ = now;
    suppressed = held_back_;
    held_back_ = 0;
    return true;
  }

 private:
  time::Duration interval_;
  std::optional<time::Timestamp> last_;
  std::uint64_t held_back_ = 0;
};

std::string short_id(const std::string& source) {
  if (source.empty()) return "<no id>";
  return source.size() > 8 ? source.substr(0, 8) : source;
}

std::string format_seconds(time::Duration d) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", time::to_seconds(d));
  return text;
}

}  // namespace

struct RefereeGatewayService::Impl {
  Impl(const ServiceOptions& service_options, net::MulticastReceiver receiver_in,
       dds::Writer<idl::referee::RefereeState> state_writer_in,
       dds::Writer<idl::referee::RefereeEvent> event_writer_in, dds::HealthReporter health_in,
       std::shared_ptr<spdlog::logger> logger_in, time::Clock& wall_in, time::Clock& monotonic_in)
      : options(service_options),
        receiver(std::move(receiver_in)),
        state_writer(std::move(state_writer_in)),
        event_writer(std::move(event_writer_in)),
        health(std::move(health_in)),
        logger(std::move(logger_in)),
        wall(wall_in),
        monotonic(monotonic_in),
        ingest(service_options.gateway, service_options.source),
        malformed_log(service_options.log_interval),
        foreign_log(service_options.log_interval),
        jump_log(service_options.log_interval),
        write_log(service_options.log_interval),
        receive_log(service_options.log_interval),
        started(monotonic_in.now()) {}

  void run();
  void handle(std::span<const std::uint8_t> bytes, const net::Endpoint& sender);
  void publish(const StepOutput& output);
  void report_health(time::Timestamp now);

  ServiceOptions options;
  net::MulticastReceiver receiver;
  dds::Writer<idl::referee::RefereeState> state_writer;
  dds::Writer<idl::referee::RefereeEvent> event_writer;
  dds::HealthReporter health;
  std::shared_ptr<spdlog::logger> logger;
  time::Clock& wall;
  time::Clock& monotonic;
  RefereeIngest ingest;
  Throttle malformed_log;
  Throttle foreign_log;
  Throttle jump_log;
  Throttle write_log;
  Throttle receive_log;
  time::Timestamp started;  // monotonic
  std::uint64_t write_failures = 0;
  std::uint64_t receive_errors = 0;
  std::uint64_t truncated = 0;
  std::uint64_t accepted_at_last_report = 0;
  time::Timestamp last_report;  // monotonic
  bool was_stale = true;
};

void RefereeGatewayService::Impl::handle(std::span<const std::uint8_t> bytes, const net::Endpoint& sender) {
  const time::Timestamp now = monotonic.now();
  IngestResult result = ingest.handle(bytes, wall.now(), now);
  std::uint64_t suppressed = 0;
  if (result.malformed) {
    if (malformed_log.allow(now, suppressed)) {
      logger->warn(
          "malformed referee packet from {} ({} bytes): {} ({} more since the last report, {} in total)",
          sender.to_string(), bytes.size(), result.malformed->message, suppressed, ingest.malformed());
    }
    return;
  }
  const StepOutput& output = result.output;
  const RefereeGateway& core = ingest.core();
  if (output.verdict == PacketVerdict::kForeignSource) {
    if (foreign_log.allow(now, suppressed)) {
      logger->warn(
          "ignoring referee source '{}' from {}: following '{}' ({} more ignored since the last report)",
          core.last_foreign_source(), sender.to_string(), core.chosen_source().value_or(""), suppressed);
    }
    return;
  }
  if (output.switched_from) {
    logger->warn("now following referee source '{}' from {}: '{}' was silent for {} or more",
                 core.chosen_source().value_or(""), sender.to_string(), *output.switched_from,
                 format_seconds(core.options().source_switch_after));
  } else if (output.reason == PublishReason::kFirst) {
    logger->info("following referee source '{}' from {}", core.chosen_source().value_or(""),
                 sender.to_string());
  }
  if (output.counter_jump && jump_log.allow(now, suppressed)) {
    logger->warn(
        "command counter jumped from {} to {}: commands may have been missed ({} more since the last "
        "report, {} in total)",
        output.counter_jump->from, output.counter_jump->to, suppressed, core.counters().counter_jumps);
  }
  publish(output);
}

void RefereeGatewayService::Impl::publish(const StepOutput& output) {
  const auto report_failure = [&](const Status& status) {
    ++write_failures;
    std::uint64_t suppressed = 0;
    if (write_log.allow(monotonic.now(), suppressed)) {
      logger->error("{} ({} more since the last report)", status.error().message, suppressed);
    }
  };
  for (const RefereeEvent& event : output.events) {
    logger->info("game event {} by {} (command {} #{})", to_string(event.event.type),
                 event.event.by_team == Team::kBlue     ? "blue"
                 : event.event.by_team == Team::kYellow ? "yellow"
                                                        : "nobody",
                 to_string(event.command), event.command_counter);
    if (Status sent = event_writer.write(to_idl(event)); !sent) report_failure(sent);
  }
  if (output.state) {
    if (output.reason == PublishReason::kChange || output.reason == PublishReason::kFirst) {
      logger->debug("referee state: {} #{} stage {}", to_string(output.state->command),
                    output.state->command_counter, to_string(output.state->stage));
    }
    if (Status sent = state_writer.write(to_idl(*output.state)); !sent) report_failure(sent);
  }
}

void RefereeGatewayService::Impl::report_health(time::Timestamp now) {
  const RefereeGateway& core = ingest.core();
  const GatewayCounters& counters = core.counters();
  const Liveness liveness = core.liveness(now);
  const double window = time::to_seconds(now - last_report);
  const double rate =
      window > 0 ? static_cast<double>(counters.accepted - accepted_at_last_report) / window : 0.0;
  accepted_at_last_report = counters.accepted;
  last_report = now;

  std::string status;
  if (!liveness.age) {
    status = "stale: no referee packet yet (" + format_seconds(now - started) + " since start) on " +
             receiver.group().to_string();
  } else if (liveness.stale) {
    status = "stale: no referee packet for " + format_seconds(*liveness.age);
  } else {
    status = "following '" + short_id(core.chosen_source().value_or("")) + "'";
  }
  if (const auto& last = core.last_published()) {
    status += std::string(liveness.stale ? ", last " : ": ") + std::string(to_string(last->command)) + " #" +
              std::to_string(last->command_counter) + ", " + std::string(to_string(last->stage));
  }
  if (counters.foreign_source > 0)
    status += "; " + std::to_string(counters.foreign_source) + " foreign packets";
  if (liveness.stale != was_stale) {
    if (liveness.stale) {
      logger->warn("referee is stale: {}", status);
    } else {
      logger->info("referee packets arrive: {}", status);
    }
    was_stale = liveness.stale;
  }

  const std::uint64_t malformed = ingest.malformed();
  dds::HealthReport report{.level = liveness.stale ? dds::HealthLevel::kWarn : dds::HealthLevel::kOk,
                           .status = status,
                           .rate_hz = rate,
                           .errors = write_failures + receive_errors,
                           .dropped = malformed + counters.foreign_source,
                           .counters = {{"packets", counters.packets + malformed},
                                        {"accepted", counters.accepted},
                                        {"malformed", malformed},
                                        {"foreign_source", counters.foreign_source},
                                        {"source_switches", counters.source_switches},
                                        {"counter_jumps", counters.counter_jumps},
                                        {"events_published", counters.events_published},
                                        {"states_published", counters.states_published},
                                        {"heartbeats", counters.heartbeats},
                                        {"write_failures", write_failures},
                                        {"receive_errors", receive_errors},
                                        {"state_readers", state_writer.counters().matched_readers},
                                        {"event_readers", event_writer.counters().matched_readers}}};
  if (liveness.age) {
    report.counters.emplace_back("referee_age_ms", static_cast<std::uint64_t>(std::max<std::int64_t>(
                                                       0, liveness.age->count() / 1'000'000)));
  }
  if (Status sent = health.publish(report); !sent) {
    ++write_failures;
    std::uint64_t suppressed = 0;
    if (write_log.allow(now, suppressed)) logger->error("{}", sent.error().message);
  }
}

void RefereeGatewayService::Impl::run() {
  std::vector<std::uint8_t> buffer(65536);
  last_report = monotonic.now();
  time::Timestamp next_health = last_report + health.period(options.health_period);
  for (;;) {
    const net::ReceiveResult received = receiver.receive(buffer, 100ms);
    switch (received.status) {
      case net::ReceiveStatus::kReceived:
        handle(std::span<const std::uint8_t>(buffer).first(received.size), received.sender);
        break;
      case net::ReceiveStatus::kTruncated: {
        ingest.count_truncated();
        std::uint64_t suppressed = 0;
        if (malformed_log.allow(monotonic.now(), suppressed)) {
          logger->warn("oversized referee datagram from {} ({} bytes) dropped", received.sender.to_string(),
                       received.size);
        }
        break;
      }
      case net::ReceiveStatus::kTimeout: break;
      case net::ReceiveStatus::kInterrupted: return;
      case net::ReceiveStatus::kError: {
        ++receive_errors;
        std::uint64_t suppressed = 0;
        if (receive_log.allow(monotonic.now(), suppressed)) {
          logger->error("receiving referee packets failed: {} ({} more since the last report)",
                        received.error, suppressed);
        }
        monotonic.sleep_for(10ms);  // a failing socket must not spin
        break;
      }
    }
    const time::Timestamp now = monotonic.now();
    if (now >= next_health) {
      report_health(now);
      next_health = now + health.period(options.health_period);
    }
  }
}

Result<std::unique_ptr<RefereeGatewayService>> RefereeGatewayService::open(
    const ServiceOptions& options, dds::Participant& participant, std::shared_ptr<spdlog::logger> logger,
    time::Clock& wall, time::Clock& monotonic) {
  auto receiver = net::MulticastReceiver::open(options.group, options.port, options.interface_address);
  if (!receiver) return receiver.error();
  auto state_writer = participant.make_writer(dds::topics::kRefereeState);
  if (!state_writer) return state_writer.error();
  auto event_writer = participant.make_writer(dds::topics::kRefereeEvent);
  if (!event_writer) return event_writer.error();
  auto health = dds::HealthReporter::create(participant, options.health_name);
  if (!health) return health.error();
  health->exit_when_stalled();
  auto impl = std::make_unique<Impl>(options, std::move(*receiver), std::move(*state_writer),
                                     std::move(*event_writer), std::move(*health), std::move(logger), wall,
                                     monotonic);
  return std::unique_ptr<RefereeGatewayService>(new RefereeGatewayService(std::move(impl)));
}

RefereeGatewayService::RefereeGatewayService(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

RefereeGatewayService::~RefereeGatewayService() { stop(); }

void RefereeGatewayService::start() {
  if (thread_.joinable()) return;
  thread_ = std::thread([this] { impl_->run(); });
}

void RefereeGatewayService::stop() {
  impl_->receiver.interrupt();
  if (thread_.joinable()) thread_.join();
}

}  // namespace ssl::referee
