// BuiltinRefereeService: runs the built-in referee (builtin/builtin_referee.h) as a league referee. One
// thread owns everything; every step_period it
//
//   vision.detection (DDS) -> VisionObservation -+
//   referee.command (DDS, the operator) ---------+-> BuiltinReferee.step(now) -> Referee packet (league
//                                                    protobuf) multicast on group:port
//
// sending a packet at once on a new command and otherwise every send_period, as a Game Controller does.
// With teleport_placement_to (simulated matches) a ball placement is done by the simulator: one
// SimulatorCommand teleports the ball onto the placement point (counted as placements_teleported).
// Our own referee_gateway (and any other team's software) reads those packets like a Game Controller's,
// so referee.state and referee.event come from the usual gateway path: the packets are the only output.
// With a state_file the referee keeps the match there (the last Referee packet, written to a temporary
// file and renamed: on each new command and at least every second) and, when it starts and finds one
// written less than resume_within ago by the packet's own stamp, resumes it (BuiltinReferee::resume): a
// restarted referee goes on with the score, stage, clocks and cards instead of a new match in HALT. An
// unreadable or stale file is logged and a new match starts; failed writes are counted
// (state_file_errors).
// Health "referee_gateway/builtin" once per health_period: rate = packets sent per second, WARN while no
// fresh vision arrives (the referee then sees no ball), counters: packets_sent, send_errors,
// operator_commands, rejected_commands, vision_frames, invalid_detections and the core's input counters.
//
// Clocks: `wall` (Unix) stamps the packets and drives the referee's timers; a monotonic clock of the
// service's own paces the loop (stop() stops it, so the thread never hangs in a sleep).
//
//   auto service = BuiltinRefereeService::open(options, participant, logger, wall);
//   (*service)->start(); shutdown.wait(); (*service)->stop();
#pragma once

#include <spdlog/logger.h>

#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "libs/common/result.h"
#include "libs/dds/participant.h"
#include "libs/time/clock.h"
#include "services/referee_gateway/builtin/builtin_referee.h"

namespace ssl::referee {

/// How old the newest frame of a camera may be to count in the referee's observation (receive time).
inline constexpr time::Duration kVisionMaxAge = std::chrono::milliseconds(100);

struct BuiltinServiceOptions {
  std::string group = "224.5.23.1";
  int port = 10003;
  std::string interface_address = "127.0.0.1";
  RefereeProfile profile;
  FieldGeometry field = FieldGeometry::division_b();
  MatchSetup setup;
  time::Duration step_period = std::chrono::milliseconds(10);
  time::Duration send_period = std::chrono::milliseconds(100);  // between packets without a new command
  time::Duration vision_max_age = kVisionMaxAge;
  time::Duration health_period = std::chrono::seconds(1);
  std::string health_name = "referee_gateway/builtin";
  // In a simulated match: the simulator's control port (SimulatorCommand, UDP). When set, each ball
  // placement the referee orders is done by teleporting the ball onto the placement point at once (the
  // robots need not fetch a ball that rolled far out); the referee then sees the placement succeed.
  std::optional<std::string> teleport_placement_to;  // "host:port", e.g. "127.0.0.1:10300"
  std::string state_file;  // "" none
  time::Duration resume_within = std::chrono::minutes(10);
  time::Duration save_period = std::chrono::seconds(1);  // between writes without a new command
};

class BuiltinRefereeService {
 public:
  /// Opens the multicast sender, the two readers and the health reporter; the error names what failed.
  static Result<std::unique_ptr<BuiltinRefereeService>> open(const BuiltinServiceOptions& options,
                                                             dds::Participant& participant,
                                                             std::shared_ptr<spdlog::logger> logger,
                                                             time::Clock& wall);
  ~BuiltinRefereeService();  // stop()
  BuiltinRefereeService(const BuiltinRefereeService&) = delete;
  BuiltinRefereeService& operator=(const BuiltinRefereeService&) = delete;

  /// Starts the referee thread (once).
  void start();
  /// Stops and joins the referee thread; idempotent.
  void stop();

 private:
  struct Impl;
  explicit BuiltinRefereeService(std::unique_ptr<Impl> impl);

  std::unique_ptr<Impl> impl_;
  std::thread thread_;
};

}  // namespace ssl::referee
