// Backends: where robot_link's per-tick commands go and where robot feedback comes from, behind one small
// interface chosen by config, so that swapping the simulator for real robots is a change of config only.
//
//   kSim    RobotControl (simulation protocol) by UDP to host:port (10301 blue / 10302 yellow);
//           feedback: RobotControlResponse on the same socket.
//   kGrsim  grSim_Packet (legacy grSim) by UDP to host:port (20011);
//           feedback: Robots_Status on 30011 blue / 30012 yellow.
//   kRadio  radio command frames (radio_frame.h) by UDP to a base station or over a serial device;
//           feedback: radio status frames.
//
// One send() per tick carries every robot of the team (one datagram or frame); it never blocks for long
// (UDP sendto, or a non-blocking serial write). poll_feedback() returns what arrived since the last call
// without blocking. Counters are totals since opening. Not thread-safe: one thread drives a backend.
//
//   auto backend = make_backend({.kind = BackendKind::kSim, .team = TeamColor::kBlue,
//                                .host = "127.0.0.1", .port = 10301});
//   if (!backend) fail(backend.error().message);
//   (void)(*backend)->send(tick.commands);
//   for (const FeedbackReport& report : (*backend)->poll_feedback()) publish(report);
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "libs/common/result.h"
#include "libs/common/team.h"
#include "services/robot_link/core/types.h"

namespace ssl::robot_link {

enum class BackendKind { kSim, kGrsim, kRadio };
enum class RadioTransport { kUdp, kSerial };

struct BackendCounters {
  std::uint64_t packets_sent = 0;  // datagrams or frames sent
  std::uint64_t bytes_sent = 0;
  std::uint64_t send_errors = 0;        // failed sends (the tick's commands did not leave)
  std::uint64_t feedback_received = 0;  // feedback packets / frames decoded
  std::uint64_t feedback_errors = 0;    // feedback that did not decode (malformed datagram, bad frame)
  std::uint64_t remote_errors = 0;      // errors the simulator reported (RobotControlResponse.errors)
  std::uint64_t frames_lost = 0;        // radio: gaps in the base station's status sequence numbers
};

struct BackendOptions {
  BackendKind kind = BackendKind::kSim;
  TeamColor team = TeamColor::kBlue;
  std::string bind_address = "0.0.0.0";  // local address of UDP sockets (the interface facing the peer)
  std::string host = "127.0.0.1";        // sim / grsim / radio-over-UDP peer
  int port = 0;                          // peer port; 0 = league default (see default_port)
  // grsim: listen for grSim's Robots_Status; port 0 = grSim's default (30011 blue, 30012 yellow).
  bool grsim_feedback = true;
  int grsim_status_port = 0;
  // radio
  RadioTransport radio_transport = RadioTransport::kUdp;
  int radio_local_port = 0;   // UDP port status frames arrive on; 0 = ephemeral (replies)
  std::string serial_device;  // e.g. /dev/ttyUSB0
  int serial_baud = 115200;
};

/// The default peer port: the league's 10301 blue / 10302 yellow (sim) and 20011 (grsim); 10400 for the
/// radio base station (our choice, documented in README.md).
int default_port(BackendKind kind, TeamColor team);

/// grSim's robot status port: 30011 blue, 30012 yellow.
int default_grsim_status_port(TeamColor team);

class Backend {
 public:
  virtual ~Backend() = default;

  /// Sends one tick's commands (ordered by id, at most 16) as one packet.
  virtual Status send(std::span<const OutgoingCommand> commands) = 0;

  /// Feedback received since the last call; never blocks.
  virtual std::vector<FeedbackReport> poll_feedback() = 0;

  virtual BackendCounters counters() const = 0;

  /// "sim 127.0.0.1:10301", for logs and health.
  virtual std::string description() const = 0;

  /// The newest error text from the peer or from decoding feedback ("" if none), for logs.
  virtual std::string last_error() const = 0;
};

/// Opens the backend described by `options` (sockets bound, serial device opened in raw mode).
Result<std::unique_ptr<Backend>> make_backend(const BackendOptions& options);

}  // namespace ssl::robot_link
