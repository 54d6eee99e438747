// VisionGatewayService: the gateway's network and DDS face. It owns
//   * a MulticastReceiver on the SSL-Vision group (224.5.23.2:10006, or :10020 for simulators) joined on
//     the configured interface, read by one thread that runs, per datagram: decode + convert + core
//     (VisionPipeline) -> vision.detection (one sample per accepted camera frame, with capture, sent and
//     receive times) and vision.geometry (reliable, transient local: on the first geometry and on changes);
//   * optionally a second receiver + thread for tracked vision (224.5.23.2:10010), decoded and counted;
//   * the system.health reporter ("vision_gateway"), published from the vision thread once per second:
//     published frames/s, packet-to-publish latency p50/p99 over the last second (monotonic clock, from
//     right after the datagram left the socket to right after the last DDS write it caused), counters,
//     and level WARN when no frame was published for `vision_timeout` (ERROR when DDS writes fail).
// Malformed datagrams are counted and logged at most once per `malformed_log_interval` with their count.
// The core is only touched by the vision thread; the tracker monitor is shared under a mutex.
//
//   auto service = VisionGatewayService::create(options, participant, logger);
//   if (!service) { logger->critical("{}", service.error().message); return 1; }
//   (*service)->run(shutdown);   // until SIGINT/SIGTERM
#pragma once

#include <spdlog/logger.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "libs/common/result.h"
#include "libs/common/shutdown.h"
#include "libs/dds/participant.h"
#include "services/vision_gateway/core/gateway.h"

namespace ssl::vision_gateway {

struct ServiceOptions {
  GatewayOptions gateway;
  std::string interface_address = "127.0.0.1";
  std::string vision_group = "224.5.23.2";
  int vision_port = 10006;
  bool tracker_enabled = false;
  std::string tracker_group = "224.5.23.2";
  int tracker_port = 10010;
  time::Duration vision_timeout = std::chrono::seconds(1);
  time::Duration malformed_log_interval = std::chrono::seconds(1);
  time::Duration health_period = std::chrono::seconds(1);
  std::string health_name = "vision_gateway";  // system.health key
};

class VisionGatewayService {
 public:
  /// Joins the multicast group(s) and creates the DDS writers. Errors name the group, port and interface
  /// or the DDS entity that failed.
  static Result<std::unique_ptr<VisionGatewayService>> create(const ServiceOptions& options,
                                                              dds::Participant& participant,
                                                              std::shared_ptr<spdlog::logger> logger);
  ~VisionGatewayService();
  VisionGatewayService(const VisionGatewayService&) = delete;
  VisionGatewayService& operator=(const VisionGatewayService&) = delete;

  /// Receives, converts and publishes until `shutdown` is requested; then stops and joins its threads.
  void run(ShutdownSignal& shutdown);

 private:
  struct Impl;
  explicit VisionGatewayService(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace ssl::vision_gateway
