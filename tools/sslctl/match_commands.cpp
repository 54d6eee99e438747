// sslctl match report: the league's Referee stream (and SSL-Vision: the ball, the robots, the field's size),
// live from multicast or from an SSL log file, into a MatchReport (match_report.h).
#include <array>
#include <chrono>
#include <optional>
#include <ostream>
#include <vector>

#include "libs/league/decode.h"
#include "libs/league/field_geometry.h"
#include "libs/league/log_file.h"
#include "libs/net/multicast.h"
#include "libs/time/clock.h"
#include "services/referee_gateway/adapter/convert.h"
#include "tools/sslctl/commands.h"
#include "tools/sslctl/match_report.h"

namespace ssl::sslctl {
namespace {

using namespace std::chrono_literals;

constexpr std::string_view kVisionGroup = "224.5.23.2";
constexpr std::string_view kRefereeGroup = "224.5.23.1";
constexpr std::size_t kDatagramBufferBytes = 65536;

/// A Referee packet into the builder; false when it does not decode.
bool add_referee(MatchReportBuilder& builder, std::span<const std::uint8_t> bytes, time::Timestamp t) {
  auto packet = league::decode_referee(bytes);
  if (!packet) return false;
  builder.on_referee(referee::from_proto(*packet, t, referee::RefereeSource::kGameController), t);
  return true;
}

/// One SSL-Vision packet into the builder (metres): a camera frame's robots with its most confident ball (its
/// camera and capture time with it), and the field's size from geometry (positive sizes only); false when it
/// does not decode. `robots` is scratch.
bool add_vision(MatchReportBuilder& builder, std::span<const std::uint8_t> bytes, time::Timestamp t,
                std::vector<PlayAccount::Robot>& robots) {
  auto packet = league::decode_vision_wrapper(bytes);
  if (!packet) return false;
  if (packet->has_geometry()) {
    const SSL_GeometryFieldSize& size = packet->geometry().field();
    if (size.field_length() > 0 && size.field_width() > 0 && size.goal_width() > 0) {
      builder.set_field(league::field_from_proto(size));
    }
  }
  if (!packet->has_detection()) return true;
  const SSL_DetectionFrame& frame = packet->detection();
  robots.clear();
  for (auto [team, detections] : {std::pair{TeamColor::kYellow, &frame.robots_yellow()},
                                  std::pair{TeamColor::kBlue, &frame.robots_blue()}}) {
    for (const SSL_DetectionRobot& robot : *detections) {
      robots.push_back(
          {.team = team, .id = robot.robot_id(), .position = geom::Vec2(robot.x() / 1000.0, robot.y() / 1000.0)});
    }
  }
  const SSL_DetectionBall* best = nullptr;
  for (const SSL_DetectionBall& ball : frame.balls()) {
    if (best == nullptr || ball.confidence() > best->confidence()) best = &ball;
  }
  if (best != nullptr) {
    builder.on_frame(geom::Vec2(best->x() / 1000.0, best->y() / 1000.0), robots, t,
                     PlayAccount::Camera{.id = frame.camera_id(),
                                         .capture = time::Timestamp::from_seconds(frame.t_capture())});
  } else {
    builder.on_robots(robots, t);
  }
  return true;
}

int print(const MatchReport& report, bool json, std::ostream& out) {
  out << (json ? to_json(report) + "\n" : to_text(report));
  return report.referee_samples > 0 ? 0 : 1;
}

int from_file(const MatchReportOptions& options, std::ostream& out, std::ostream& err) {
  auto reader = league::LogReader::open(options.file);
  if (!reader) {
    err << "sslctl: " << reader.error().message << '\n';
    return 1;
  }
  MatchReportBuilder builder;
  std::vector<PlayAccount::Robot> robots;
  std::optional<Error> damage;
  while (true) {
    auto record = reader->next();
    if (!record) {
      damage = record.error();
      break;
    }
    if (!*record) break;
    const league::LogRecord& r = **record;
    const time::Timestamp t = time::Timestamp::from_nanoseconds(r.timestamp_ns);
    bool decoded = true;
    if (r.type == league::MessageType::kRefbox2013) decoded = add_referee(builder, league::byte_span(r.payload), t);
    if (r.type == league::MessageType::kVision2014) {
      decoded = add_vision(builder, league::byte_span(r.payload), t, robots);
    }
    if (!decoded) builder.on_malformed();
  }
  const MatchReport report = builder.report();
  if (report.referee_samples == 0 && !damage) err << "sslctl: no referee packets in " << options.file << '\n';
  const int status = print(report, options.json, out);
  if (damage) {
    err << "sslctl: " << options.file << ": " << damage->message << '\n';
    return 1;
  }
  return status;
}

int live(const MatchReportOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err) {
  for (const auto& [flag, port] : {std::pair{"--referee-port", options.referee_port},
                                   std::pair{"--vision-port", options.vision_port}}) {
    if (port < 1 || port > 65535) {
      err << "sslctl: " << flag << ' ' << port << " is not a port (1-65535)\n";
      return 2;
    }
  }
  auto referee_socket = net::MulticastReceiver::open(kRefereeGroup, options.referee_port, options.interface_address);
  if (!referee_socket) {
    err << "sslctl: referee " << kRefereeGroup << ':' << options.referee_port << ": "
        << referee_socket.error().message << '\n';
    return 1;
  }
  auto vision_socket = net::MulticastReceiver::open(kVisionGroup, options.vision_port, options.interface_address);
  if (!vision_socket) {
    err << "sslctl: vision " << kVisionGroup << ':' << options.vision_port << ": " << vision_socket.error().message
        << '\n';
    return 1;
  }
  err << "sslctl: reading the referee on " << kRefereeGroup << ':' << options.referee_port << " and vision on "
      << kVisionGroup << ':' << options.vision_port << " via " << options.interface_address
      << (options.duration_s > 0 ? " for " + std::to_string(options.duration_s) + " s" : " until Ctrl-C") << '\n';
  if (options.on_ready) options.on_ready();

  MatchReportBuilder builder;
  std::vector<PlayAccount::Robot> robots;
  time::RealClock wall;
  std::array<std::uint8_t, kDatagramBufferBytes> buffer{};
  const auto start = std::chrono::steady_clock::now();
  const auto done = [&] {
    return shutdown.requested() || (options.until_final_whistle && builder.final_whistle()) ||
           (options.duration_s > 0 &&
            std::chrono::steady_clock::now() - start >= std::chrono::duration<double>(options.duration_s));
  };
  while (!done()) {
    // Drain the vision socket (many packets per second), then wait briefly on the referee.
    for (int i = 0; i < 64; ++i) {
      const net::ReceiveResult received = vision_socket->receive(buffer, 0ns);
      if (!received.ok()) break;
      if (!add_vision(builder, {buffer.data(), received.size}, wall.now(), robots)) builder.on_malformed();
    }
    const net::ReceiveResult received = referee_socket->receive(buffer, 5ms);
    if (received.ok() && !add_referee(builder, {buffer.data(), received.size}, wall.now())) builder.on_malformed();
  }
  const MatchReport report = builder.report();
  if (report.referee_samples == 0) {
    err << "sslctl: no referee packet arrived on " << kRefereeGroup << ':' << options.referee_port << '\n';
  }
  return print(report, options.json, out);
}

}  // namespace

int match_report(const MatchReportOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err) {
  return options.file.empty() ? live(options, shutdown, out, err) : from_file(options, out, err);
}

}  // namespace ssl::sslctl
