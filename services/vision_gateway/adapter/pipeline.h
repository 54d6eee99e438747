// VisionPipeline: what the gateway does with one received datagram, minus the network and DDS: decode and
// convert it (VisionDecoder: malformed or oversized datagrams become a counted error, never a crash) and
// hand the packet to the core (VisionGateway). The service runs one pipeline on its receive thread;
// tests and the benchmark drive it directly with bytes.
//
// Also here: LogThrottle, the "log at most once per interval, with the count since the last line" helper
// the service uses for malformed packets (time is an argument, so it is testable).
//
//   VisionPipeline pipeline(gateway_options);
//   DatagramResult r = pipeline.on_datagram(bytes, sender, {.wall = wall_now, .monotonic = mono_now});
//   if (r.malformed) throttle_and_log(*r.malformed);
//   if (r.output.frame) publish(*r.output.frame);
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "libs/net/endpoint.h"
#include "services/vision_gateway/adapter/convert.h"
#include "services/vision_gateway/core/gateway.h"

namespace ssl::vision_gateway {

struct DatagramResult {
  PacketOutput output;                   // empty when the datagram was malformed
  std::optional<std::string> malformed;  // why the datagram was rejected (decoder or validation message)
};

class VisionPipeline {
 public:
  explicit VisionPipeline(GatewayOptions options) : gateway_(std::move(options)) {}

  DatagramResult on_datagram(std::span<const std::uint8_t> bytes, const net::Endpoint& sender,
                             const ReceiveTime& received);

  /// Datagrams that did not decode or failed validation (never reach the core).
  std::uint64_t malformed() const noexcept { return malformed_; }
  const VisionGateway& gateway() const noexcept { return gateway_; }

 private:
  VisionDecoder decoder_;
  VisionGateway gateway_;
  std::uint64_t malformed_ = 0;
};

/// Allows one log line per `interval` (monotonic time) and counts the events in between, so a flood of
/// bad packets costs one line per second: "42 malformed vision packets in the last 1.0 s; last: ...".
class LogThrottle {
 public:
  explicit LogThrottle(time::Duration interval) : interval_(interval) {}

  /// Counts one event; returns how many events the caller should report now (this one included), or 0
  /// when it must stay quiet.
  std::uint64_t on_event(time::Timestamp now_monotonic);

 private:
  time::Duration interval_;
  std::optional<time::Timestamp> last_logged_;
  std::uint64_t pending_ = 0;
};

}  // namespace ssl::vision_gateway
