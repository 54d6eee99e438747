#include "services/robot_link/backend/backend.h"

#include <array>
#include <chrono>
#include <optional>

#include "libs/league/decode.h"
#include "libs/net/udp.h"
#include "services/robot_link/backend/serial_port.h"
#include "services/robot_link/backend/wire_convert.h"
#include "services/robot_link/radio/radio_frame.h"

namespace ssl::robot_link {
namespace {

constexpr int kRadioDefaultPort = 10400;
constexpr std::size_t kMaxDrainPerPoll =
    64;  // datagrams / reads per poll_feedback, so a flood cannot stall a tick

double wall_clock_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

int resolve_port(const BackendOptions& options) {
  return options.port != 0 ? options.port : default_port(options.kind, options.team);
}

/// Sends a protobuf message as one datagram, counting the outcome.
Status send_message(net::UdpSocket& socket, const net::Endpoint& peer,
                    const google::protobuf::Message& message, BackendCounters& counters) {
  auto bytes = league::encode_datagram(message);
  if (!bytes) {
    ++counters.send_errors;
    return bytes.error();
  }
  if (Status sent = socket.send_to(peer, league::byte_span(*bytes)); !sent) {
    ++counters.send_errors;
    return sent;
  }
  ++counters.packets_sent;
  counters.bytes_sent += bytes->size();
  return {};
}

// ---------------------------------------------------------------------------------------------------------

/// The simulation protocol: RobotControl to the team's port, RobotControlResponse back on the same socket.
class SimBackend final : public Backend {
 public:
  SimBackend(net::UdpSocket socket, net::Endpoint peer) : socket_(std::move(socket)), peer_(peer) {}

  Status send(std::span<const OutgoingCommand> commands) override {
    return send_message(socket_, peer_, to_robot_control(commands), counters_);
  }

  std::vector<FeedbackReport> poll_feedback() override {
    std::vector<FeedbackReport> reports;
    for (std::size_t i = 0; i < kMaxDrainPerPoll; ++i) {
      const net::ReceiveResult received = socket_.receive(buffer_, std::chrono::nanoseconds(0));
      if (received.status == net::ReceiveStatus::kTruncated) {
        ++counters_.feedback_errors;
        continue;
      }
      if (!received.ok()) break;
      auto response = league::decode_robot_control_response(std::span(buffer_).first(received.size));
      if (!response) {
        ++counters_.feedback_errors;
        last_error_ = response.error().message;
        continue;
      }
      ++counters_.feedback_received;
      counters_.remote_errors += static_cast<std::uint64_t>(response->errors_size());
      if (response->errors_size() > 0) {
        const SimulatorError& error = response->errors(response->errors_size() - 1);
        last_error_ = "simulator: " + error.code() + ": " + error.message();
      }
      for (FeedbackReport& report : feedback_from_response(*response)) reports.push_back(report);
    }
    return reports;
  }

  BackendCounters counters() const override { return counters_; }
  std::string description() const override { return "sim " + peer_.to_string(); }
  std::string last_error() const override { return last_error_; }

 private:
  net::UdpSocket socket_;
  net::Endpoint peer_;
  BackendCounters counters_;
  std::string last_error_;
  std::array<std::uint8_t, 65536> buffer_{};
};

// ---------------------------------------------------------------------------------------------------------

/// grSim's legacy protocol: grSim_Packet to 20011; Robots_Status arrives on 30011/30012 (optional).
class GrsimBackend final : public Backend {
 public:
  GrsimBackend(net::UdpSocket socket, net::Endpoint peer, TeamColor team,
               std::optional<net::UdpSocket> status)
      : socket_(std::move(socket)), peer_(peer), team_(team), status_(std::move(status)) {}

  Status send(std::span<const OutgoingCommand> commands) override {
    return send_message(socket_, peer_, to_grsim_packet(commands, team_, wall_clock_seconds()), counters_);
  }

