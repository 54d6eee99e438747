// vision_gateway_benchmark: what the gateway costs and how fast a vision packet reaches DDS readers.
//
// 1. Throughput, one core (Google Benchmark), on a realistic capture instant: four camera packets
//    (Division A, 11 + 11 robots and the ball; each detection in every camera that sees it, 0.3 m overlap),
//    serialized as ssl-vision sends them:
//      BM_DecodeConvertPublishPath  bytes -> decode + validate + mm->m (VisionDecoder) -> core
//      (VisionGateway)
//                                   -> IDL sample (to_idl): everything the gateway does per packet except
//                                   the socket and the DDS write. items/s = packets per second.
//      BM_DecodeConvert, BM_Core, BM_ToIdl  the three stages alone.
//      BM_UnchangedGeometry         a geometry packet that did not change (decode + resolve + compare).
// 2. Packet-to-topic latency (printed after the Google Benchmark table): this process starts the real
//    build/bin/vision_gateway on a private domain and port, multicasts one camera packet at a time to
//    224.5.23.2:<port> on 127.0.0.1 and waits until a DDS reader in THIS process (listener callback on the
//    Fast DDS thread) receives the vision.detection sample with that frame number. Measured on the
//    monotonic clock of this process: from just before sendto() to the reader's callback, so it includes
//    the kernel's loopback multicast, the gateway's receive thread, decode/convert/core, its DataWriter and
//    Fast DDS transport (shared memory between the two processes) to the reader. One packet in flight at
//    a time (no queueing); a 1 s timeout counts a packet as lost. The gateway's own view (receive -> after
//    write, from its last system.health) is printed beside it.
//
//   build/bench/vision_gateway_benchmark [--latency-samples N] [--latency-domain D] [--latency-port P]
//                                        [--no-latency] [Google Benchmark flags]
#include <benchmark/benchmark.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "libs/dds/participant.h"
#include "libs/net/multicast.h"
#include "services/vision_gateway/adapter/convert.h"
#include "services/vision_gateway/adapter/pipeline.h"
#include "services/vision_gateway/testing/builders.h"

extern char** environ;

