#include "services/vision_gateway/adapter/service.h"

#include <spdlog/spdlog.h>

#include <array>
#include <cstdio>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include "libs/dds/health.h"
#include "libs/net/multicast.h"
#include "libs/time/clock.h"
#include "services/vision_gateway/adapter/convert.h"
#include "services/vision_gateway/adapter/pipeline.h"
#include "services/vision_gateway/core/latency_window.h"
#include "services/vision_gateway/core/tracker.h"

namespace ssl::vision_gateway {
namespace {

using std::chrono::milliseconds;

/// How long one receive() may block: bounds the health period's jitter when no packet arrives.
constexpr auto kReceivePoll = milliseconds(100);

}  // namespace

struct VisionGatewayService::Impl {
  Impl(ServiceOptions options_in, std::shared_ptr<spdlog::logger> logger_in, net::MulticastReceiver vision_in,
       std::optional<net::MulticastReceiver> tracker_in,
       dds::Writer<idl::vision::DetectionFrame> detection_in, dds::Writer<idl::vision::Geometry> geometry_in,
       dds::HealthReporter health_in)
      : options(std::move(options_in)),
        logger(std::move(logger_in)),
        vision(std::move(vision_in)),
        tracker(std::move(tracker_in)),
        detection_writer(std::move(detection_in)),
        geometry_writer(std::move(geometry_in)),
        health(std::move(health_in)),
        pipeline(options.gateway),
        malformed_log(options.malformed_log_interval),
        foreign_log(options.malformed_log_interval),
        tracker_malformed_log(options.malformed_log_interval) {}

  void vision_loop();
  void tracker_loop();
  void handle(std::span<const std::uint8_t> bytes, const net::Endpoint& sender, const ReceiveTime& received);
  void maybe_report(time::Timestamp now_monotonic);

  ServiceOptions options;
  std::shared_ptr<spdlog::logger> logger;
  net::MulticastReceiver vision;
  std::optional<net::MulticastReceiver> tracker;
  dds::Writer<idl::vision::DetectionFrame> detection_writer;
  dds::Writer<idl::vision::Geometry> geometry_writer;
  dds::HealthReporter health;
  time::RealClock wall_clock;
  time::MonotonicClock monotonic_clock;

  // Vision thread only.
  VisionPipeline pipeline;
  LogThrottle malformed_log;
  LogThrottle foreign_log;
  LatencyWindow latency;
  idl::vision::DetectionFrame detection_sample;
  idl::vision::Geometry geometry_sample;
  std::array<std::uint8_t, 65536> vision_buffer{};
  std::optional<net::Endpoint> logged_source;
  std::uint64_t frames_in_period = 0;
  std::uint64_t write_failures = 0;
  std::uint64_t receive_errors_logged = 0;
  std::optional<time::Timestamp> period_start;

