// Unicast UDP for the league's request/response streams (simulation control :10300, robot control
// :10301/:10302, grSim commands :20011), plus the receive types shared with multicast.h.
//
// Contract of every socket in ssl::net:
//   * Opening is the only step that can fail for setup reasons; it returns Result<Socket> with a message
//     naming the address:port and the errno text. Nothing here throws.
//   * receive() never blocks longer than its timeout (ppoll), and never forever; interrupt() from any
//     thread wakes a blocked receive() at once and makes every later receive() return kInterrupted
//     (permanent: it is meant for shutdown; it is async-signal-safe).
//   * Datagrams larger than the buffer are detected (MSG_TRUNC) and reported as kTruncated, never handed
//     out as if whole. A 65536-byte buffer never truncates a UDP datagram.
//   * Sockets are RAII (closed in the destructor), movable, not copyable. One thread receives at a time;
//     send, interrupt() and counters() may be called from other threads. A moved-from socket reports
//     errors ("socket is closed") instead of crashing.
//
// The simulator answers to the sender's address and port, so a client binds an ephemeral port and
// receives the reply on the same socket:
//
//   ssl::Result<ssl::net::UdpSocket> socket = ssl::net::UdpSocket::open("127.0.0.1", 0);
//   if (!socket) return socket.error();
//   ssl::Status sent = socket->send_to(simulator_endpoint, request_bytes);
//   std::array<std::uint8_t, 65536> buffer;
//   ssl::net::ReceiveResult reply = socket->receive(buffer, std::chrono::milliseconds(100));
//   if (reply.ok()) decode(std::span(buffer).first(reply.size));
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "libs/common/result.h"
#include "libs/net/endpoint.h"

namespace ssl::net {

namespace detail {
class SocketCore;
}

/// Per-socket traffic counters, a snapshot copied out of the socket (safe to read from another thread
/// while the socket is in use). Services publish them on their health topic.
struct SocketCounters {
  std::uint64_t received = 0;        ///< datagrams delivered whole (kReceived)
  std::uint64_t bytes_received = 0;  ///< payload bytes of those datagrams
  std::uint64_t truncated = 0;       ///< datagrams larger than the receive buffer (kTruncated)
  std::uint64_t receive_errors = 0;  ///< failed poll/recvfrom calls (kError)
  std::uint64_t sent = 0;            ///< datagrams sent
  std::uint64_t bytes_sent = 0;
  std::uint64_t send_errors = 0;  ///< failed sendto calls
};

enum class ReceiveStatus {
  kReceived,     ///< a whole datagram is in the buffer: `size` bytes from `sender`
  kTruncated,    ///< the datagram (`size` bytes on the wire) did not fit; the buffer holds only its start
  kTimeout,      ///< nothing arrived within the timeout
  kInterrupted,  ///< interrupt() was called
  kError,        ///< the socket failed; `error` says why
};

/// "received", "truncated", ...
std::string_view to_string(ReceiveStatus status);

struct ReceiveResult {
  ReceiveStatus status = ReceiveStatus::kTimeout;
  /// kReceived: bytes written to the buffer. kTruncated: the datagram's full size (> buffer size).
  std::size_t size = 0;
  /// kReceived / kTruncated: where the datagram came from (answer here for request/response).
  Endpoint sender;
  /// kError: what failed, with errno text.
  std::string error;

  bool ok() const noexcept { return status == ReceiveStatus::kReceived; }
};

/// A UDP socket bound to a local address and port, for unicast request/response.
class UdpSocket {
 public:
  /// Binds to `local` (address 0.0.0.0 = all interfaces; port 0 = a free ephemeral port).
  /// Error: "bind 127.0.0.1:10300 failed: Address already in use".
  static Result<UdpSocket> open(const Endpoint& local);
  /// Same, validating the address literal and the port range first.
  static Result<UdpSocket> open(std::string_view address, int port);

  UdpSocket(UdpSocket&& other) noexcept;
  UdpSocket& operator=(UdpSocket&& other) noexcept;
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;
  ~UdpSocket();

  /// The address and port actually bound (the chosen port when opened with port 0).
  Endpoint local_endpoint() const noexcept { return local_; }

  /// Sends one datagram without blocking. Error: "send to 127.0.0.1:10300 failed: <errno text>" (also when
  /// the socket's send buffer is full: the datagram is dropped).
  Status send_to(const Endpoint& destination, std::span<const std::uint8_t> bytes);

  /// Waits at most `timeout` (<= 0: just check) for one datagram and copies it into `buffer`.
  ReceiveResult receive(std::span<std::uint8_t> buffer, std::chrono::nanoseconds timeout);

  /// Wakes a blocked receive() and makes all later ones return kInterrupted. Thread- and signal-safe.
  void interrupt() noexcept;

  SocketCounters counters() const noexcept;

 private:
  UdpSocket(std::unique_ptr<detail::SocketCore> core, Endpoint local) noexcept;

  std::unique_ptr<detail::SocketCore> core_;
  Endpoint local_;
};

}  // namespace ssl::net
