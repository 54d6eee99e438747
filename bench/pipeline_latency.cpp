// pipeline_latency: how long a vision packet takes to become a command datagram, through the real
// vision_gateway, world_model, planner and robot_link of one team in one run, beside a bare UDP relay over
// the same four hops.
//
// The pipeline: this process starts the four services (blue, private DDS domain and UDP ports), publishes
// referee.state FORCE_START (so the planner runs its full tree, not HALT's shortcut) and multicasts
// SSL_WrapperPacket detection frames to vision_gateway on 127.0.0.1: six robots per team and the ball, all
// moving, from --cameras cameras that each see the whole field, each at --rate Hz, their phases spread over
// the frame period. robot_link (sim backend) sends its RobotControl datagrams to a UDP port of this process.
//
// Which frame a datagram descends from: robot_link writes robot.sent for every packet it sends (the
// VisionStamp of the robot.commands sample it carried, whether that sample was sent before, the send
// time). Datagrams and robot.sent samples are paired in order, within 2 ms of each other. A packet that
// carried a sample for the first time gives one measurement: from just before this process's sendto() of
// that camera frame to this process receiving the datagram, both on this host's wall clock. Frames that
// never reached the radio as a new command (superseded by a newer frame before robot_link had a token,
// when frames come faster than the radio's rate) are counted, not measured.
//
// The relay: four processes (this program with --relay IN OUT), each receiving on a loopback UDP port and
// sending what it got to the next, the last to this process; the same packets at the same times. Measured
// from sendto() to receive, the frame recognised by its content.
//
// Prints median, p99 and max of both, their ratios, where the pipeline's time goes (from robot.sent's
// stamps), the time to the frame's first robot.commands sample (received here: the three-process figure),
// and "BUDGET <name> <value>" lines for ./ssl bench (bench/budget_table.cpp holds the budgets).
// Exits non-zero only when it cannot run (a process does not start, nothing arrives); a budget it misses
// is reported, not failed. Figures taken on a loaded machine are noisy: `uptime` is printed beside them.
//
// Two runs: --cameras (1) at --rate (75 Hz), slower than the radio's 100 Hz, whose figures are the budget's;
// then --rate-limited-cameras (4) at the same rate, faster than the radio,
// where robot_link's token bucket may add up to one radio period (the budget's allowance).
//
//   build/bench/pipeline_latency [--frames N] [--cameras C] [--rate-limited-cameras C] [--rate HZ]
//                                [--domain D] [--port P]
//   (ports P: vision, P+1: commands, P+2..P+5: relays, P+6: relay out)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <set>
#include <fstream>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "bench/sample_stats.h"
#include "libs/dds/participant.h"
#include "libs/net/multicast.h"
#include "libs/net/udp.h"
#include "proto/ssl_vision_wrapper.pb.h"
#include "tests/support/process.h"

