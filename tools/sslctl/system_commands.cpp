#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "idl/idl_json.h"
#include "libs/common/percentile.h"
#include "libs/dds/participant.h"
#include "tools/sslctl/commands.h"
#include "tools/sslctl/participant.h"

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
  auto participant = open_participant(dds_options.domain_id, dds_options.site, dds_options.team, "sslctl/estop");
  if (!participant) {
    err << "sslctl: " << participant.error().message << '\n';
    return 1;
  }
  auto writer = participant->make_writer(dds::topics::kSystemEstop, dds_options.team);
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
  out << "e-stop " << (engage ? "ENGAGED" : "released") << " for "
      << (dds_options.team ? "team " + std::string(to_string(*dds_options.team)) : std::string("every team"))
      << " on domain " << dds_options.domain_id << " ("
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
  auto participant = open_participant(dds_options.domain_id, dds_options.site, dds_options.team, "sslctl/health");
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

namespace {

/// Latencies of one pipeline stage, ms.
struct Stage {
  std::string name;
  std::string path;  // what the latency spans
  std::vector<double> ms;
};

}  // namespace

int latency(const LatencyOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err) {
  auto participant = open_participant(options.domain_id, options.site, std::nullopt, "sslctl/latency");
  if (!participant) {
    err << "sslctl: " << participant.error().message << '\n';
    return 1;
  }
  const char* from_gateway = "vision_gateway receive -> here";
  std::vector<Stage> stages = {
      {"vision delay", "capture (vision host) -> vision_gateway receive", {}},
      {"vision.detection", from_gateway, {}},
      {"world.state/blue", from_gateway, {}},
      {"world.state/yellow", from_gateway, {}},
      {"robot.commands/blue", from_gateway, {}},
      {"robot.commands/yellow", from_gateway, {}},
      // robot_link's own stamp of when the packet left (robot.sent): the end of the path.
      {"command out of robot_link/blue", "vision_gateway receive -> command packet out of robot_link", {}},
      {"command out of robot_link/yellow", "vision_gateway receive -> command packet out of robot_link", {}},
  };
  // Callback readers: every sample counts when it arrives (a polled keep-last-1 reader would miss some),
  // with the time it arrived. The callbacks run on Fast DDS threads.
  std::mutex mutex;
  auto add = [&](std::size_t stage, std::int64_t from_ns, std::int64_t to_ns) {
    if (from_ns <= 0 || to_ns <= 0) return;
    std::lock_guard lock(mutex);
    stages[stage].ms.push_back(static_cast<double>(to_ns - from_ns) * 1e-6);
  };
  auto vision = participant->make_reader(
      dds::topics::kVisionDetection, std::nullopt, [&](const dds::Sample<idl::vision::DetectionFrame>& sample) {
        add(0, sample.data.capture_unix_ns(), sample.data.receive_unix_ns());
        add(1, sample.data.receive_unix_ns(), sample.reception_unix_ns);
      });
  if (!vision) {
    err << "sslctl: " << vision.error().message << '\n';
    return 1;
  }
  std::vector<dds::Reader<idl::world::WorldState>> worlds;
  std::vector<dds::Reader<idl::robot::RobotCommands>> commands;
  std::vector<dds::Reader<idl::robot::CommandsSent>> sent;
  for (const std::size_t team : {0u, 1u}) {
    const TeamColor color = team == 0 ? TeamColor::kBlue : TeamColor::kYellow;
    auto world = participant->make_reader(
        dds::topics::kWorldState, color, [&add, team](const dds::Sample<idl::world::WorldState>& sample) {
          add(2 + team, sample.data.stamp().receive_unix_ns(), sample.reception_unix_ns);
        });
    auto command = participant->make_reader(
        dds::topics::kRobotCommands, color, [&add, team](const dds::Sample<idl::robot::RobotCommands>& sample) {
          add(4 + team, sample.data.stamp().receive_unix_ns(), sample.reception_unix_ns);
        });
    // Only the packet that first carried a sample: a heartbeat's resend is not the path's latency.
    auto packets = participant->make_reader(
        dds::topics::kRobotSent, color, [&add, team](const dds::Sample<idl::robot::CommandsSent>& sample) {
          if (!sample.data.resend()) add(6 + team, sample.data.stamp().receive_unix_ns(), sample.data.sent_unix_ns());
        });
    if (!world || !command || !packets) {
      err << "sslctl: "
          << (!world ? world.error().message : !command ? command.error().message : packets.error().message)
          << '\n';
      return 1;
    }
    worlds.push_back(std::move(*world));
    commands.push_back(std::move(*command));
    sent.push_back(std::move(*packets));
  }
  shutdown.wait_for(duration_cast<nanoseconds>(duration<double>(options.listen_s)));
  // Stop the callbacks (delete the readers) before reading what they collected.
  { auto closed = std::move(*vision); }
  worlds.clear();
  commands.clear();
  sent.clear();
  std::lock_guard lock(mutex);
  bool any = false;
  if (!options.json) {
    out << std::left << std::setw(34) << "STAGE" << std::setw(9) << "SAMPLES" << std::setw(10) << "P50 ms"
        << std::setw(10) << "P99 ms" << std::setw(10) << "MAX ms" << "SPAN\n";
  }
  for (Stage& stage : stages) {
    if (stage.ms.empty()) continue;
    any = true;
    const double max = *std::max_element(stage.ms.begin(), stage.ms.end());
    const double p50 = percentile(stage.ms, 0.5);
    const double p99 = percentile(stage.ms, 0.99);
    if (options.json) {
      out << nlohmann::json{{"stage", stage.name}, {"span", stage.path}, {"samples", stage.ms.size()},
                            {"p50_ms", p50}, {"p99_ms", p99}, {"max_ms", max}}
                 .dump()
          << '\n';
      continue;
    }
    out << std::left << std::setw(34) << stage.name << std::setw(9) << stage.ms.size() << std::fixed
        << std::setprecision(3) << std::setw(10) << p50 << std::setw(10) << p99 << std::setw(10) << max
        << stage.path << '\n';
  }
  if (!any) {
    err << "sslctl: no vision.detection, world.state, robot.commands or robot.sent sample on domain " << options.domain_id
        << " within " << options.listen_s << " s\n";
    return 1;
  }
  return 0;
}

}  // namespace ssl::sslctl
