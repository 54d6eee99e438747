// ConsoleService: the console's network and DDS face. It owns
//   * readers of everything the page shows: vision.detection, vision.geometry, referee.state,
//     referee.event, system.health, system.estop, and per team world.state, planner.debug, robot.feedback;
//     polled by the console loop at the frame rate (no middleware callbacks), fed to ConsoleState;
//   * writers of the operator's actions: referee.command, and system.estop through a participant of its
//     own (Fast DDS does not keep a writer's liveliness asserted towards readers of its own participant);
//   * a UDP socket to the simulator's control port (placing the ball and robots), when configured;
//   * the HTTP server (cpp-httplib): the page, /events (Server-Sent Events through StreamHub), /api/state
//     and the POST actions of PROTOCOL.md, each checked by AccessPolicy;
//   * its system.health ("console/<http port>"): viewers, frames sent and dropped, actions done and refused.
// The console loop is the only writer of ConsoleState; HTTP threads read it and log actions under the
// same mutex.
//
//   auto service = ConsoleService::create(options, participant, logger);
//   (*service)->run(shutdown);   // until SIGINT/SIGTERM
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "libs/common/result.h"
#include "libs/common/shutdown.h"
#include "libs/dds/participant.h"
#include "services/console/core/console_state.h"

namespace spdlog {
class logger;
}

namespace ssl::console {

struct ServiceOptions {
  int http_port = 8080;                 // 0: any free port (tests)
  std::string bind = "127.0.0.1";
  std::string token;                    // "" none
  std::size_t max_streams = 32;
  double frame_rate = 30;               // Hz
  std::string simulator_control;        // "" none, else host:port
  std::optional<referee::RefereeProfile> profile;
  ConsoleStateOptions state;
  dds::ParticipantOptions estop_participant;  // the e-stop writer's own participant (domain, discovery)
};

class ConsoleService {
 public:
  static Result<std::unique_ptr<ConsoleService>> create(const ServiceOptions& options, dds::Participant& participant,
                                                        std::shared_ptr<spdlog::logger> logger);
  ~ConsoleService();
  ConsoleService(const ConsoleService&) = delete;
  ConsoleService& operator=(const ConsoleService&) = delete;

  /// The HTTP port the page is served on (the bound one when options.http_port was 0).
  int port() const;
  /// Serves and streams until `shutdown` is requested.
  void run(ShutdownSignal& shutdown);

 private:
  struct Impl;
  explicit ConsoleService(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace ssl::console