namespace {

using namespace std::chrono_literals;
using SteadyClock = std::chrono::steady_clock;
using ssl::testing::ChildProcess;

constexpr int kRobotsPerTeam = 6;
constexpr std::int64_t kPairingToleranceNs = 2'000'000;  // a datagram and its robot.sent sample
constexpr auto kStartTimeout = 30s;
constexpr std::uint32_t kWarmupFrames = 150;  // per camera, after the first command arrived

std::int64_t wall_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

struct Options {
  std::uint32_t frames = 1500;  // measured, per camera
  std::uint32_t cameras = 1;    // the budgeted run: frames slower than the radio's rate
  std::uint32_t rate_limited_cameras = 4;  // a second run above the radio's rate (0: none)
  double rate = 75;             // Hz per camera
  int domain = 196;             // of this bench only
  int port = 44700;
};

using ssl::bench::SampleStats;
using ssl::bench::summarize;

int fail(const std::string& message) {
  std::fprintf(stderr, "pipeline_latency: %s\n", message.c_str());
  return 1;
}

std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

/// One camera's detection frame at `t` (Unix s): both teams' robots and the ball on slow circles (mm).
std::string wrapper_bytes(std::uint32_t camera, std::uint32_t frame_number, double t) {
  SSL_WrapperPacket packet;
  SSL_DetectionFrame& frame = *packet.mutable_detection();
  frame.set_frame_number(frame_number);
  frame.set_t_capture(t);
  frame.set_t_sent(t);
  frame.set_camera_id(camera);
  SSL_DetectionBall& ball = *frame.add_balls();
  ball.set_confidence(0.95f);
  ball.set_x(static_cast<float>(1500 * std::cos(0.5 * t)));
  ball.set_y(static_cast<float>(1000 * std::sin(0.5 * t)));
  ball.set_pixel_x(0);
  ball.set_pixel_y(0);
  for (int team = 0; team < 2; ++team) {
    for (int id = 0; id < kRobotsPerTeam; ++id) {
      SSL_DetectionRobot& robot = team == 0 ? *frame.add_robots_blue() : *frame.add_robots_yellow();
      const double side = team == 0 ? -1 : 1;
      const double phase = 0.3 * t + id;
      robot.set_confidence(0.9f);
      robot.set_robot_id(static_cast<std::uint32_t>(id));
      robot.set_x(static_cast<float>(side * (1000 + 500 * id) + 300 * std::cos(phase)));
      robot.set_y(static_cast<float>(-2000 + 800 * id + 300 * std::sin(phase)));
      robot.set_orientation(static_cast<float>(phase));
      robot.set_pixel_x(0);
      robot.set_pixel_y(0);
      robot.set_height(150);
    }
  }
  return packet.SerializeAsString();
}

/// Where camera frames are sent: frame numbers 1, 2, ... per camera; their sendto() times by (camera, number).
class FrameClock {
 public:
  explicit FrameClock(const Options& options) : options_(options), sent_ns_(options.cameras) {}

  /// Sends frame `number` of every camera at its time from `start` (the cameras' phases spread evenly),
  /// through `send`; `between` runs while waiting.
  template <typename Send, typename Between>
  void send_frame(std::uint32_t number, SteadyClock::time_point start, Send&& send, Between&& between) {
    const double period = 1.0 / options_.rate;
    for (std::uint32_t camera = 0; camera < options_.cameras; ++camera) {
      const double offset = period * (number + static_cast<double>(camera) / options_.cameras);
      const auto due = start + std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(offset));
      between();
      std::this_thread::sleep_until(due);
      const std::string bytes = wrapper_bytes(camera, number, static_cast<double>(wall_ns()) * 1e-9);
      auto& times = sent_ns_[camera];
      if (times.size() <= number) times.resize(number + 1, 0);
      times[number] = wall_ns();
      send(bytes);
    }
  }

  /// When frame `number` of `camera` was sent (0: never).
  std::int64_t sent_ns(std::uint32_t camera, std::uint32_t number) const {
    if (camera >= sent_ns_.size() || number >= sent_ns_[camera].size()) return 0;
    return sent_ns_[camera][number];
  }

 private:
  const Options& options_;
  std::vector<std::vector<std::int64_t>> sent_ns_;
};

/// Receives datagrams on a loopback port on its own thread, stamping each on arrival (wall clock).
class DatagramSink {
 public:
  struct Arrival {
    std::int64_t at_ns;
    std::string bytes;
  };

  static ssl::Result<std::unique_ptr<DatagramSink>> open(int port) {
    auto socket = ssl::net::UdpSocket::open("127.0.0.1", port);
    if (!socket) return socket.error();
    return std::unique_ptr<DatagramSink>(new DatagramSink(std::move(*socket)));
  }
  ~DatagramSink() {
    socket_.interrupt();
    thread_.join();
  }
  std::vector<Arrival> arrivals() const {
    std::lock_guard lock(mutex_);
    return arrivals_;
  }

 private:
  explicit DatagramSink(ssl::net::UdpSocket socket) : socket_(std::move(socket)) {
    thread_ = std::thread([this] {
      std::vector<std::uint8_t> buffer(65536);
      while (true) {
        const ssl::net::ReceiveResult got = socket_.receive(buffer, 1s);
        const std::int64_t at = wall_ns();
        if (got.status == ssl::net::ReceiveStatus::kInterrupted) return;
        if (!got.ok()) continue;
        std::lock_guard lock(mutex_);
        arrivals_.push_back({at, std::string(reinterpret_cast<const char*>(buffer.data()), got.size)});
      }
    });
  }

  ssl::net::UdpSocket socket_;
  mutable std::mutex mutex_;
  std::vector<Arrival> arrivals_;
  std::thread thread_;
};

