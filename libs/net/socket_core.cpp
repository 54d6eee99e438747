#include "libs/net/socket_core.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>

namespace ssl::net::detail {
namespace {

sockaddr_in to_sockaddr(const Endpoint& endpoint) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(endpoint.address());
  address.sin_port = htons(endpoint.port());
  return address;
}

Endpoint from_sockaddr(const sockaddr_in& address) {
  return Endpoint(ntohl(address.sin_addr.s_addr), ntohs(address.sin_port));
}

timespec to_timespec(std::chrono::nanoseconds duration) {
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(duration);
  return timespec{static_cast<std::time_t>(seconds.count()), static_cast<long>((duration - seconds).count())};
}

constexpr auto kRelaxed = std::memory_order_relaxed;

}  // namespace

std::string errno_message(std::string_view what) {
  const int error = errno;
  char buffer[256];
  // GNU strerror_r: thread-safe (sockets are used from several threads), returns the text to use.
  return std::string(what) + " failed: " + ::strerror_r(error, buffer, sizeof buffer);
}

Result<std::unique_ptr<SocketCore>> SocketCore::create() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, IPPROTO_UDP);
  if (fd < 0) return Error{errno_message("create UDP socket")};
  const int wake_fd = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (wake_fd < 0) {
    Error error{errno_message("create eventfd")};
    ::close(fd);
    return error;
  }
  return std::unique_ptr<SocketCore>(new SocketCore(fd, wake_fd));
}

SocketCore::~SocketCore() {
  ::close(fd_);
  ::close(wake_fd_);
}

Status SocketCore::set_int_option(int level, int name, int value, std::string_view what) {
  return set_option(level, name, &value, sizeof value, what);
}

Result<int> SocketCore::int_option(int level, int name, std::string_view what) const {
  int value = 0;
  socklen_t length = sizeof value;
  if (::getsockopt(fd_, level, name, &value, &length) != 0) return Error{errno_message(what)};
  return value;
}

Status SocketCore::set_option(int level, int name, const void* value, unsigned length,
                              std::string_view what) {
  if (::setsockopt(fd_, level, name, value, length) != 0) return Error{errno_message(what)};
  return Status::success();
}

Status SocketCore::bind(const Endpoint& local) {
  const sockaddr_in address = to_sockaddr(local);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    return Error{errno_message("bind " + local.to_string())};
  }
  return Status::success();
}

Result<Endpoint> SocketCore::local_endpoint() const {
  sockaddr_in address{};
  socklen_t length = sizeof address;
  if (::getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    return Error{errno_message("getsockname")};
  }
  return from_sockaddr(address);
}

Status SocketCore::send_to(const Endpoint& destination, std::span<const std::uint8_t> bytes) {
  const sockaddr_in address = to_sockaddr(destination);
  for (;;) {
    // Never blocks: a datagram that finds the socket's send buffer full is not sent (EAGAIN, counted by
    // the caller as a send error). A blocked sendto stalled the built-in referee's loop for 4-5 s under a
    // garbage flood on its ports (tests/faults); a real-time sender drops rather than waits.
    const ssize_t sent = ::sendto(fd_, bytes.data(), bytes.size(), MSG_DONTWAIT,
                                  reinterpret_cast<const sockaddr*>(&address), sizeof address);
    if (sent >= 0) {
      sent_.fetch_add(1, kRelaxed);
      bytes_sent_.fetch_add(static_cast<std::uint64_t>(sent), kRelaxed);
      return Status::success();
    }
    if (errno == EINTR) continue;
    send_errors_.fetch_add(1, kRelaxed);
    return Error{
        errno_message("send " + std::to_string(bytes.size()) + " bytes to " + destination.to_string())};
  }
}

ReceiveResult SocketCore::fail_receive(std::string message) {
  receive_errors_.fetch_add(1, kRelaxed);
  return ReceiveResult{ReceiveStatus::kError, 0, Endpoint{}, std::move(message)};
}

ReceiveResult SocketCore::receive(std::span<std::uint8_t> buffer, std::chrono::nanoseconds timeout) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point deadline = Clock::now() + std::max(timeout, std::chrono::nanoseconds::zero());
  for (;;) {
    pollfd fds[2] = {{fd_, POLLIN, 0}, {wake_fd_, POLLIN, 0}};
    const timespec remaining =
        to_timespec(std::max(std::chrono::duration_cast<std::chrono::nanoseconds>(deadline - Clock::now()),
                             std::chrono::nanoseconds{0}));
    const int ready = ::ppoll(fds, 2, &remaining, nullptr);
    if (ready < 0) {
      if (errno == EINTR) continue;  // a signal: poll again for the remaining time
      return fail_receive(errno_message("poll"));
    }
    // The interrupt wins over pending datagrams so that shutdown is prompt even under load.
    if (fds[1].revents != 0) return ReceiveResult{ReceiveStatus::kInterrupted, 0, Endpoint{}, {}};
    if (ready == 0) return ReceiveResult{ReceiveStatus::kTimeout, 0, Endpoint{}, {}};

    sockaddr_in from{};
    socklen_t from_length = sizeof from;
    // MSG_TRUNC makes recvfrom return the datagram's real size even when it did not fit the buffer.
    const ssize_t size = ::recvfrom(fd_, buffer.data(), buffer.size(), MSG_TRUNC | MSG_DONTWAIT,
                                    reinterpret_cast<sockaddr*>(&from), &from_length);
    if (size < 0) {
      // Readable but nothing to read (e.g. a datagram dropped for a bad checksum): wait again.
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) continue;
      return fail_receive(errno_message("receive"));
    }
    const auto full_size = static_cast<std::size_t>(size);
    if (full_size > buffer.size()) {
      truncated_.fetch_add(1, kRelaxed);
      return ReceiveResult{ReceiveStatus::kTruncated, full_size, from_sockaddr(from), {}};
    }
    received_.fetch_add(1, kRelaxed);
    bytes_received_.fetch_add(full_size, kRelaxed);
    return ReceiveResult{ReceiveStatus::kReceived, full_size, from_sockaddr(from), {}};
  }
}

void SocketCore::interrupt() noexcept {
  // The eventfd counter is never read back, so it stays readable: the interrupt is latched.
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t written = ::write(wake_fd_, &one, sizeof one);
}

SocketCounters SocketCore::counters() const noexcept {
  SocketCounters counters;
  counters.received = received_.load(kRelaxed);
  counters.bytes_received = bytes_received_.load(kRelaxed);
  counters.truncated = truncated_.load(kRelaxed);
  counters.receive_errors = receive_errors_.load(kRelaxed);
  counters.sent = sent_.load(kRelaxed);
  counters.bytes_sent = bytes_sent_.load(kRelaxed);
  counters.send_errors = send_errors_.load(kRelaxed);
  return counters;
}

Error closed_socket_error() { return Error{"socket is closed (moved from)"}; }

ReceiveResult closed_socket_receive() {
  return ReceiveResult{ReceiveStatus::kError, 0, Endpoint{}, closed_socket_error().message};
}

}  // namespace ssl::net::detail
