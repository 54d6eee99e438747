#include "services/robot_link/adapter/estop_inputs.h"

#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <chrono>

namespace ssl::robot_link {

std::optional<bool> EstopByteParser::feed(std::span<const std::uint8_t> bytes) {
  std::optional<bool> state;
  for (const std::uint8_t byte : bytes) {
    switch (byte) {
      case '1': state = true; break;
      case '0': state = false; break;
      case '\r':
      case '\n':
      case ' ':
      case '\t': break;
      default: ++garbage_; break;
    }
  }
  return state;
}

// ---------------------------------------------------------------------------------------------------------

SerialEstop::SerialEstop(std::string path, int baud) : path_(std::move(path)), baud_(baud) {}

std::optional<EstopEvent> SerialEstop::lost(std::string why) {
  port_.reset();
  last_error_ = std::move(why);
  ++losses_;
  last_state_.reset();
  if (reported_loss_) return std::nullopt;
  reported_loss_ = true;
  return EstopEvent{true, "e-stop device lost: " + last_error_};
}

std::optional<EstopEvent> SerialEstop::poll(time::Timestamp now_mono) {
  if (!port_) {
    if (next_open_mono_ && now_mono < *next_open_mono_) return std::nullopt;
    next_open_mono_ = now_mono + std::chrono::seconds(1);
    auto opened = SerialPort::open(path_, baud_);
    if (!opened) return lost(opened.error().message);
    port_.emplace(std::move(*opened));
    reported_loss_ = false;
  }
  std::array<std::uint8_t, 256> buffer{};
  std::optional<bool> state;
  for (int i = 0; i < 16; ++i) {
    auto got = port_->read(buffer);
    if (!got) return lost(got.error().message);
    if (*got == 0) break;
    if (auto parsed = parser_.feed(std::span(buffer).first(*got))) state = parsed;
  }
  if (!state || state == last_state_) return std::nullopt;
  last_state_ = state;
  return EstopEvent{*state, *state ? "e-stop button pressed" : "e-stop button released"};
}

// ---------------------------------------------------------------------------------------------------------

KeyboardEstop::KeyboardEstop() {
  if (::isatty(STDIN_FILENO) == 0) return;
  termios original{};
  if (::tcgetattr(STDIN_FILENO, &original) != 0) return;
  termios raw = original;
  raw.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO);
  raw.c_cc[VMIN] = 0;
  raw.c_cc[VTIME] = 0;
  if (::tcsetattr(STDIN_FILENO, TCSANOW, &raw) != 0) return;
  saved_ = std::make_unique<termios>(original);
  active_ = true;
}

KeyboardEstop::~KeyboardEstop() {
  if (saved_) ::tcsetattr(STDIN_FILENO, TCSANOW, saved_.get());
}

int KeyboardEstop::poll() {
  if (!active_) return 0;
  int presses = 0;
  for (int i = 0; i < 16; ++i) {
    pollfd entry{.fd = STDIN_FILENO, .events = POLLIN, .revents = 0};
    if (::poll(&entry, 1, 0) <= 0 || (entry.revents & POLLIN) == 0) break;
    std::array<char, 64> buffer{};
    const ssize_t got = ::read(STDIN_FILENO, buffer.data(), buffer.size());
    if (got <= 0) {
      active_ = false;  // the terminal went away
      break;
    }
    for (ssize_t j = 0; j < got; ++j) presses += buffer[static_cast<std::size_t>(j)] == ' ' ? 1 : 0;
  }
  return presses;
}

}  // namespace ssl::robot_link
