// RefereeGatewayService: the referee gateway's DDS adapter. One receive thread owns everything:
//
//   MulticastReceiver(group:port on interface) -> RefereeIngest (decode, convert, core) -> writers
//   referee.event (each new game event once) and referee.state (on a meaningful change and on the
//   heartbeat), plus system.health ("referee_gateway") once per health period.
//
// Health: rate_hz = accepted referee packets per second; level WARN while the referee is stale (no
// accepted packet for stale_after, or none yet) with the age in the status text; errors = DDS write
// failures + socket receive errors; dropped = malformed + foreign-source packets; counters: packets,
// accepted, malformed, foreign_source, source_switches, counter_jumps, events_published,
// states_published, heartbeats, write_failures, receive_errors, referee_age_ms (once a packet arrived),
// and state_readers / event_readers (DDS readers matched by the two writers).
// Logging goes to the logger passed in; repeated warnings of one kind (malformed packets, foreign
// sources, counter jumps, write failures) are throttled to one per log_interval with a count.
//
// Clocks: `wall` stamps receive times (Unix); `monotonic` drives the core's timing and the health period.
//
//   auto service = RefereeGatewayService::open(options, participant, logger, wall, monotonic);
//   if (!service) fail(service.error().message);
//   (*service)->start();
//   shutdown.wait();
//   (*service)->stop();
#pragma once

#include <spdlog/logger.h>

#include <memory>
#include <string>
#include <thread>

#include "libs/common/result.h"
#include "libs/dds/participant.h"
#include "libs/time/clock.h"
#include "services/referee_gateway/core/gateway.h"

namespace ssl::referee {

struct ServiceOptions {
  std::string group = "224.5.23.1";
  int port = 10003;
  std::string interface_address = "127.0.0.1";
  GatewayOptions gateway;
  RefereeSource source = RefereeSource::kGameController;
  time::Duration log_interval = std::chrono::seconds(5);
  time::Duration health_period = std::chrono::seconds(1);
  std::string health_name = "referee_gateway";
};

class RefereeGatewayService {
 public:
  /// Joins the group and creates the writers and the health reporter; the error names what failed
  /// (e.g. "join multicast group 224.5.23.1 on interface ...").
  static Result<std::unique_ptr<RefereeGatewayService>> open(const ServiceOptions& options,
                                                             dds::Participant& participant,
                                                             std::shared_ptr<spdlog::logger> logger,
                                                             time::Clock& wall, time::Clock& monotonic);
  ~RefereeGatewayService();  // stop()
  RefereeGatewayService(const RefereeGatewayService&) = delete;
  RefereeGatewayService& operator=(const RefereeGatewayService&) = delete;

  /// Starts the receive thread (once).
  void start();
  /// Wakes and joins the receive thread; idempotent.
  void stop();

 private:
  struct Impl;
  explicit RefereeGatewayService(std::unique_ptr<Impl> impl);

  std::unique_ptr<Impl> impl_;
  std::thread thread_;
};

}  // namespace ssl::referee
