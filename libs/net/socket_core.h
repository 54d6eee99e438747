// Internal to ssl::net (not part of the public API): one UDP file descriptor plus an eventfd that
// interrupts receives, and the atomic counters behind SocketCounters. The public socket classes own a
// SocketCore through a unique_ptr, which makes them cheap to move while the atomics stay in place.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "libs/common/result.h"
#include "libs/net/endpoint.h"
#include "libs/net/udp.h"

namespace ssl::net::detail {

/// "<what> failed: <strerror(errno)>", read from errno at the call.
std::string errno_message(std::string_view what);

class SocketCore {
 public:
  /// A blocking IPv4 UDP socket and a non-blocking eventfd, both close-on-exec.
  static Result<std::unique_ptr<SocketCore>> create();

  SocketCore(const SocketCore&) = delete;
  SocketCore& operator=(const SocketCore&) = delete;
  ~SocketCore();

  /// setsockopt with an int value; `what` names the option in the error ("set SO_REUSEPORT").
  Status set_int_option(int level, int name, int value, std::string_view what);
  Result<int> int_option(int level, int name, std::string_view what) const;
  /// setsockopt with any value type.
  Status set_option(int level, int name, const void* value, unsigned length, std::string_view what);

  Status bind(const Endpoint& local);
  Result<Endpoint> local_endpoint() const;

  Status send_to(const Endpoint& destination, std::span<const std::uint8_t> bytes);
  ReceiveResult receive(std::span<std::uint8_t> buffer, std::chrono::nanoseconds timeout);
  void interrupt() noexcept;
  SocketCounters counters() const noexcept;

 private:
  SocketCore(int fd, int wake_fd) noexcept : fd_(fd), wake_fd_(wake_fd) {}

  ReceiveResult fail_receive(std::string message);

  const int fd_;
  const int wake_fd_;

  std::atomic<std::uint64_t> received_{0};
  std::atomic<std::uint64_t> bytes_received_{0};
  std::atomic<std::uint64_t> truncated_{0};
  std::atomic<std::uint64_t> receive_errors_{0};
  std::atomic<std::uint64_t> sent_{0};
  std::atomic<std::uint64_t> bytes_sent_{0};
  std::atomic<std::uint64_t> send_errors_{0};
};

/// Result of an operation on a moved-from socket.
Error closed_socket_error();
ReceiveResult closed_socket_receive();

}  // namespace ssl::net::detail