  // Shared with the tracker thread.
  std::mutex tracker_mutex;
  TrackerMonitor tracker_monitor;       // guarded by tracker_mutex
  std::uint64_t tracker_malformed = 0;  // guarded by tracker_mutex
  LogThrottle tracker_malformed_log;    // tracker thread only
  std::array<std::uint8_t, 65536> tracker_buffer{};
};

void VisionGatewayService::Impl::handle(std::span<const std::uint8_t> bytes, const net::Endpoint& sender,
                                        const ReceiveTime& received) {
  DatagramResult result = pipeline.on_datagram(bytes, sender, received);
  if (result.malformed) {
    if (const std::uint64_t count = malformed_log.on_event(received.monotonic)) {
      logger->warn("{} malformed vision packet(s) dropped (last from {}, {} bytes): {}", count,
                   sender.to_string(), bytes.size(), *result.malformed);
    }
    return;
  }
  const PacketOutput& out = result.output;
  if (out.frame_decision == FrameDecision::kForeignSource ||
      out.geometry_decision == GeometryDecision::kForeignSource) {
    if (const std::uint64_t count = foreign_log.on_event(received.monotonic)) {
      const auto source = pipeline.gateway().source();
      logger->warn("{} vision packet(s) from {} ignored: the source is {}", count, sender.to_string(),
                   source ? source->to_string() : std::string("not chosen yet"));
    }
  }
  if (pipeline.gateway().source() != logged_source) {
    logged_source = pipeline.gateway().source();
    if (out.source_switched) {
      logger->warn("vision source switched to {} (the previous one was silent)", logged_source->to_string());
    } else {
      logger->info("vision source: {}", logged_source->to_string());
    }
  }
  if (out.camera_restarted && out.frame) {
    logger->info("camera {} restarted: frame numbers went back to {}", out.frame->frame.camera_id,
                 out.frame->frame.frame_number);
  }

  bool wrote = false;
  if (out.frame) {
    to_idl(*out.frame, detection_sample);
    if (!detection_writer.write(detection_sample)) ++write_failures;
    ++frames_in_period;
    wrote = true;
  }
  if (out.geometry) {
    to_idl(*out.geometry, geometry_sample);
    if (!geometry_writer.write(geometry_sample)) ++write_failures;
    const FieldGeometry& g = out.geometry->geometry;
    std::string defaulted;
    for (const std::string& name : g.defaulted_fields)
      defaulted += (defaulted.empty() ? "; defaulted: " : ", ") + name;
    logger->info("geometry: field {:.3f} x {:.3f} m (division {} defaults), {} lines, {} arcs, {} cameras{}",
                 g.field.field_length, g.field.field_width, to_string(g.defaults_division),
                 g.field.lines.size(), g.field.arcs.size(), g.calibrations.size(), defaulted);
    wrote = true;
  }
  if (wrote) latency.add(monotonic_clock.now() - received.monotonic);
}

void VisionGatewayService::Impl::maybe_report(time::Timestamp now) {
  if (!period_start) period_start = now;
  const time::Duration elapsed = now - *period_start;
  if (elapsed < health.period(options.health_period)) return;
  period_start = now;

  const double rate = static_cast<double>(frames_in_period) / time::to_seconds(elapsed);
  frames_in_period = 0;
  const LatencySummary summary = latency.take();
  const GatewayCounters& c = pipeline.gateway().counters();
  const net::SocketCounters socket = vision.counters();
  TrackerCounters tracker_counters;
  std::uint64_t tracker_bad = 0;
  std::string tracker_source;
  {
    std::lock_guard lock(tracker_mutex);
    tracker_counters = tracker_monitor.counters();
    tracker_bad = tracker_malformed;
    tracker_source = tracker_monitor.last_source();
  }

  const std::optional<time::Duration> age = pipeline.gateway().vision_age(now);
  const bool stale = !age || *age >= options.vision_timeout;
  const std::string where = options.vision_group + ":" + std::to_string(options.vision_port);
  char text[256];
  if (!age) {
    std::snprintf(text, sizeof text, "no vision yet on %s", where.c_str());
  } else if (stale) {
    std::snprintf(text, sizeof text, "no vision for %.1f s on %s", time::to_seconds(*age), where.c_str());
  } else {
    const auto source = pipeline.gateway().source();
    const std::string from = source ? source->to_string() : "?";
    std::snprintf(text, sizeof text, "%zu camera(s), %.0f frames/s from %s",
                  pipeline.gateway().cameras().size(), rate, from.c_str());
  }
  std::string status = text;
  if (options.tracker_enabled) {
    status += tracker_counters.packets == 0 ? "; no tracker packets" : "; tracker: " + tracker_source;
  }

  dds::HealthLevel level = dds::HealthLevel::kOk;
  if (stale) level = dds::HealthLevel::kWarn;
  if (write_failures > 0) level = dds::HealthLevel::kError;
  const std::uint64_t malformed = pipeline.malformed();
  const dds::HealthReport report{
      .level = level,
      .status = status,
      .rate_hz = rate,
      .latency_p50 = time::to_seconds(summary.p50),
      .latency_p99 = time::to_seconds(summary.p99),
      .errors = write_failures + socket.receive_errors,
      .dropped = malformed + socket.truncated + c.empty_packets + c.foreign_source + c.duplicates +
                 c.out_of_order + tracker_bad,
      .counters = {{"packets", malformed + c.packets},
                   {"malformed", malformed},
                   {"truncated", socket.truncated},
                   {"empty_packets", c.empty_packets},
                   {"duplicates", c.duplicates},
                   {"out_of_order", c.out_of_order},
                   {"camera_restarts", c.camera_restarts},
                   {"foreign_source", c.foreign_source},
                   {"source_switches", c.source_switches},
                   {"frames_published", c.frames_published},
                   {"geometry_packets", c.geometry_packets},
                   {"geometry_updates", c.geometry_updates},
                   {"tracker_packets", tracker_counters.packets},
                   {"tracker_malformed", tracker_bad},
                   {"tracker_frames", tracker_counters.frames},
                   {"tracker_sources", tracker_counters.sources},
                   {"write_failures", write_failures},
                   {"latency_samples", summary.count}},
  };
  if (Status published = health.publish(report); !published) {
    logger->warn("system.health: {}", published.error().message);
  }
  logger->debug("{}; p50 {:.0f} us, p99 {:.0f} us; {} malformed, {} duplicates, {} out of order, {} foreign",
                status, time::to_seconds(summary.p50) * 1e6, time::to_seconds(summary.p99) * 1e6, malformed,
                c.duplicates, c.out_of_order, c.foreign_source);
}

void VisionGatewayService::Impl::vision_loop() {
  while (true) {
    const net::ReceiveResult received = vision.receive(vision_buffer, kReceivePoll);
    if (received.status == net::ReceiveStatus::kInterrupted) break;
    if (received.ok()) {
      const ReceiveTime at{.wall = wall_clock.now(), .monotonic = monotonic_clock.now()};
      handle(std::span<const std::uint8_t>(vision_buffer).first(received.size), received.sender, at);
    } else if (received.status == net::ReceiveStatus::kError) {
      if (receive_errors_logged++ < 10) logger->error("vision receive: {}", received.error);
      monotonic_clock.sleep_for(milliseconds(10));  // never spin on a failing socket
    }
    maybe_report(monotonic_clock.now());
  }
}

void VisionGatewayService::Impl::tracker_loop() {
  while (true) {
    const net::ReceiveResult received = tracker->receive(tracker_buffer, kReceivePoll);
    if (received.status == net::ReceiveStatus::kInterrupted) break;
    if (received.status == net::ReceiveStatus::kError) {
      monotonic_clock.sleep_for(milliseconds(10));
      continue;
    }
    if (!received.ok()) continue;
    const ReceiveTime at{.wall = wall_clock.now(), .monotonic = monotonic_clock.now()};
    Result<TrackerPacket> packet =
        decode_tracker_packet(std::span<const std::uint8_t>(tracker_buffer).first(received.size));
    if (!packet) {
      {
        std::lock_guard lock(tracker_mutex);
        ++tracker_malformed;
      }
      if (const std::uint64_t count = tracker_malformed_log.on_event(at.monotonic)) {
        logger->warn("{} malformed tracker packet(s) dropped (last from {}): {}", count,
                     received.sender.to_string(), packet.error().message);
      }
      continue;
    }
    std::lock_guard lock(tracker_mutex);
    tracker_monitor.on_packet(*packet, at);
  }
}

Result<std::unique_ptr<VisionGatewayService>> VisionGatewayService::create(
    const ServiceOptions& options, dds::Participant& participant, std::shared_ptr<spdlog::logger> logger) {
  auto vision =
      net::MulticastReceiver::open(options.vision_group, options.vision_port, options.interface_address);
  if (!vision) return Error{"vision: " + vision.error().message};
  std::optional<net::MulticastReceiver> tracker;
  if (options.tracker_enabled) {
    auto opened =
        net::MulticastReceiver::open(options.tracker_group, options.tracker_port, options.interface_address);
    if (!opened) return Error{"tracker: " + opened.error().message};
    tracker.emplace(std::move(*opened));
  }
  auto detection = participant.make_writer(dds::topics::kVisionDetection);
  if (!detection) return detection.error();
  auto geometry = participant.make_writer(dds::topics::kVisionGeometry);
  if (!geometry) return geometry.error();
  auto health = dds::HealthReporter::create(participant, options.health_name);
  if (!health) return health.error();
  health->exit_when_stalled();
  auto impl = std::make_unique<Impl>(options, std::move(logger), std::move(*vision), std::move(tracker),
                                     std::move(*detection), std::move(*geometry), std::move(*health));
  return std::unique_ptr<VisionGatewayService>(new VisionGatewayService(std::move(impl)));
}

VisionGatewayService::VisionGatewayService(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

VisionGatewayService::~VisionGatewayService() = default;

void VisionGatewayService::run(ShutdownSignal& shutdown) {
  Impl& impl = *impl_;
  impl.logger->info("listening for vision on {}:{} via {}{}", impl.options.vision_group,
                    impl.options.vision_port, impl.options.interface_address,
                    impl.tracker ? ", tracker on " + impl.options.tracker_group + ":" +
                                       std::to_string(impl.options.tracker_port)
                                 : std::string());
  std::thread vision_thread([&impl] { impl.vision_loop(); });
  std::optional<std::thread> tracker_thread;
  if (impl.tracker) tracker_thread.emplace([&impl] { impl.tracker_loop(); });
  shutdown.wait();
  impl.vision.interrupt();
  if (impl.tracker) impl.tracker->interrupt();
  vision_thread.join();
  if (tracker_thread) tracker_thread->join();
}

}  // namespace ssl::vision_gateway
