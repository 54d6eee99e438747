#include "services/simulator/adapter/server.h"

#include <array>

#include "libs/league/decode.h"
#include "proto/ssl_simulation_synchronous.pb.h"
#include "services/simulator/adapter/convert.h"

namespace ssl::sim {
namespace {

constexpr std::size_t kReceiveBufferBytes = 65536;  // never truncates a UDP datagram
constexpr auto kReceivePoll = std::chrono::milliseconds(200);
constexpr std::uint16_t kGrsimBlueStatusPort = 30011;
constexpr std::uint16_t kGrsimYellowStatusPort = 30012;

std::vector<SimError> decode_error(const Error& error) { return {{"DECODE_ERROR", error.message}}; }

}  // namespace

Result<std::unique_ptr<SimulatorServer>> SimulatorServer::open(const ServerOptions& options) {
  std::vector<Port> ports;
  for (const auto& [channel, port] : {std::pair{Channel::kControl, options.control_port},
                                      std::pair{Channel::kBlue, options.blue_port},
                                      std::pair{Channel::kYellow, options.yellow_port},
                                      std::pair{Channel::kGrsim, options.grsim_port}}) {
    auto socket = net::UdpSocket::open(options.bind_address, port);
    if (!socket) return socket.error();
    ports.push_back({channel, std::move(*socket)});
  }
  auto vision = net::MulticastSender::open(options.vision_group, options.vision_port, options.interface_address);
  if (!vision) return vision.error();
  return std::unique_ptr<SimulatorServer>(new SimulatorServer(options, std::move(ports), std::move(*vision)));
}

SimulatorServer::SimulatorServer(ServerOptions options, std::vector<Port> ports, net::MulticastSender vision)
    : options_(std::move(options)), ports_(std::move(ports)), vision_(std::move(vision)) {
  for (Port& port : ports_) receivers_.emplace_back([this, &port] { receive_loop(port); });
}

SimulatorServer::~SimulatorServer() {
  for (Port& port : ports_) port.socket.interrupt();
  for (std::thread& receiver : receivers_) receiver.join();
}

void SimulatorServer::receive_loop(Port& port) {
  std::array<std::uint8_t, kReceiveBufferBytes> buffer;
  while (true) {
    const net::ReceiveResult result = port.socket.receive(buffer, kReceivePoll);
    if (result.status == net::ReceiveStatus::kInterrupted) return;
    if (result.status != net::ReceiveStatus::kReceived) continue;  // timeouts; errors are in the socket's counters
    {
      std::lock_guard lock(inbox_mutex_);
      inbox_.push_back({port.channel, result.sender, {buffer.begin(), buffer.begin() + result.size}});
    }
    inbox_changed_.notify_one();
  }
}

bool SimulatorServer::wait_for_input(std::chrono::nanoseconds timeout) {
  std::unique_lock lock(inbox_mutex_);
  return inbox_changed_.wait_for(lock, timeout, [this] { return !inbox_.empty(); });
}

void SimulatorServer::handle_pending(Simulator& sim, time::Duration unix_offset) {
  std::vector<Datagram> pending;
  {
    std::lock_guard lock(inbox_mutex_);
    pending.swap(inbox_);
  }
  for (const Datagram& datagram : pending) handle(datagram, sim, unix_offset);
}

SimulatorServer::Port& SimulatorServer::port_of(Channel channel) {
  for (Port& port : ports_) {
    if (port.channel == channel) return port;
  }
  return ports_.front();  // unreachable: every channel has a port
}

void SimulatorServer::answer(Port& port, const net::Endpoint& to, const google::protobuf::Message& message) {
  auto bytes = league::encode_datagram(message);
  const bool sent = bytes && port.socket.send_to(to, league::byte_span(*bytes)).ok();
  if (!sent) {
    std::lock_guard lock(counters_mutex_);
    ++counters_.send_failures;
  }
}

void SimulatorServer::handle(const Datagram& datagram, Simulator& sim, time::Duration unix_offset) {
  Port& port = port_of(datagram.channel);
  std::vector<SimError> errors;
  bool malformed = false;
  switch (datagram.channel) {
    case Channel::kControl: {
      if (options_.lockstep) {
        auto request = league::decode<SimulationSyncRequest>(datagram.bytes);
        SimulationSyncResponse response;
        if (!request) {
          malformed = true;
          errors = decode_error(request.error());
        } else {
          if (request->has_simulator_command()) {
            auto control = control_from_proto(request->simulator_command(), errors);
            auto applied = sim.apply(control);
            errors.insert(errors.end(), applied.begin(), applied.end());
          }
          if (request->has_robot_control()) {
            // A sync request carries one RobotControl without a team: it drives blue; yellow uses its port.
            auto commands = commands_from_proto(request->robot_control(), errors);
            auto applied = sim.set_commands(TeamColor::kBlue, commands);
            errors.insert(errors.end(), applied.begin(), applied.end());
          }
          const double step_s = request->has_sim_step() ? request->sim_step() : 1.0 / 75.0;
          if (!(step_s > 0 && step_s <= 1.0)) {
            errors.push_back({"INVALID_SIM_STEP", "sim_step must be in (0, 1] s"});
          } else {
            const StepOutput output =
                sim.step(std::chrono::duration_cast<time::Duration>(std::chrono::duration<double>(step_s)));
            for (const DetectionFrame& frame : output.frames) {
              *response.add_detection() = detection_to_proto(frame, unix_offset);
            }
            publish(output, sim, unix_offset);
            std::lock_guard lock(counters_mutex_);
            ++counters_.sync_steps;
          }
        }
        *response.mutable_robot_control_response() = response_to_proto(sim.feedback(TeamColor::kBlue), errors);
        answer(port, datagram.sender, response);
        break;
      }
      auto command = league::decode_simulator_command(datagram.bytes);
      if (!command) {
        malformed = true;
        errors = decode_error(command.error());
      } else {
        auto control = control_from_proto(*command, errors);
        auto applied = sim.apply(control);
        errors.insert(errors.end(), applied.begin(), applied.end());
      }
      answer(port, datagram.sender, response_to_proto(errors));
      std::lock_guard lock(counters_mutex_);
      ++counters_.control_requests;
      break;
    }
    case Channel::kBlue:
    case Channel::kYellow: {
      const TeamColor team = datagram.channel == Channel::kBlue ? TeamColor::kBlue : TeamColor::kYellow;
      auto control = league::decode_robot_control(datagram.bytes);
      if (!control) {
        malformed = true;
        errors = decode_error(control.error());
      } else {
        auto commands = commands_from_proto(*control, errors);
        auto applied = sim.set_commands(team, commands);
        errors.insert(errors.end(), applied.begin(), applied.end());
      }
      answer(port, datagram.sender, response_to_proto(sim.feedback(team), errors));
      std::lock_guard lock(counters_mutex_);
      ++counters_.robot_control_packets;
      break;
    }
    case Channel::kGrsim: {
      // grSim's legacy port has no response message: errors are only counted.
      auto packet = league::decode_grsim_packet(datagram.bytes);
      if (!packet) {
        malformed = true;
        errors = decode_error(packet.error());
      } else {
        GrsimInput input = grsim_from_proto(*packet, errors);
        auto applied = sim.apply(input.control);
        errors.insert(errors.end(), applied.begin(), applied.end());
        applied = sim.set_commands(input.team, input.commands);
        errors.insert(errors.end(), applied.begin(), applied.end());
        if (packet->has_commands()) {
          // As grSim does: the robots' status goes to the sender's address, port 30011 (blue) / 30012 (yellow).
          const std::uint16_t status_port = input.team == TeamColor::kBlue ? kGrsimBlueStatusPort : kGrsimYellowStatusPort;
          answer(port, net::Endpoint(datagram.sender.address(), status_port), grsim_status_to_proto(sim.feedback(input.team)));
        }
      }
      std::lock_guard lock(counters_mutex_);
      ++counters_.grsim_packets;
      break;
    }
  }
  std::lock_guard lock(counters_mutex_);
  if (malformed) ++counters_.malformed_packets;
  counters_.errors_answered += errors.size();
}

void SimulatorServer::publish(const StepOutput& output, const Simulator& sim, time::Duration unix_offset) {
  std::uint64_t sent = 0;
  std::uint64_t geometry = 0;
  std::uint64_t failures = 0;
  auto send = [&](const SSL_WrapperPacket& packet) {
    auto bytes = league::encode_datagram(packet);
    if (bytes && vision_.send(league::byte_span(*bytes)).ok()) return true;
    ++failures;
    return false;
  };
  if (output.geometry_due) {
    SSL_WrapperPacket packet;
    *packet.mutable_geometry() = geometry_to_proto(sim.geometry());
    packet.set_source(SSL_SOURCE_OTHER);
    geometry += send(packet) ? 1 : 0;
  }
  for (const DetectionFrame& frame : output.frames) {
    SSL_WrapperPacket packet;
    *packet.mutable_detection() = detection_to_proto(frame, unix_offset);
    packet.set_source(SSL_SOURCE_OTHER);
    sent += send(packet) ? 1 : 0;
  }
  std::lock_guard lock(counters_mutex_);
  counters_.vision_packets_sent += sent;
  counters_.geometry_packets_sent += geometry;
  counters_.send_failures += failures;
}

ServerCounters SimulatorServer::counters() const {
  std::lock_guard lock(counters_mutex_);
  return counters_;
}

}  // namespace ssl::sim