/// Reads what the children printed, so that a full pipe never blocks one.
void drain(std::vector<ChildProcess>& children) {
  for (ChildProcess& child : children) {
    while (child.read_line(0ms)) {
    }
    (void)child.drain_stderr();
  }
}

// ---- the pipeline ----------------------------------------------------------------------------------

struct Sent {
  std::int64_t gateway_receive_ns;  // the frame's VisionStamp
  std::int64_t sent_ns;
  std::uint32_t camera;
  std::uint32_t frame_number;
  bool resend;
};

struct PipelineResult {
  SampleStats stats;
  // sendto -> the frame's first robot.commands sample received here (vision_gateway, world_model, planner:
  // the design's three-process figure).
  SampleStats to_commands;
  // Where the time goes (same packets): sendto -> vision_gateway receive, -> robot_link send returned,
  // -> this process's receive.
  SampleStats to_gateway;
  SampleStats through_services;
  SampleStats to_here;
  std::size_t frames_sent = 0;
  std::size_t packets = 0;
  std::size_t heartbeats = 0;
};

ssl::Result<PipelineResult> run_pipeline(const Options& options) {
  namespace fs = std::filesystem;
  const fs::path bin = ssl::testing::bin_dir();
  const std::string domain = std::to_string(options.domain);
  auto commands_sink = DatagramSink::open(options.port + 1);
  if (!commands_sink) return commands_sink.error();

  auto participant = ssl::dds::Participant::create({.domain_id = options.domain, .name = "bench/pipeline_latency"});
  if (!participant) return participant.error();
  std::mutex sent_mutex;
  std::vector<Sent> sent;
  auto sent_reader = participant->make_reader(
      ssl::dds::topics::kRobotSent, ssl::TeamColor::kBlue,
      [&](const ssl::dds::Sample<ssl::idl::robot::CommandsSent>& sample) {
        std::lock_guard lock(sent_mutex);
        sent.push_back({sample.data.stamp().receive_unix_ns(), sample.data.sent_unix_ns(), sample.data.stamp().camera_id(),
                        sample.data.stamp().frame_number(), sample.data.resend()});
      });
  // Every robot.commands sample's frame and when it arrived here (one per planner tick).
  struct CommandsArrival {
    std::uint32_t camera;
    std::uint32_t frame_number;
    std::int64_t at_ns;
  };
  std::vector<CommandsArrival> commands;
  auto commands_reader = participant->make_reader(
      ssl::dds::topics::kRobotCommands, ssl::TeamColor::kBlue,
      [&](const ssl::dds::Sample<ssl::idl::robot::RobotCommands>& sample) {
        std::lock_guard lock(sent_mutex);
        commands.push_back({sample.data.stamp().camera_id(), sample.data.stamp().frame_number(),
                            sample.reception_unix_ns});
      });
  auto referee_writer = participant->make_writer(ssl::dds::topics::kRefereeState);
  if (!sent_reader) return sent_reader.error();
  if (!commands_reader) return commands_reader.error();
  if (!referee_writer) return referee_writer.error();
  ssl::idl::referee::RefereeState referee;
  referee.command(ssl::idl::referee::COMMAND_FORCE_START);
  referee.command_counter(1);
  referee.has_blue_team_on_positive_half(true);
  referee.blue_team_on_positive_half(false);
  if (auto written = referee_writer->write(referee); !written) return written.error();

  std::vector<ChildProcess> children;
  const auto start = [&](const std::string& program, std::vector<std::string> args) -> ssl::Status {
    args.insert(args.end(), {"--domain", domain, "--log-level", "warn"});
    auto child = ChildProcess::start(bin / program, args);
    if (!child) return child.error();
    children.push_back(std::move(*child));
    return {};
  };
  for (const ssl::Status& started :
       {start("vision_gateway", {"--vision-port", std::to_string(options.port), "--interface", "127.0.0.1"}),
        start("world_model", {"--team", "blue"}), start("planner", {"--team", "blue"}),
        start("robot_link", {"--team", "blue", "--backend", "sim", "--sim-host", "127.0.0.1", "--sim-port",
                             std::to_string(options.port + 1)})}) {
    if (!started) return started.error();
  }
  // world_model, planner and robot_link read referee.state; robot_link writes robot.sent.
  // What the services said, for an error.
  const auto their_words = [&] {
    std::string words;
    for (ChildProcess& child : children) {
      words += '\n';
      words += child.drain_stderr();
    }
    return words;
  };
  if (!referee_writer->wait_for_match(3, kStartTimeout) || !sent_reader->wait_for_match(1, kStartTimeout)) {
    return ssl::Error{"the services did not come up within 30 s" + their_words()};
  }
  auto vision = ssl::net::MulticastSender::open("224.5.23.2", options.port, "127.0.0.1");
  if (!vision) return vision.error();
  const auto send_vision = [&](const std::string& bytes) { (void)vision->send(bytes_of(bytes)); };
  const auto keep_drained = [&] { drain(children); };

  // Frames until a command descending from one left robot_link, then kWarmupFrames more, unmeasured.
  FrameClock frames(options);
  const auto t0 = SteadyClock::now();
  std::uint32_t number = 1;
  const auto reached_radio = [&] {
    std::lock_guard lock(sent_mutex);
    return std::any_of(sent.begin(), sent.end(), [](const Sent& s) { return s.frame_number > 0; });
  };
  while (!reached_radio()) {
    if (SteadyClock::now() - t0 > kStartTimeout) {
      return ssl::Error{"no command descending from a frame within 30 s" + their_words()};
    }
    frames.send_frame(number++, t0, send_vision, keep_drained);
  }
  const std::uint32_t first_measured = number + kWarmupFrames;
  const std::uint32_t end = first_measured + options.frames;
  while (number < end) frames.send_frame(number++, t0, send_vision, keep_drained);
  std::this_thread::sleep_for(200ms);  // the last frames' commands are still on their way
  for (ChildProcess& child : children) child.signal(SIGTERM);
  for (ChildProcess& child : children) (void)child.wait(10s);

  // Datagrams and robot.sent samples in send order, paired when within the tolerance of each other.
  std::vector<DatagramSink::Arrival> datagrams = (*commands_sink)->arrivals();
  std::lock_guard lock(sent_mutex);
  PipelineResult result;
  result.frames_sent = static_cast<std::size_t>(options.frames) * options.cameras;
  std::vector<double> ms;
  std::vector<double> to_gateway_ms;
  std::vector<double> through_services_ms;
  std::vector<double> to_here_ms;
  std::size_t d = 0;
  std::size_t s = 0;
  while (d < datagrams.size() && s < sent.size()) {
    const std::int64_t gap = datagrams[d].at_ns - sent[s].sent_ns;
    if (gap > kPairingToleranceNs) {
      ++s;  // its datagram was lost (or came before the sink opened)
      continue;
    }
    if (gap < -kPairingToleranceNs) {
      ++d;  // its robot.sent sample was lost
      continue;
    }
    const Sent& packet = sent[s];
    if (packet.frame_number >= first_measured && packet.frame_number < end) {
      ++result.packets;
      if (packet.resend) {
        ++result.heartbeats;
      } else if (const std::int64_t in = frames.sent_ns(packet.camera, packet.frame_number); in > 0) {
        ms.push_back(static_cast<double>(datagrams[d].at_ns - in) * 1e-6);
        to_gateway_ms.push_back(static_cast<double>(packet.gateway_receive_ns - in) * 1e-6);
        through_services_ms.push_back(static_cast<double>(packet.sent_ns - packet.gateway_receive_ns) * 1e-6);
        to_here_ms.push_back(static_cast<double>(datagrams[d].at_ns - packet.sent_ns) * 1e-6);
      }
    }
    ++d;
    ++s;
  }
  std::vector<double> to_commands_ms;
  std::set<std::pair<std::uint32_t, std::uint32_t>> planned;  // (camera, frame) already measured
  for (const CommandsArrival& arrival : commands) {
    if (arrival.frame_number < first_measured || arrival.frame_number >= end) continue;
    if (!planned.insert({arrival.camera, arrival.frame_number}).second) continue;
    if (const std::int64_t in = frames.sent_ns(arrival.camera, arrival.frame_number); in > 0) {
      to_commands_ms.push_back(static_cast<double>(arrival.at_ns - in) * 1e-6);
    }
  }
  result.to_commands = summarize(std::move(to_commands_ms));
  result.stats = summarize(std::move(ms));
  result.to_gateway = summarize(std::move(to_gateway_ms));
  result.through_services = summarize(std::move(through_services_ms));
  result.to_here = summarize(std::move(to_here_ms));
  if (result.stats.count == 0) return ssl::Error{"no command datagram could be paired with its frame"};
  return result;
}

