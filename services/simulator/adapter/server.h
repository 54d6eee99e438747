// SimulatorServer: the simulator's network face. It serves the league's simulation protocol (control on
// UDP 10300, blue robots 10301, yellow robots 10302), grSim's legacy commands (UDP 20011) and sends
// SSL-Vision packets to multicast 224.5.23.2:10020, so other teams' software drives it as it drives grSim
// or the ER-Force simulator.
//
// One receiver thread per port only copies datagrams into an inbox; the owner's loop drains the inbox
// with handle_pending() on its own thread, so the Simulator core is only ever touched by one thread.
// Every datagram gets an answer (SimulatorResponse / RobotControlResponse) to its sender's address and
// port; malformed ones are answered with a DECODE_ERROR and counted, never crash anything.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <google/protobuf/message.h>

#include "libs/common/result.h"
#include "libs/net/multicast.h"
#include "libs/net/udp.h"
#include "services/simulator/core/simulator.h"

namespace ssl::sim {

struct ServerOptions {
  std::string bind_address = "0.0.0.0";       // where the protocol ports listen
  std::string interface_address = "127.0.0.1"; // multicast interface of the vision output
  std::string vision_group = "224.5.23.2";
  int vision_port = 10020;
  int control_port = 10300;
  int blue_port = 10301;
  int yellow_port = 10302;
  int grsim_port = 20011;
  bool lockstep = false;  // the control port speaks SimulationSyncRequest/Response instead
};

/// What the server has done since it started; published on health.
struct ServerCounters {
  std::uint64_t control_requests = 0;
  std::uint64_t robot_control_packets = 0;
  std::uint64_t grsim_packets = 0;
  std::uint64_t sync_steps = 0;
  std::uint64_t malformed_packets = 0;   // could not be decoded (answered with DECODE_ERROR)
  std::uint64_t errors_answered = 0;     // SimulatorErrors sent back, malformed ones included
  std::uint64_t vision_packets_sent = 0;
  std::uint64_t geometry_packets_sent = 0;
  std::uint64_t send_failures = 0;
};

class SimulatorServer {
 public:
  static Result<std::unique_ptr<SimulatorServer>> open(const ServerOptions& options);
  ~SimulatorServer();  // wakes and joins the receiver threads
  SimulatorServer(const SimulatorServer&) = delete;
  SimulatorServer& operator=(const SimulatorServer&) = delete;

  /// Waits until a datagram is pending or `timeout` passes; true when one is pending.
  bool wait_for_input(std::chrono::nanoseconds timeout);

  /// Applies every pending datagram to `sim` in arrival order and answers each sender. In lockstep mode
  /// a SimulationSyncRequest also steps the simulation and its vision output is answered and published.
  void handle_pending(Simulator& sim, time::Duration unix_offset);

  /// Sends the vision output of one step (and the geometry when due) to the multicast group.
  void publish(const StepOutput& output, const Simulator& sim, time::Duration unix_offset);

  ServerCounters counters() const;
  const ServerOptions& options() const { return options_; }

 private:
  enum class Channel { kControl, kBlue, kYellow, kGrsim };
  struct Datagram {
    Channel channel;
    net::Endpoint sender;
    std::vector<std::uint8_t> bytes;
  };
  struct Port {
    Channel channel;
    net::UdpSocket socket;
  };

  SimulatorServer(ServerOptions options, std::vector<Port> ports, net::MulticastSender vision);
  void receive_loop(Port& port);
  void answer(Port& port, const net::Endpoint& to, const google::protobuf::Message& message);
  void handle(const Datagram& datagram, Simulator& sim, time::Duration unix_offset);
  Port& port_of(Channel channel);

  ServerOptions options_;
  std::vector<Port> ports_;
  net::MulticastSender vision_;
  std::vector<std::thread> receivers_;

  std::mutex inbox_mutex_;
  std::condition_variable inbox_changed_;
  std::vector<Datagram> inbox_;

  mutable std::mutex counters_mutex_;
  ServerCounters counters_;
};

}  // namespace ssl::sim
