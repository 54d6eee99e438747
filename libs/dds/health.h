// HealthReporter: publishes one service instance's system.health sample (rate, latency, errors, dropped
// inputs and named counters). Services call publish() about once per second from their own loop; each
// report also tells the service manager (libs/common/service_manager.h): READY=1 with the first report once
// the service's inputs are matched (ready_when; without it, the first report), WATCHDOG=1 with every one.
//
//   ssl::dds::HealthReporter health(participant, "simulator");
//   health.publish({.level = HealthLevel::kOk, .status = "running", .rate_hz = 500,
//                   .counters = {{"vision_packets_sent", n}}});
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "libs/common/result.h"
#include "libs/dds/participant.h"

namespace ssl::dds {

enum class HealthLevel { kOk, kWarn, kError };

struct HealthReport {
  HealthLevel level = HealthLevel::kOk;
  std::string status;             // short human text
  double rate_hz = 0;             // main loop or output rate
  double latency_p50 = 0;         // s
  double latency_p99 = 0;         // s
  std::uint64_t errors = 0;
  std::uint64_t dropped = 0;      // inputs counted and dropped (malformed, stale, ...)
  std::vector<std::pair<std::string, std::uint64_t>> counters;
};

class HealthReporter {
 public:
  /// `service` is the instance name, e.g. "simulator" or "world_model/blue" (the sample's key).
  static Result<HealthReporter> create(Participant& participant, std::string service);

  /// Publishes one sample stamped with the wall clock and the reporter's uptime.
  Status publish(const HealthReport& report);

  /// READY waits until `inputs_matched()` holds (the service's DDS readers of what it needs have matched a
  /// writer: the planner a world.state writer), or until `grace` passed since the reporter was made, so
  /// that a host whose peers are not up yet still comes up within the unit's TimeoutStartSec. The
  /// condition must stay valid when the reporter moves (capture reader handles by value).
  void ready_when(std::function<bool()> inputs_matched, std::chrono::nanoseconds grace = kReadyGrace);

  static constexpr std::chrono::nanoseconds kReadyGrace = std::chrono::seconds(10);

 private:
  HealthReporter(Writer<idl::system::Health> writer, std::string service);

  Writer<idl::system::Health> writer_;
  std::string service_;
  std::string host_;
  std::int64_t start_unix_ns_ = 0;
  bool ready_sent_ = false;  // READY=1 went to the service manager
  std::function<bool()> inputs_matched_;  // empty: ready with the first report
  std::chrono::nanoseconds ready_grace_ = kReadyGrace;
};

}  // namespace ssl::dds
