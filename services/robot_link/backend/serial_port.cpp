#include "services/robot_link/backend/serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace ssl::robot_link {
namespace {

struct BaudRate {
  int baud;
  speed_t speed;
};

constexpr BaudRate kBaudRates[] = {
    {9600, B9600},       {19200, B19200},     {38400, B38400},     {57600, B57600},     {115200, B115200},
    {230400, B230400},   {460800, B460800},   {500000, B500000},   {576000, B576000},   {921600, B921600},
    {1000000, B1000000}, {1152000, B1152000}, {1500000, B1500000}, {2000000, B2000000}, {2500000, B2500000},
    {3000000, B3000000}, {3500000, B3500000}, {4000000, B4000000},
};

std::string errno_text(int error) { return std::strerror(error); }

}  // namespace

bool is_supported_baud(int baud) {
  for (const BaudRate& rate : kBaudRates) {
    if (rate.baud == baud) return true;
  }
  return false;
}

Result<SerialPort> SerialPort::open(const std::string& path, int baud) {
  speed_t speed = 0;
  bool found = false;
  for (const BaudRate& rate : kBaudRates) {
    if (rate.baud == baud) {
      speed = rate.speed;
      found = true;
    }
  }
  const std::string name = "serial " + path;
  if (!found) return Error{name + ": unsupported baud rate " + std::to_string(baud)};
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return Error{name + ": open failed: " + errno_text(errno)};
  SerialPort port(fd, path);  // closes fd on every error path below

  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) return Error{name + ": not a terminal device: " + errno_text(errno)};
  ::cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS);
  tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (::cfsetispeed(&tio, speed) != 0 || ::cfsetospeed(&tio, speed) != 0) {
    return Error{name + ": cannot set " + std::to_string(baud) + " baud: " + errno_text(errno)};
  }
  if (::tcsetattr(fd, TCSANOW, &tio) != 0) return Error{name + ": tcsetattr failed: " + errno_text(errno)};
  ::tcflush(fd, TCIOFLUSH);
  return port;
}

SerialPort::SerialPort(SerialPort&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), path_(std::move(other.path_)) {}

SerialPort& SerialPort::operator=(SerialPort&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
    path_ = std::move(other.path_);
  }
  return *this;
}

SerialPort::~SerialPort() {
  if (fd_ >= 0) ::close(fd_);
}

Status SerialPort::write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds write_timeout) {
  if (fd_ < 0) return Error{"serial port is closed"};
  std::size_t done = 0;
  bool waited = false;
  while (done < bytes.size()) {
    const ssize_t written = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (written > 0) {
      done += static_cast<std::size_t>(written);
      continue;
    }
    if (written < 0 && errno == EINTR) continue;
    if (written < 0 && (errno == EAGAIN || errno == EWOULDBLOCK) && !waited) {
      pollfd entry{.fd = fd_, .events = POLLOUT, .revents = 0};
      ::poll(&entry, 1, static_cast<int>(write_timeout.count()));
      waited = true;
      continue;
    }
    const int error = errno;
    return Error{"serial " + path_ + ": wrote " + std::to_string(done) + " of " +
                 std::to_string(bytes.size()) +
                 " bytes: " + (written < 0 ? errno_text(error) : std::string("device full"))};
  }
  return {};
}

Result<std::size_t> SerialPort::read(std::span<std::uint8_t> buffer, std::chrono::milliseconds timeout) {
  if (fd_ < 0) return Error{"serial port is closed"};
  pollfd entry{.fd = fd_, .events = POLLIN, .revents = 0};
  const int ready = ::poll(&entry, 1, static_cast<int>(timeout.count()));
  if (ready < 0) {
    if (errno == EINTR) return std::size_t{0};
    return Error{"serial " + path_ + ": poll failed: " + errno_text(errno)};
  }
  if (ready == 0) return std::size_t{0};
  const ssize_t got = ::read(fd_, buffer.data(), buffer.size());
  if (got > 0) return static_cast<std::size_t>(got);
  if (got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return std::size_t{0};
  if (got == 0 || (entry.revents & POLLHUP) != 0) return Error{"serial " + path_ + ": device hung up"};
  return Error{"serial " + path_ + ": read failed: " + errno_text(errno)};
}

}  // namespace ssl::robot_link
