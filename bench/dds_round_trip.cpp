// Round-trip latency between two processes through our DDS wrappers, beside a bare UDP socket round trip
// measured in the same run, with their ratio; and the same DDS round trip with DDS Security on (certificates
// made for the run by deploy/dds-certs.sh), with its ratio to security off.
//
// The parent sends a vision.detection frame (22 robots + ball, the size of a real frame) and the peer
// process answers with a world.state (blue partition) carrying the same frame number; one message is in
// flight at a time. Then the same ping-pong runs over two plain UDP sockets on 127.0.0.1 with the same
// payload size. Both sides wait by blocking (condition variable, poll), as services do. With security the
// ping is signed (a shared topic) and the answer encrypted (a team topic), as the governance says.
//
//   build/bench/dds_round_trip [--iterations N] [--domain D]   (the secure run uses domain D + 1)
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/sample_stats.h"
#include "libs/common/deploy_files.h"
#include "libs/dds/participant.h"

namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::seconds;
constexpr std::uint32_t kStopFrame = 0xFFFFFFFF;
constexpr int kWarmup = 200;

using ssl::bench::SampleStats;
using ssl::bench::summarize;

ssl::idl::vision::DetectionFrame make_frame() {
  ssl::idl::vision::DetectionFrame frame;
  frame.camera_id(0);
  frame.balls().resize(1);
  frame.robots_blue().resize(11);
  frame.robots_yellow().resize(11);
  for (std::uint32_t i = 0; i < 11; ++i) {
    frame.robots_blue()[i].robot_id(i);
    frame.robots_yellow()[i].robot_id(i);
  }
  return frame;
}

int fail(const std::string& message) {
  std::fprintf(stderr, "dds_round_trip: %s\n", message.c_str());
  return 1;
}

// ---- DDS ---------------------------------------------------------------------------------------------

/// Security for a run: off with no directory, else on with the files in `certs`.
ssl::dds::ParticipantOptions participant_options(int domain, const std::string& name, const std::string& certs,
                                                 const std::string& identity) {
  return {.domain_id = domain, .name = name, .security = {.enabled = !certs.empty(), .directory = certs},
          .identity = identity};
}

// The answering side is a team stack (publishes its world.state), the pinging side an operator of every
// team (it may publish vision and read the blue team's world.state).
constexpr const char* kPeerIdentity = "blue";
constexpr const char* kMainIdentity = "operator";

int dds_peer(int domain, const std::string& certs) {
  auto participant = ssl::dds::Participant::create(participant_options(domain, "bench/peer", certs, kPeerIdentity));
  if (!participant) return fail(participant.error().message);
  auto pings = participant->make_reader(ssl::dds::topics::kVisionDetection);
  auto pongs = participant->make_writer(ssl::dds::topics::kWorldState, ssl::TeamColor::kBlue);
  if (!pings || !pongs) return fail("peer cannot create its reader or writer");
  ssl::idl::world::WorldState reply;
  reply.friendly().resize(11);
  reply.enemy().resize(11);
  while (pings->wait_for_data(seconds(30))) {
    for (const auto& ping : pings->take()) {
      if (ping.data.frame_number() == kStopFrame) return 0;
      reply.stamp().frame_number(ping.data.frame_number());
      (void)pongs->write(reply);
    }
  }
  return fail("peer heard nothing for 30 s");
}

ssl::Result<SampleStats> dds_round_trips(int domain, int iterations, const std::string& certs, const char* self) {
  auto participant = ssl::dds::Participant::create(participant_options(domain, "bench/main", certs, kMainIdentity));
  if (!participant) return participant.error();
  auto pings = participant->make_writer(ssl::dds::topics::kVisionDetection);
  auto pongs = participant->make_reader(ssl::dds::topics::kWorldState, ssl::TeamColor::kBlue);
  if (!pings || !pongs) return ssl::Error{"cannot create the writer or reader"};

  const pid_t peer = fork();
  if (peer == 0) {
    execl(self, self, "--peer-dds", std::to_string(domain).c_str(), certs.c_str(), nullptr);
    _exit(127);
  }
  if (!pings->wait_for_match(1, seconds(20)) || !pongs->wait_for_match(1, seconds(20))) {
    return ssl::Error{"the peer process did not match within 20 s"};
  }
  auto frame = make_frame();
  std::vector<double> samples;
  samples.reserve(static_cast<std::size_t>(iterations));
  std::uint32_t lost = 0;
  for (int i = 0; i < kWarmup + iterations; ++i) {
    frame.frame_number(static_cast<std::uint32_t>(i));
    const auto start = Clock::now();
    if (!pings->write(frame)) return ssl::Error{"write failed"};
    bool answered = false;
    while (!answered && pongs->wait_for_data(std::chrono::milliseconds(200))) {
      for (const auto& pong : pongs->take()) answered |= pong.data.stamp().frame_number() == frame.frame_number();
    }
    if (!answered) {
      ++lost;  // best effort: a ping may be lost; it is counted, not timed
      continue;
    }
    if (i >= kWarmup) samples.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
  }
  frame.frame_number(kStopFrame);
  (void)pings->write(frame);
  int status = 0;
  waitpid(peer, &status, 0);
  if (lost > 0) std::printf("  (DDS: %u of %d pings lost and not timed)\n", lost, kWarmup + iterations);
  return summarize(std::move(samples));
}

// ---- bare UDP ----------------------------------------------------------------------------------------

int udp_socket_on(std::uint16_t port) {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    close(fd);
    return -1;
  }
  return fd;
}

sockaddr_in loopback(std::uint16_t port) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  return address;
}

bool wait_readable(int fd, int timeout_ms) {
  pollfd entry{fd, POLLIN, 0};
  return poll(&entry, 1, timeout_ms) == 1;
}

