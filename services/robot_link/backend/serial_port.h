// SerialPort: a serial device (USB radio base station, serial e-stop button) opened in raw mode with
// termios: 8N1, no flow control, no echo or line processing, at a configured baud rate. Reads and writes
// never block for long: reads return what is available (possibly nothing); a write waits at most
// `write_timeout` for the device to accept all bytes. A pseudo-terminal (posix_openpt) can stand in for
// the device in tests: open its slave path here and talk to the master side.
//
//   auto port = SerialPort::open("/dev/ttyUSB0", 115200);
//   if (!port) fail(port.error().message);     // "serial /dev/ttyUSB0: open failed: No such file..."
//   (void)port->write(frame_bytes);
//   std::array<std::uint8_t, 512> buffer;
//   auto got = port->read(buffer);             // 0 bytes when nothing arrived
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "libs/common/result.h"

namespace ssl::robot_link {

/// True when `baud` is a rate termios supports (9600 ... 4000000).
bool is_supported_baud(int baud);

class SerialPort {
 public:
  /// Opens `path` (O_NOCTTY, non-blocking) and sets raw mode at `baud`. Error names the path and errno.
  static Result<SerialPort> open(const std::string& path, int baud);

  SerialPort(SerialPort&& other) noexcept;
  SerialPort& operator=(SerialPort&& other) noexcept;
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;
  ~SerialPort();

  /// Writes every byte, waiting at most `write_timeout` for room in the device's buffer.
  Status write(std::span<const std::uint8_t> bytes,
               std::chrono::milliseconds write_timeout = std::chrono::milliseconds(5));

  /// Reads what is available (up to buffer.size()), waiting at most `timeout` for the first byte;
  /// 0 when nothing arrived. Error when the device failed or hung up (unplugged).
  Result<std::size_t> read(std::span<std::uint8_t> buffer,
                           std::chrono::milliseconds timeout = std::chrono::milliseconds(0));

  const std::string& path() const noexcept { return path_; }
  int fd() const noexcept { return fd_; }

 private:
  SerialPort(int fd, std::string path) noexcept : fd_(fd), path_(std::move(path)) {}

  int fd_ = -1;
  std::string path_;
};

}  // namespace ssl::robot_link
