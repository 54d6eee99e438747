// RefereeIngest: one datagram of the referee multicast group in, the core's decision out. It decodes the
// bytes (libs/league/decode.h: never throws, never reads outside the buffer), converts the Referee
// message once to SI (convert.h) and steps the core (core/gateway.h). Malformed datagrams — random bytes,
// truncated packets, packets missing required fields — are counted and their error returned, never a
// crash. No DDS, no sockets, no threads: the service (service.h) feeds it from its receive thread, and
// tests feed it bytes directly.
//
// Clocks: `receive_wall` (this host's wall clock, Unix) is stamped on the outputs; `now` (monotonic)
// drives the core's heartbeat, staleness and source switching.
//
//   RefereeIngest ingest({.heartbeat_period = 1s});
//   IngestResult result = ingest.handle(bytes, wall.now(), monotonic.now());
//   if (result.malformed) log_throttled(result.malformed->message);
//   else publish(result.output);
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "libs/common/result.h"
#include "libs/time/time.h"
#include "services/referee_gateway/core/gateway.h"

namespace ssl::referee {

struct IngestResult {
  StepOutput output;               // empty (nothing to publish) when malformed
  std::optional<Error> malformed;  // why the datagram was rejected
};

class RefereeIngest {
 public:
  explicit RefereeIngest(GatewayOptions options, RefereeSource source = RefereeSource::kGameController)
      : core_(std::move(options)), source_(source) {}

  IngestResult handle(std::span<const std::uint8_t> bytes, time::Timestamp receive_wall, time::Timestamp now);

  /// Counts a datagram that did not fit the receive buffer (it is malformed by definition).
  void count_truncated() noexcept { ++malformed_; }

  /// Datagrams that could not be decoded (or were truncated).
  std::uint64_t malformed() const noexcept { return malformed_; }
  const RefereeGateway& core() const noexcept { return core_; }

 private:
  RefereeGateway core_;
  RefereeSource source_;
  std::uint64_t malformed_ = 0;
};

}  // namespace ssl::referee
