// HealthReporter: publishes one service instance's system.health sample (rate, latency, errors, dropped
// inputs and named counters). Services call publish() from their own loop every period(): once a second,
// and every 0.1 s while they start (until their first HEALTH_OK report), so that a restarted service is
// seen healthy as soon as it hears its inputs rather than up to a second later. Each report also tells the
// service manager (libs/common/service_manager.h): READY=1 with the first report once
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

  /// How long after this report the next one is due: at most kStartupPeriod until a report said HEALTH_OK
  /// (for at most kStartupReports reports: a service that never gets its inputs falls back), then `steady`
  /// (the service's own period, kPeriod unless configured). Rates in a report are over the time since the
  /// previous one, not per period.
  std::chrono::nanoseconds period(std::chrono::nanoseconds steady = kPeriod) const;

  static constexpr std::chrono::nanoseconds kPeriod = std::chrono::seconds(1);
  static constexpr std::chrono::nanoseconds kStartupPeriod = std::chrono::milliseconds(100);
  static constexpr int kStartupReports = 100;

  /// READY waits until `inputs_matched()` holds (the service's DDS readers of what it needs have matched a
  /// writer: the planner a world.state writer), or until `grace` passed since the reporter was made, so
  /// that a host whose peers are not up yet still comes up within the unit's TimeoutStartSec. The
  /// condition must stay valid when the reporter moves (capture reader handles by value).
  void ready_when(std::function<bool()> inputs_matched, std::chrono::nanoseconds grace = kReadyGrace);

  static constexpr std::chrono::nanoseconds kReadyGrace = std::chrono::seconds(10);

  /// From now on a report that comes longer than the participant's lease after the previous one ends the
  /// process with kExitStalled (after a line on stderr), for its supervisor (./ssl up, systemd) to start a
  /// fresh one. Such a gap means the whole process stood still (SIGSTOP, a suspended host, swapping)
  /// long enough for its peers to drop its participant; Fast DDS 2.9 then never rejoins them (measured:
  /// a planner resumed after 3.5 s stayed without world.state), while a new process is matched within a
  /// second. The same limit as the units' WatchdogSec. Only for loops that report continuously (not a
  /// lockstep simulator waiting for its client).
  void exit_when_stalled();

  static constexpr int kExitStalled = 75;  // EX_TEMPFAIL

 private:
  HealthReporter(Writer<idl::system::Health> writer, std::string service, std::chrono::nanoseconds lease);

  Writer<idl::system::Health> writer_;
  std::string service_;
  std::string host_;
  std::int64_t start_unix_ns_ = 0;
  bool ready_sent_ = false;  // READY=1 went to the service manager
  bool reported_ok_ = false;  // some report said HEALTH_OK
  int reports_ = 0;
  std::function<bool()> inputs_matched_;  // empty: ready with the first report
  std::chrono::nanoseconds lease_;        // the participant's
  bool exit_when_stalled_ = false;
  std::chrono::steady_clock::time_point last_report_;
  std::chrono::nanoseconds ready_grace_ = kReadyGrace;
};

}  // namespace ssl::dds
