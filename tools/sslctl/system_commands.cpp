#include <chrono>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "idl/idl_json.h"
#include "libs/dds/participant.h"
#include "tools/sslctl/commands.h"

namespace ssl::sslctl {
namespace {

using std::chrono::duration;
using std::chrono::duration_cast;
using std::chrono::nanoseconds;

std::int64_t wall_clock_unix_ns() {
  return duration_cast<nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace

int estop(bool engage, const std::string& reason, const DdsOptions& dds_options, double linger_s,
          ShutdownSignal& shutdown, std::ostream& out, std::ostream& err) {
  auto participant = dds::Participant::create({.domain_id = dds_options.domain_id, .name = "sslctl/estop"});
  if (!participant) {
    err << "sslctl: " << participant.error().message << '\n';
    return 1;
  }
  auto writer = participant->make_writer(dds::topics::kSystemEstop);
  if (!writer) {
    err << "sslctl: " << writer.error().message << '\n';
    return 1;
  }
  idl::system::Estop sample;
  sample.engaged(engage);
  sample.source("sslctl@" + std::to_string(getpid()));
  sample.reason(reason);
  sample.stamp_unix_ns(wall_clock_unix_ns());
  if (auto written = writer->write(sample); !written) {
    err << "sslctl: " << written.error().message << '\n';
    return 1;
  }
  writer->wait_for_acknowledgments(std::chrono::seconds(2));
  out << "e-stop " << (engage ? "ENGAGED" : "released") << " on domain " << dds_options.domain_id << " ("
      << writer->counters().matched_readers << " reader(s) matched)\n" << std::flush;
  // The sample stays available to late joiners only while this writer lives.
  if (linger_s < 0) {
    shutdown.wait();
  } else if (linger_s > 0) {
    shutdown.wait_for(duration_cast<nanoseconds>(duration<double>(linger_s)));
  }
  return 0;
}

int health(const DdsOptions& dds_options, double listen_s, bool json, ShutdownSignal& shutdown,
           std::ostream& out, std::ostream& err) {
  auto participant = dds::Participant::create({.domain_id = dds_options.domain_id, .name = "sslctl/health"});
  if (!participant) {
    err << "sslctl: " << participant.error().message << '\n';
    return 1;
  }
  auto reader = participant->make_reader(dds::topics::kSystemHealth);
  if (!reader) {
    err << "sslctl: " << reader.error().message << '\n';
    return 1;
  }
  // Health is published once per second per service: listen long enough to hear everyone once.
  std::map<std::string, idl::system::Health> latest;
  const auto deadline = std::chrono::steady_clock::now() + duration_cast<nanoseconds>(duration<double>(listen_s));
  while (!shutdown.requested() && std::chrono::steady_clock::now() < deadline) {
    reader->wait_for_data(std::chrono::milliseconds(100));
    for (auto& sample : reader->take()) latest[sample.data.service()] = std::move(sample.data);
  }
  if (json) {
    for (const auto& [name, health] : latest) out << nlohmann::json(health).dump() << '\n';
    return 0;
  }
  if (latest.empty()) {
    out << "no service published health on domain " << dds_options.domain_id << " within " << listen_s << " s\n";
    return 1;
  }
  out << std::left << std::setw(24) << "SERVICE" << std::setw(8) << "LEVEL" << std::setw(10) << "RATE Hz"
      << std::setw(12) << "P99 ms" << std::setw(10) << "ERRORS" << std::setw(10) << "DROPPED" << "STATUS\n";
  for (const auto& [name, health] : latest) {
    out << std::left << std::setw(24) << name << std::setw(8)
        << idl::system::to_string(health.level()).substr(std::string_view("HEALTH_").size()) << std::setw(10)
        << std::fixed << std::setprecision(1) << health.rate_hz() << std::setw(12) << std::setprecision(3)
        << health.latency_p99() * 1e3 << std::setw(10) << health.errors() << std::setw(10) << health.dropped()
        << health.status() << '\n';
  }
  return 0;
}

}  // namespace ssl::sslctl
