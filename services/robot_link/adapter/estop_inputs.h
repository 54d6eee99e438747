// Local e-stop inputs of robot_link, besides the system.estop topic:
//  - a serial e-stop device (a button box on USB serial). Byte protocol, device -> robot_link: '1'
//    engaged, '0' released; CR, LF, spaces and tabs are ignored (so "1\n" lines work); any other byte is
//    counted as garbage and ignored. The newest state byte wins. Devices should repeat their state
//    (e.g. every 100 ms) but need not. Fail-safe: a device that cannot be opened, hangs up or errors
//    engages the e-stop ("e-stop device lost"); it is reopened once per second, and only an explicit '0'
//    (or any engaged=false sample) releases.
//  - the keyboard (`--keyboard-estop`): when stdin is a terminal it is switched to non-canonical,
//    no-echo mode (restored on exit) and each space toggles the e-stop.
// Both are polled (never blocking) from the fixed-rate loop.
//
//   SerialEstop device("/dev/ttyACM0", 9600);
//   if (auto event = device.poll(clock.now())) {
//     mailbox.on_estop(event->engaged, "estop device", event->reason);
//   }
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "libs/time/time.h"
#include "services/robot_link/backend/serial_port.h"

struct termios;

namespace ssl::robot_link {

/// Parses the serial e-stop byte protocol (pure).
class EstopByteParser {
 public:
  /// The newest state in `bytes` (true = engaged), nullopt when they hold none.
  std::optional<bool> feed(std::span<const std::uint8_t> bytes);
  std::uint64_t garbage_bytes() const noexcept { return garbage_; }

 private:
  std::uint64_t garbage_ = 0;
};

struct EstopEvent {
  bool engaged = false;
  std::string reason;
};

class SerialEstop {
 public:
  SerialEstop(std::string path, int baud);

  /// The state change since the last poll, if any (device readings and device loss).
  std::optional<EstopEvent> poll(time::Timestamp now_mono);

  bool connected() const noexcept { return port_.has_value(); }
  std::uint64_t garbage_bytes() const noexcept { return parser_.garbage_bytes(); }
  std::uint64_t device_losses() const noexcept { return losses_; }
  const std::string& last_error() const noexcept { return last_error_; }

 private:
  std::optional<EstopEvent> lost(std::string why);

  std::string path_;
  int baud_;
  std::optional<SerialPort> port_;
  bool reported_loss_ = false;
  std::optional<time::Timestamp> next_open_mono_;
  std::optional<bool> last_state_;
  EstopByteParser parser_;
  std::uint64_t losses_ = 0;
  std::string last_error_;
};

/// Space bar toggles; owns the terminal mode of stdin while it lives.
class KeyboardEstop {
 public:
  KeyboardEstop();
  ~KeyboardEstop();
  KeyboardEstop(const KeyboardEstop&) = delete;
  KeyboardEstop& operator=(const KeyboardEstop&) = delete;

  /// False when stdin is not a terminal (then poll() never reports).
  bool active() const noexcept { return active_; }

  /// Number of space presses since the last poll (never blocks).
  int poll();

 private:
  bool active_ = false;
  std::unique_ptr<termios> saved_;  // the original mode, restored in the destructor
};

}  // namespace ssl::robot_link
