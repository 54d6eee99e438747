#include "libs/dds/health.h"

#include "libs/common/service_manager.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace ssl::dds {
namespace {

std::int64_t wall_clock_unix_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

}  // namespace

Result<HealthReporter> HealthReporter::create(Participant& participant, std::string service) {
  auto writer = participant.make_writer(topics::kSystemHealth);
  if (!writer) return writer.error();
  return HealthReporter(std::move(*writer), std::move(service), participant.lease_duration());
}

HealthReporter::HealthReporter(Writer<idl::system::Health> writer, std::string service,
                               std::chrono::nanoseconds lease)
    : writer_(std::move(writer)),
      service_(std::move(service)),
      host_(host_name()),
      start_unix_ns_(wall_clock_unix_ns()),
      lease_(lease),
      last_report_(std::chrono::steady_clock::now()) {}

void HealthReporter::exit_when_stalled() {
  exit_when_stalled_ = true;
  last_report_ = std::chrono::steady_clock::now();
}

Status HealthReporter::publish(const HealthReport& report) {
  const auto reported = std::chrono::steady_clock::now();
  if (exit_when_stalled_ && reported - last_report_ > lease_) {
    std::fprintf(stderr,
                 "%s: stood still %.1f s, longer than the DDS lease (%.1f s): its peers dropped this process, which "
                 "would not rejoin them; exiting (%d) for a fresh start\n",
                 service_.c_str(), std::chrono::duration<double>(reported - last_report_).count(),
                 std::chrono::duration<double>(lease_).count(), kExitStalled);
    std::fflush(stderr);
    std::_Exit(kExitStalled);  // as if killed: the restart path every service already survives
  }
  last_report_ = reported;
  idl::system::Health sample;
  sample.service(service_);
  sample.host(host_);
  sample.pid(static_cast<std::uint32_t>(getpid()));
  switch (report.level) {
    case HealthLevel::kOk: sample.level(idl::system::HEALTH_OK); break;
    case HealthLevel::kWarn: sample.level(idl::system::HEALTH_WARN); break;
    case HealthLevel::kError: sample.level(idl::system::HEALTH_ERROR); break;
  }
  sample.status(report.status);
  sample.rate_hz(report.rate_hz);
  sample.latency_p50(report.latency_p50);
  sample.latency_p99(report.latency_p99);
  sample.errors(report.errors);
  sample.dropped(report.dropped);
  for (const auto& [name, value] : report.counters) {
    idl::system::Counter counter;
    counter.name(name);
    counter.value(value);
    sample.counters().push_back(std::move(counter));
  }
  const std::int64_t now = wall_clock_unix_ns();
  sample.uptime_ns(now - start_unix_ns_);
  sample.stamp_unix_ns(now);
  Status written = writer_.write(sample);
  ++reports_;
  reported_ok_ = reported_ok_ || report.level == HealthLevel::kOk;
  // The service manager hears the same: up once the loop reports and hears its inputs (or the grace
  // passed), alive while it keeps reporting.
  const bool matched = !inputs_matched_ || inputs_matched_();
  const bool grace_over = std::chrono::nanoseconds(now - start_unix_ns_) >= ready_grace_;
  if (!ready_sent_ && (matched || grace_over)) {
    service_manager::ready(matched ? report.status : report.status + " (up without its inputs: none heard yet)");
    ready_sent_ = true;
  } else {
    service_manager::alive(ready_sent_ ? report.status : report.status + " (waiting for its inputs)");
  }
  return written;
}

std::chrono::nanoseconds HealthReporter::period(std::chrono::nanoseconds steady) const {
  return reported_ok_ || reports_ >= kStartupReports ? steady : std::min(steady, kStartupPeriod);
}

void HealthReporter::ready_when(std::function<bool()> inputs_matched, std::chrono::nanoseconds grace) {
  inputs_matched_ = std::move(inputs_matched);
  ready_grace_ = grace;
}

}  // namespace ssl::dds