int udp_peer(std::uint16_t port) {
  const int fd = udp_socket_on(port);
  if (fd < 0) return fail("peer cannot bind UDP port " + std::to_string(port));
  std::vector<char> buffer(65536);
  while (wait_readable(fd, 30000)) {
    sockaddr_in from{};
    socklen_t from_size = sizeof from;
    const ssize_t got = recvfrom(fd, buffer.data(), buffer.size(), 0, reinterpret_cast<sockaddr*>(&from), &from_size);
    if (got == 1) return 0;  // the stop message
    if (got > 0) sendto(fd, buffer.data(), static_cast<std::size_t>(got), 0, reinterpret_cast<sockaddr*>(&from), from_size);
  }
  return fail("UDP peer heard nothing for 30 s");
}

ssl::Result<SampleStats> udp_round_trips(std::uint16_t port, int iterations, std::size_t payload_size,
                                         const char* self) {
  const int fd = udp_socket_on(0);
  if (fd < 0) return ssl::Error{"cannot bind a UDP socket"};
  const pid_t peer = fork();
  if (peer == 0) {
    execl(self, self, "--peer-udp", std::to_string(port).c_str(), nullptr);
    _exit(127);
  }
  const sockaddr_in to = loopback(port);
  std::vector<char> payload(payload_size, 'x');
  std::vector<char> buffer(65536);
  // The peer binds after exec: probe until it answers (bounded), rather than sleeping a fixed time.
  bool ready = false;
  for (int attempt = 0; attempt < 200 && !ready; ++attempt) {
    sendto(fd, payload.data(), payload.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
    ready = wait_readable(fd, 50) && recv(fd, buffer.data(), buffer.size(), 0) > 0;
  }
  if (!ready) return ssl::Error{"the UDP peer did not answer"};
  std::vector<double> samples;
  for (int i = 0; i < kWarmup + iterations; ++i) {
    const auto start = Clock::now();
    sendto(fd, payload.data(), payload.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
    if (!wait_readable(fd, 1000) || recv(fd, buffer.data(), buffer.size(), 0) <= 0) continue;
    if (i >= kWarmup) samples.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
  }
  const char stop = 0;
  sendto(fd, &stop, 1, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  int status = 0;
  waitpid(peer, &status, 0);
  close(fd);
  return summarize(std::move(samples));
}

}  // namespace

int main(int argc, char** argv) {
  int iterations = 5000;
  int domain = 199;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--peer-dds" && i + 2 < argc) return dds_peer(std::stoi(argv[i + 1]), argv[i + 2]);
    if (arg == "--peer-udp" && i + 1 < argc) return udp_peer(static_cast<std::uint16_t>(std::stoi(argv[i + 1])));
    if (arg == "--iterations" && i + 1 < argc) {
      iterations = std::stoi(argv[++i]);
    } else if (arg == "--domain" && i + 1 < argc) {
      domain = std::stoi(argv[++i]);
    } else if (arg == "--help" || arg == "-h") {
      std::printf("usage: dds_round_trip [--iterations N] [--domain D]\n");
      return 0;
    } else {
      return fail("unknown argument '" + arg + "' (see --help)");
    }
  }
  if (iterations <= 0) return fail("--iterations must be positive");

  // The payload of the UDP baseline matches the serialized size of the DDS ping.
  ssl::idl::vision::DetectionFramePubSubType support;
  auto frame = make_frame();
  const std::size_t payload = support.getSerializedSizeProvider(&frame)();

  auto dds = dds_round_trips(domain, iterations, "", argv[0]);
  if (!dds) return fail(dds.error().message);
  // The security files of this run only, in a fresh directory ($SSL_CERTS_DIR would beat it).
  ::unsetenv("SSL_CERTS_DIR");
  const std::filesystem::path certs =
      std::filesystem::temp_directory_path() / ("ssl_dds_round_trip_certs_" + std::to_string(::getpid()));
  auto script = ssl::find_deploy_file("dds-certs.sh");
  if (!script) return fail(script.error().message);
  if (std::system(("'" + *script + "' --dir '" + certs.string() + "' --teams blue >/dev/null").c_str()) != 0) {
    return fail("deploy/dds-certs.sh could not make the certificates (run it by hand to see why)");
  }
  auto secure = dds_round_trips(domain + 1, iterations, certs.string(), argv[0]);
  std::filesystem::remove_all(certs);
  if (!secure) return fail("with DDS Security: " + secure.error().message);
  auto udp = udp_round_trips(static_cast<std::uint16_t>(41000 + domain), iterations, payload, argv[0]);
  if (!udp) return fail(udp.error().message);

  std::printf("round trip between two processes, %d iterations, %zu-byte ping\n", iterations, payload);
  std::printf("  %-28s median %8.1f us   p99 %8.1f us   max %8.1f us\n", "DDS (our wrappers)", dds->median,
              dds->p99, dds->max);
  std::printf("  %-28s median %8.1f us   p99 %8.1f us   max %8.1f us\n", "DDS with DDS Security",
              secure->median, secure->p99, secure->max);
  std::printf("  %-28s median %8.1f us   p99 %8.1f us   max %8.1f us\n", "bare UDP socket", udp->median,
              udp->p99, udp->max);
  std::printf("  ratio DDS / UDP               median %8.2f x    p99 %8.2f x\n", dds->median / udp->median,
              dds->p99 / udp->p99);
  std::printf("  ratio secure / insecure DDS   median %8.2f x    p99 %8.2f x\n", secure->median / dds->median,
              secure->p99 / dds->p99);
  std::printf("BUDGET dds_round_trip_ratio_median %.2f\n", dds->median / udp->median);
  return 0;
}