// ---- the bare UDP relay ----------------------------------------------------------------------------

int relay(int in_port, int out_port) {
  auto socket = ssl::net::UdpSocket::open("127.0.0.1", in_port);
  if (!socket) return fail(socket.error().message);
  auto out = ssl::net::Endpoint::from_parts("127.0.0.1", out_port);
  if (!out) return fail(out.error().message);
  std::printf("ready\n");
  std::fflush(stdout);
  std::vector<std::uint8_t> buffer(65536);
  while (true) {
    const ssl::net::ReceiveResult got = socket->receive(buffer, 60s);
    if (!got.ok()) return fail("relay on port " + std::to_string(in_port) + ": nothing for 60 s");
    (void)socket->send_to(*out, std::span(buffer).first(got.size));
    if (got.size == 1) return 0;  // the stop message, passed on
  }
}

ssl::Result<SampleStats> run_relay(const Options& options) {
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe");
  const int first = options.port + 2;
  const int out_port = options.port + 6;
  auto sink = DatagramSink::open(out_port);
  if (!sink) return sink.error();
  std::vector<ChildProcess> relays;
  for (int hop = 0; hop < 4; ++hop) {
    const int next = hop == 3 ? out_port : first + hop + 1;
    auto child = ChildProcess::start(self, {"--relay", std::to_string(first + hop), std::to_string(next)});
    if (!child) return child.error();
    if (!child->read_line(std::chrono::duration_cast<std::chrono::milliseconds>(kStartTimeout))) {
      return ssl::Error{"relay " + std::to_string(hop) + " did not start: " + child->drain_stderr()};
    }
    relays.push_back(std::move(*child));
  }
  auto socket = ssl::net::UdpSocket::open("127.0.0.1", 0);
  if (!socket) return socket.error();
  auto to = ssl::net::Endpoint::from_parts("127.0.0.1", first);
  if (!to) return to.error();
  const auto send = [&](const std::string& bytes) { (void)socket->send_to(*to, bytes_of(bytes)); };

  FrameClock frames(options);
  const auto t0 = SteadyClock::now();
  const std::uint32_t first_measured = 1 + kWarmupFrames;
  const std::uint32_t end = first_measured + options.frames;
  for (std::uint32_t number = 1; number < end; ++number) frames.send_frame(number, t0, send, [] {});
  std::this_thread::sleep_for(200ms);
  const std::uint8_t stop = 0;
  (void)socket->send_to(*to, std::span(&stop, 1));
  for (ChildProcess& child : relays) (void)child.wait(10s);

  std::vector<double> ms;
  for (const DatagramSink::Arrival& arrival : (*sink)->arrivals()) {
    SSL_WrapperPacket packet;
    if (!packet.ParseFromString(arrival.bytes) || !packet.has_detection()) continue;
    const std::uint32_t number = packet.detection().frame_number();
    if (number < first_measured) continue;
    if (const std::int64_t in = frames.sent_ns(packet.detection().camera_id(), number); in > 0) {
      ms.push_back(static_cast<double>(arrival.at_ns - in) * 1e-6);
    }
  }
  SampleStats stats = summarize(std::move(ms));
  if (stats.count == 0) return ssl::Error{"nothing came through the relay"};
  return stats;
}