  std::vector<FeedbackReport> poll_feedback() override {
    std::vector<FeedbackReport> reports;
    if (!status_) return reports;
    for (std::size_t i = 0; i < kMaxDrainPerPoll; ++i) {
      const net::ReceiveResult received = status_->receive(buffer_, std::chrono::nanoseconds(0));
      if (received.status == net::ReceiveStatus::kTruncated) {
        ++counters_.feedback_errors;
        continue;
      }
      if (!received.ok()) break;
      auto status = league::decode_grsim_robots_status(std::span(buffer_).first(received.size));
      if (!status) {
        ++counters_.feedback_errors;
        last_error_ = status.error().message;
        continue;
      }
      ++counters_.feedback_received;
      for (FeedbackReport& report : feedback_from_grsim_status(*status)) reports.push_back(report);
    }
    return reports;
  }

  BackendCounters counters() const override { return counters_; }
  std::string description() const override {
    std::string text = "grsim " + peer_.to_string();
    if (status_) text += ", status on :" + std::to_string(status_->local_endpoint().port());
    return text;
  }
  std::string last_error() const override { return last_error_; }

 private:
  net::UdpSocket socket_;
  net::Endpoint peer_;
  TeamColor team_;
  std::optional<net::UdpSocket> status_;
  BackendCounters counters_;
  std::string last_error_;
  std::array<std::uint8_t, 65536> buffer_{};
};

// ---------------------------------------------------------------------------------------------------------

/// Where radio frames travel: UDP datagrams to a base station or bytes on a serial line.
class ByteLink {
 public:
  virtual ~ByteLink() = default;
  virtual Status write(std::span<const std::uint8_t> bytes) = 0;
  /// Non-blocking; 0 when nothing is waiting.
  virtual Result<std::size_t> read(std::span<std::uint8_t> buffer) = 0;
  virtual std::string description() const = 0;
};

class UdpLink final : public ByteLink {
 public:
  UdpLink(net::UdpSocket socket, net::Endpoint peer) : socket_(std::move(socket)), peer_(peer) {}
  Status write(std::span<const std::uint8_t> bytes) override { return socket_.send_to(peer_, bytes); }
  Result<std::size_t> read(std::span<std::uint8_t> buffer) override {
    const net::ReceiveResult received = socket_.receive(buffer, std::chrono::nanoseconds(0));
    if (received.ok()) return received.size;
    if (received.status == net::ReceiveStatus::kTruncated) return Error{"radio datagram too large"};
    if (received.status == net::ReceiveStatus::kError) return Error{received.error};
    return std::size_t{0};
  }
  std::string description() const override { return "udp " + peer_.to_string(); }

 private:
  net::UdpSocket socket_;
  net::Endpoint peer_;
};

class SerialLink final : public ByteLink {
 public:
  explicit SerialLink(SerialPort port, int baud) : port_(std::move(port)), baud_(baud) {}
  Status write(std::span<const std::uint8_t> bytes) override { return port_.write(bytes); }
  Result<std::size_t> read(std::span<std::uint8_t> buffer) override { return port_.read(buffer); }
  std::string description() const override { return "serial " + port_.path() + " @" + std::to_string(baud_); }

 private:
  SerialPort port_;
  int baud_;
};

/// Our radio: a command frame per tick, status frames back (a stream: frames may be split or merged).
class RadioBackend final : public Backend {
 public:
  explicit RadioBackend(std::unique_ptr<ByteLink> link) : link_(std::move(link)) {}

  Status send(std::span<const OutgoingCommand> commands) override {
    auto bytes = radio::encode_command_frame(to_command_frame(commands, sequence_));
    if (!bytes) {
      ++counters_.send_errors;
      return bytes.error();
    }
    ++sequence_;  // a frame that failed to leave still uses its number: the robot sees the gap
    if (Status sent = link_->write(*bytes); !sent) {
      ++counters_.send_errors;
      return sent;
    }
    ++counters_.packets_sent;
    counters_.bytes_sent += bytes->size();
    return {};
  }