namespace ssl::vision_gateway {
namespace {

using SteadyClock = std::chrono::steady_clock;
using std::chrono::milliseconds;

const net::Endpoint kSender = *net::Endpoint::parse("127.0.0.1:40000");

/// Serialized camera packets of `instants` capture instants, 4 cameras each, frame numbers 1..instants.
std::vector<std::string> packet_bytes(std::uint32_t instants) {
  std::vector<std::string> packets;
  for (std::uint32_t n = 1; n <= instants; ++n) {
    for (DetectionFrame& frame : testing::four_camera_frame(n, testing::kCaptureSeconds + n / 75.0)) {
      VisionPacket packet;
      packet.detection = std::move(frame);
      packet.source = VisionSource::kSslVision;
      packets.push_back(to_proto(packet).SerializeAsString());
    }
  }
  return packets;
}

std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

constexpr std::uint32_t kInstants = 512;  // distinct frame numbers before the cycle repeats

void BM_DecodeConvertPublishPath(benchmark::State& state) {
  const std::vector<std::string> packets = packet_bytes(kInstants);
  VisionPipeline pipeline{GatewayOptions{}};
  idl::vision::DetectionFrame sample;
  time::Timestamp now = time::Timestamp::from_seconds(1000);
  std::size_t i = 0;
  std::uint64_t published = 0;
  std::size_t bytes = 0;
  for (auto _ : state) {
    if (i == packets.size()) {
      // Frame numbers start again: after a 1 s silence the gateway takes that as a camera restart.
      i = 0;
      now += std::chrono::seconds(1);
    }
    now += std::chrono::microseconds(3333);
    const std::string& packet = packets[i++];
    bytes += packet.size();
    DatagramResult result = pipeline.on_datagram(bytes_of(packet), kSender, {.wall = now, .monotonic = now});
    if (result.output.frame) {
      to_idl(*result.output.frame, sample);
      ++published;
    }
    benchmark::DoNotOptimize(sample);
  }
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
  const auto iterations = static_cast<double>(std::max<std::int64_t>(state.iterations(), 1));
  state.counters["published_fraction"] = static_cast<double>(published) / iterations;
  state.counters["bytes_per_packet"] = static_cast<double>(bytes) / iterations;
}
BENCHMARK(BM_DecodeConvertPublishPath);

void BM_DecodeConvert(benchmark::State& state) {
  const std::vector<std::string> packets = packet_bytes(4);
  VisionDecoder decoder;
  std::size_t i = 0;
  for (auto _ : state) {
    auto packet = decoder.decode(bytes_of(packets[i++ % packets.size()]));
    benchmark::DoNotOptimize(packet);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecodeConvert);

void BM_Core(benchmark::State& state) {
  // Packets are prepared in batches outside the timing (the core takes them by value and moves the frame
  // out), so only on_packet is measured.
  constexpr std::uint32_t kBatchInstants = 1024;
  const std::vector<DetectionFrame> cameras = testing::four_camera_frame(1);
  VisionGateway gateway{GatewayOptions{}};
  time::Timestamp now = time::Timestamp::from_seconds(1000);
  std::uint32_t number = 0;
  std::vector<VisionPacket> batch;
  std::size_t next = 0;
  for (auto _ : state) {
    if (next == batch.size()) {
      state.PauseTiming();
      batch.clear();
      for (std::uint32_t n = 0; n < kBatchInstants; ++n) {
        ++number;
        for (const DetectionFrame& frame : cameras) {
          batch.push_back({.detection = frame});
          batch.back().detection->frame_number = number;
        }
      }
      next = 0;
      state.ResumeTiming();
    }
    now += std::chrono::microseconds(3333);
    PacketOutput out = gateway.on_packet(std::move(batch[next++]), kSender, {.wall = now, .monotonic = now});
    benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Core);

void BM_ToIdl(benchmark::State& state) {
  const std::vector<DetectionFrame> frames = testing::four_camera_frame(1);
  std::vector<PublishedFrame> published;
  for (const DetectionFrame& frame : frames) published.push_back({frame, VisionSource::kSslVision, {}});
  idl::vision::DetectionFrame sample;
  std::size_t i = 0;
  for (auto _ : state) {
    to_idl(published[i++ % published.size()], sample);
    benchmark::DoNotOptimize(sample);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ToIdl);

void BM_UnchangedGeometry(benchmark::State& state) {
  VisionPacket geometry;
  geometry.geometry = testing::full_geometry();
  const std::string bytes = to_proto(geometry).SerializeAsString();
  VisionPipeline pipeline{GatewayOptions{}};
  time::Timestamp now = time::Timestamp::from_seconds(1000);
  for (auto _ : state) {
    now += milliseconds(13);
    DatagramResult result = pipeline.on_datagram(bytes_of(bytes), kSender, {.wall = now, .monotonic = now});
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_UnchangedGeometry);

// ---- packet-to-topic latency through the real process

struct LatencyOptions {
  bool enabled = true;
  int samples = 2000;
  int domain = 179;
  int port = 23990;
};

/// Takes our flags out of argv (Google Benchmark rejects unknown ones).
LatencyOptions parse_latency_flags(int& argc, char** argv) {
  LatencyOptions options;
  int out = 1;
  for (int in = 1; in < argc; ++in) {
    const std::string arg = argv[in];
    auto value = [&](int& target) {
      if (in + 1 < argc) target = std::atoi(argv[++in]);
    };
    if (arg == "--no-latency") {
      options.enabled = false;
    } else if (arg == "--latency-samples") {
      value(options.samples);
    } else if (arg == "--latency-domain") {
      value(options.domain);
    } else if (arg == "--latency-port") {
      value(options.port);
    } else {
      argv[out++] = argv[in];
    }
  }
  argc = out;
  return options;
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size())));
  return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

/// Receives vision.detection samples and signals the frame number of each.
struct Arrivals {
  std::mutex mutex;
  std::condition_variable changed;
  std::uint32_t newest_frame = 0;
  SteadyClock::time_point newest_at;
};

int run_latency(const LatencyOptions& options) {
  std::printf(
      "\n== packet-to-topic latency: multicast sendto() -> vision.detection sample in a reader of another "
      "process (vision_gateway in between), loopback, one packet in flight\n");
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe");
  const std::filesystem::path gateway = self.parent_path().parent_path() / "bin" / "vision_gateway";
  if (!std::filesystem::exists(gateway)) {
    std::printf("skipped: %s not built\n", gateway.c_str());
    return 0;
  }
  auto participant =
      dds::Participant::create({.domain_id = options.domain, .name = "vision_gateway_benchmark"});
  if (!participant) {
    std::printf("skipped: %s\n", participant.error().message.c_str());
    return 1;
  }
  Arrivals arrivals;
  auto reader = participant->make_reader(dds::topics::kVisionDetection, std::nullopt,
                                         [&arrivals](const dds::Sample<idl::vision::DetectionFrame>& s) {
                                           const auto at = SteadyClock::now();
                                           std::lock_guard lock(arrivals.mutex);
                                           arrivals.newest_frame = s.data.frame_number();
                                           arrivals.newest_at = at;
                                           arrivals.changed.notify_all();
                                         });
  auto health = participant->make_reader(dds::topics::kSystemHealth);
  auto sender = net::MulticastSender::open("224.5.23.2", options.port, "127.0.0.1");
  if (!reader || !health || !sender) {
    std::printf("failed: %s\n", !reader   ? reader.error().message.c_str()
                                : !health ? health.error().message.c_str()
                                          : sender.error().message.c_str());
    return 1;
  }

  const std::string port = std::to_string(options.port);
  const std::string domain = std::to_string(options.domain);
  std::vector<std::string> args = {gateway.string(), "--vision-port", port,          "--domain", domain,
                                   "--interface",    "127.0.0.1",     "--log-level", "error"};
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  if (posix_spawn(&pid, gateway.c_str(), nullptr, nullptr, argv.data(), environ) != 0) {
    std::printf("failed to start %s: %s\n", gateway.c_str(), std::strerror(errno));
    return 1;
  }

  // Packets of the four cameras in turn, frame numbers increasing per camera; sample k has frame number k.
  const std::vector<DetectionFrame> cameras = testing::four_camera_frame(1);
  auto packet_for = [&](std::uint32_t k) {
    VisionPacket packet;
    packet.detection = cameras[k % cameras.size()];
    packet.detection->frame_number = k;
    packet.source = VisionSource::kSslVision;
    return to_proto(packet).SerializeAsString();
  };
  auto wait_for = [&](std::uint32_t k,
                      SteadyClock::time_point deadline) -> std::optional<SteadyClock::time_point> {
    std::unique_lock lock(arrivals.mutex);
    if (!arrivals.changed.wait_until(lock, deadline, [&] { return arrivals.newest_frame >= k; }))
      return std::nullopt;
    return arrivals.newest_at;
  };

  // Warm-up: until the gateway is up and discovered, every packet may vanish; resend (bounded) until one
  // arrives, then 200 more unmeasured.
  std::uint32_t k = 1;
  const auto warmup_deadline = SteadyClock::now() + std::chrono::seconds(20);
  bool up = false;
  while (!up && SteadyClock::now() < warmup_deadline) {
    (void)sender->send(bytes_of(packet_for(k)));
    up = wait_for(k, SteadyClock::now() + milliseconds(50)).has_value();
    ++k;
  }
  if (!up) {
    std::printf("failed: no sample from the gateway within 20 s\n");
    kill(pid, SIGTERM);
    waitpid(pid, nullptr, 0);
    return 1;
  }
  for (int i = 0; i < 200; ++i, ++k) {
    (void)sender->send(bytes_of(packet_for(k)));
    (void)wait_for(k, SteadyClock::now() + std::chrono::seconds(1));
  }

  std::vector<double> latencies_us;
  std::size_t lost = 0;
  std::size_t bytes = 0;
  for (int i = 0; i < options.samples; ++i, ++k) {
    const std::string packet = packet_for(k);
    bytes += packet.size();
    const auto sent = SteadyClock::now();
    (void)sender->send(bytes_of(packet));
    const auto arrived = wait_for(k, sent + std::chrono::seconds(1));
    if (!arrived) {
      ++lost;
      continue;
    }
    latencies_us.push_back(std::chrono::duration<double, std::micro>(*arrived - sent).count());
  }

  // The gateway's own stage latency (receive -> after write) from its health, one report per second.
  std::optional<dds::Sample<idl::system::Health>> report;
  const auto health_deadline = SteadyClock::now() + std::chrono::seconds(3);
  while (SteadyClock::now() < health_deadline) {
    if (!health->wait_for_data(milliseconds(200))) continue;
    for (auto& sample : health->take()) {
      if (sample.data.service() == "vision_gateway" && sample.data.latency_p50() > 0) report = sample;
    }
    if (report) break;
  }
  kill(pid, SIGTERM);
  waitpid(pid, nullptr, 0);

  std::printf("samples %zu (lost %zu), %.0f bytes per packet (one camera of the 22-robot frame)\n",
              latencies_us.size(), lost, static_cast<double>(bytes) / std::max(options.samples, 1));
  std::printf("packet-to-topic latency: median %.1f us, p99 %.1f us, max %.1f us\n",
              percentile(latencies_us, 0.5), percentile(latencies_us, 0.99), percentile(latencies_us, 1.0));
  if (report) {
    std::printf(
        "gateway stage (its system.health, last second: receive -> after DDS write): p50 %.1f us, "
        "p99 %.1f us\n",
        report->data.latency_p50() * 1e6, report->data.latency_p99() * 1e6);
  }
  return lost * 100 > static_cast<std::size_t>(options.samples) ? 1 : 0;
}

}  // namespace
}  // namespace ssl::vision_gateway

int main(int argc, char** argv) {
  const auto latency = ssl::vision_gateway::parse_latency_flags(argc, argv);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return latency.enabled ? ssl::vision_gateway::run_latency(latency) : 0;
}