std::string load_average() {
  std::ifstream file("/proc/loadavg");
  std::string one;
  std::string five;
  file >> one >> five;
  return one + " (1 min), " + five + " (5 min)";
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    try {
      if (arg == "--relay" && i + 2 < argc) return relay(std::stoi(argv[i + 1]), std::stoi(argv[i + 2]));
      if (arg == "--frames" && has_value) {
        options.frames = static_cast<std::uint32_t>(std::stoul(argv[++i]));
      } else if (arg == "--cameras" && has_value) {
        options.cameras = static_cast<std::uint32_t>(std::stoul(argv[++i]));
      } else if (arg == "--rate-limited-cameras" && has_value) {
        options.rate_limited_cameras = static_cast<std::uint32_t>(std::stoul(argv[++i]));
      } else if (arg == "--rate" && has_value) {
        options.rate = std::stod(argv[++i]);
      } else if (arg == "--domain" && has_value) {
        options.domain = std::stoi(argv[++i]);
      } else if (arg == "--port" && has_value) {
        options.port = std::stoi(argv[++i]);
      } else if (arg == "--help" || arg == "-h") {
        std::printf("usage: pipeline_latency [--frames N] [--cameras C] [--rate-limited-cameras C] [--rate HZ] "
                    "[--domain D] [--port P]\n");
        return 0;
      } else {
        return fail("unknown argument '" + arg + "' (see --help)");
      }
    } catch (const std::exception&) {
      return fail("bad value for " + arg);
    }
  }
  if (options.frames == 0 || options.cameras == 0 || options.cameras > 8 || options.rate_limited_cameras > 8 ||
      !(options.rate >= 1 && options.rate <= 200) || options.domain < 0 || options.domain > 232 ||
      options.port < 1024 || options.port > 65529) {
    return fail("--frames > 0, --cameras 1..8, --rate-limited-cameras 0..8, --rate 1..200 Hz, --domain 0..232, "
                "--port 1024..65529");
  }

  // The budgeted run, then one whose frames outrun the radio's rate (a real field's cameras).
  std::vector<std::uint32_t> runs = {options.cameras};
  if (options.rate_limited_cameras > 0) runs.push_back(options.rate_limited_cameras);
  for (std::size_t run = 0; run < runs.size(); ++run) {
    Options scenario = options;
    scenario.cameras = runs[run];
    const std::string before = load_average();
    auto pipeline = run_pipeline(scenario);
    if (!pipeline) return fail("pipeline: " + pipeline.error().message);
    auto relay = run_relay(scenario);
    if (!relay) return fail("relay: " + relay.error().message);
    const SampleStats& p = pipeline->stats;
    std::printf("vision packet in -> command datagram out, %u camera(s) at %.0f Hz (%.0f frames/s), %u frames "
                "each; load average %s before, %s after\n",
                scenario.cameras, scenario.rate, scenario.cameras * scenario.rate, scenario.frames, before.c_str(),
                load_average().c_str());
    std::printf("  %-58s median %7.3f ms   p99 %7.3f ms   max %7.3f ms   (%zu of %zu frames reached the radio as "
                "new commands; %zu heartbeats)\n",
                "pipeline: vision_gateway, world_model, planner, robot_link", p.median, p.p99, p.max,
                p.count, pipeline->frames_sent, pipeline->heartbeats);
    std::printf("  %-58s median %7.3f ms   p99 %7.3f ms   max %7.3f ms   (%zu frames)\n",
                "to robot.commands (vision_gateway, world_model, planner)", pipeline->to_commands.median,
                pipeline->to_commands.p99, pipeline->to_commands.max, pipeline->to_commands.count);
    for (const auto& [name, stage] : {std::pair{"  of which sendto -> vision_gateway receive", &pipeline->to_gateway},
                                      std::pair{"  of which -> robot_link's send returned", &pipeline->through_services},
                                      std::pair{"  of which -> datagram received here", &pipeline->to_here}}) {
      std::printf("  %-58s median %7.3f ms   p99 %7.3f ms   max %7.3f ms\n", name, stage->median, stage->p99,
                  stage->max);
    }
    std::printf("  %-58s median %7.3f ms   p99 %7.3f ms   max %7.3f ms   (%zu frames)\n",
                "bare UDP relay, 4 processes", relay->median, relay->p99, relay->max, relay->count);
    std::printf("  %-58s median %7.1f x    p99 %7.1f x\n", "ratio pipeline / relay", p.median / relay->median,
                p.p99 / relay->p99);
    if (run == 0) {
      std::printf("BUDGET commands_latency_median_ms %.3f\n", pipeline->to_commands.median);
      std::printf("BUDGET commands_latency_p99_ms %.3f\n", pipeline->to_commands.p99);
      std::printf("BUDGET pipeline_latency_median_ms %.3f\n", p.median);
      std::printf("BUDGET pipeline_latency_p99_ms %.3f\n", p.p99);
    } else {
      std::printf("  (radio-rate limited: the budget allows one radio period more than the run above)\n");
    }
    std::fflush(stdout);
  }
  return 0;
}