  std::vector<FeedbackReport> poll_feedback() override {
    std::vector<FeedbackReport> reports;
    for (std::size_t i = 0; i < kMaxDrainPerPoll; ++i) {
      auto got = link_->read(buffer_);
      if (!got) {
        ++counters_.feedback_errors;
        last_error_ = got.error().message;
        break;
      }
      if (*got == 0) break;
      const std::uint64_t bad_before = assembler_.bad_frames();
      for (const radio::RadioFrame& frame : assembler_.push(std::span(buffer_).first(*got))) {
        const auto* status = std::get_if<radio::StatusFrame>(&frame);
        if (status == nullptr) {
          ++counters_.feedback_errors;  // a command frame echoed back: not feedback
          last_error_ = "radio: unexpected command frame from the base station";
          continue;
        }
        if (last_status_sequence_) {
          const auto gap = static_cast<std::uint16_t>(status->sequence - *last_status_sequence_ - 1);
          if (gap < 1000) counters_.frames_lost += gap;  // larger jumps: the base station restarted
        }
        last_status_sequence_ = status->sequence;
        ++counters_.feedback_received;
        for (FeedbackReport& report : feedback_from_status_frame(*status)) reports.push_back(report);
      }
      if (assembler_.bad_frames() != bad_before) {
        counters_.feedback_errors += assembler_.bad_frames() - bad_before;
        last_error_ = "radio: corrupt frame(s) skipped";
      }
    }
    return reports;
  }

  BackendCounters counters() const override { return counters_; }
  std::string description() const override { return "radio " + link_->description(); }
  std::string last_error() const override { return last_error_; }

 private:
  std::unique_ptr<ByteLink> link_;
  std::uint16_t sequence_ = 0;
  radio::FrameAssembler assembler_;
  std::optional<std::uint16_t> last_status_sequence_;
  BackendCounters counters_;
  std::string last_error_;
  std::array<std::uint8_t, 4096> buffer_{};
};

}  // namespace

int default_port(BackendKind kind, TeamColor team) {
  switch (kind) {
    case BackendKind::kSim: return team == TeamColor::kBlue ? 10301 : 10302;
    case BackendKind::kGrsim: return 20011;
    case BackendKind::kRadio: return kRadioDefaultPort;
  }
  return 0;
}

int default_grsim_status_port(TeamColor team) { return team == TeamColor::kBlue ? 30011 : 30012; }

Result<std::unique_ptr<Backend>> make_backend(const BackendOptions& options) {
  const bool needs_udp_peer =
      options.kind != BackendKind::kRadio || options.radio_transport == RadioTransport::kUdp;
  net::Endpoint peer;
  if (needs_udp_peer) {
    auto parsed = net::Endpoint::from_parts(options.host, resolve_port(options));
    if (!parsed) return parsed.error();
    peer = *parsed;
  }
  switch (options.kind) {
    case BackendKind::kSim: {
      auto socket = net::UdpSocket::open(options.bind_address, 0);
      if (!socket) return socket.error();
      return std::unique_ptr<Backend>(std::make_unique<SimBackend>(std::move(*socket), peer));
    }
    case BackendKind::kGrsim: {
      auto socket = net::UdpSocket::open(options.bind_address, 0);
      if (!socket) return socket.error();
      std::optional<net::UdpSocket> status;
      if (options.grsim_feedback) {
        const int port = options.grsim_status_port != 0 ? options.grsim_status_port
                                                        : default_grsim_status_port(options.team);
        auto opened = net::UdpSocket::open(options.bind_address, port);
        if (!opened) return Error{"grSim status port: " + opened.error().message};
        status.emplace(std::move(*opened));
      }
      return std::unique_ptr<Backend>(
          std::make_unique<GrsimBackend>(std::move(*socket), peer, options.team, std::move(status)));
    }
    case BackendKind::kRadio: {
      std::unique_ptr<ByteLink> link;
      if (options.radio_transport == RadioTransport::kUdp) {
        auto socket = net::UdpSocket::open(options.bind_address, options.radio_local_port);
        if (!socket) return socket.error();
        link = std::make_unique<UdpLink>(std::move(*socket), peer);
      } else {
        if (options.serial_device.empty())
          return Error{"radio over serial needs a device path (radio.device)"};
        auto port = SerialPort::open(options.serial_device, options.serial_baud);
        if (!port) return port.error();
        link = std::make_unique<SerialLink>(std::move(*port), options.serial_baud);
      }
      return std::unique_ptr<Backend>(std::make_unique<RadioBackend>(std::move(link)));
    }
  }
  return Error{"unknown backend"};
}

}  // namespace ssl::robot_link
