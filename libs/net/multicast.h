// UDP multicast for the league's broadcast streams: SSL-Vision 224.5.23.2:10006 (simulators: 10020),
// tracked vision 224.5.23.2:10010, referee 224.5.23.1:10003.
//
// The interface address picks the network card the group is sent on / joined on. It defaults to
// 127.0.0.1 so that tests and simulation never leave the machine and work in a fresh network namespace
// (which has no multicast route: without it, sending fails with "Network is unreachable" and joining
// with "No such device"). In a real match set it, from config, to the address of the NIC on the vision
// network. Receive/interrupt/counter semantics are those of udp.h.
//
// Receivers set SO_REUSEADDR + SO_REUSEPORT (several processes on one host may listen to the same
// stream; each gets every datagram), bind 0.0.0.0:port and join the group on the interface. They also
// clear IP_MULTICAST_ALL, so a receiver only gets the groups IT joined, not every group some other
// socket on the host joined on the same port (Linux's surprising default).
//
//   auto vision = ssl::net::MulticastReceiver::open("224.5.23.2", 10006, config.vision_interface);
//   if (!vision) return vision.error();   // e.g. "join multicast group 224.5.23.2 on interface ..."
//   std::array<std::uint8_t, 65536> buffer;
//   while (running) {
//     ssl::net::ReceiveResult r = vision->receive(buffer, std::chrono::milliseconds(100));
//     if (r.ok()) handle(std::span(buffer).first(r.size));
//   }
//
//   auto out = ssl::net::MulticastSender::open("224.5.23.2", 10020);   // 127.0.0.1, TTL 1
//   ssl::Status sent = out->send(bytes);
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>

#include "libs/common/result.h"
#include "libs/net/endpoint.h"
#include "libs/net/udp.h"

namespace ssl::net {

/// Loopback: the default interface, keeps multicast on this host.
inline constexpr std::string_view kLoopbackInterface = "127.0.0.1";

/// Sends datagrams to one multicast group:port.
class MulticastSender {
 public:
  /// @param group multicast group and port (224.0.0.0/4; port 1-65535).
  /// @param interface_address local IPv4 address of the outgoing interface (IP_MULTICAST_IF).
  /// @param ttl hop limit, 0-255 (1 = the local network only).
  /// Errors name the group, interface and errno text; a non-multicast group or bad TTL is rejected.
  static Result<MulticastSender> open(const Endpoint& group,
                                      std::string_view interface_address = kLoopbackInterface, int ttl = 1);
  static Result<MulticastSender> open(std::string_view group, int port,
                                      std::string_view interface_address = kLoopbackInterface, int ttl = 1);

  MulticastSender(MulticastSender&& other) noexcept;
  MulticastSender& operator=(MulticastSender&& other) noexcept;
  MulticastSender(const MulticastSender&) = delete;
  MulticastSender& operator=(const MulticastSender&) = delete;
  ~MulticastSender();

  /// Sends one datagram to the group without blocking. Error: "send to 224.5.23.2:10006 failed: <errno
  /// text>" (also when the socket's send buffer is full: the datagram is dropped).
  Status send(std::span<const std::uint8_t> bytes);

  Endpoint group() const noexcept { return group_; }
  SocketCounters counters() const noexcept;

 private:
  MulticastSender(std::unique_ptr<detail::SocketCore> core, Endpoint group) noexcept;

  std::unique_ptr<detail::SocketCore> core_;
  Endpoint group_;
};

/// Receives the datagrams sent to one multicast group:port.
class MulticastReceiver {
 public:
  /// @param group multicast group and port (224.0.0.0/4; port 0 = an ephemeral port, see port()).
  /// @param interface_address local IPv4 address of the interface to join on (imr_interface).
  static Result<MulticastReceiver> open(const Endpoint& group,
                                        std::string_view interface_address = kLoopbackInterface);
  static Result<MulticastReceiver> open(std::string_view group, int port,
                                        std::string_view interface_address = kLoopbackInterface);

  MulticastReceiver(MulticastReceiver&& other) noexcept;
  MulticastReceiver& operator=(MulticastReceiver&& other) noexcept;
  MulticastReceiver(const MulticastReceiver&) = delete;
  MulticastReceiver& operator=(const MulticastReceiver&) = delete;
  ~MulticastReceiver();

  /// Waits at most `timeout` (<= 0: just check) for one datagram; see udp.h.
  ReceiveResult receive(std::span<std::uint8_t> buffer, std::chrono::nanoseconds timeout);

  /// Wakes a blocked receive() and makes all later ones return kInterrupted. Thread- and signal-safe.
  void interrupt() noexcept;

  /// The group and the port actually bound.
  Endpoint group() const noexcept { return group_; }
  SocketCounters counters() const noexcept;
  /// The kernel's receive buffer, bytes (it reports twice what it may use for data).
  Result<int> receive_buffer_bytes() const;

  /// What open() asks for: room for bursts while the process waits for a CPU. Four cameras at 75 Hz and the
  /// referee are ~300 datagrams/s; the usual default (~200 KB, ~170 small datagrams) overflows after half a
  /// second. The kernel caps it at net.core.rmem_max.
  static constexpr int kReceiveBufferRequest = 4 << 20;

 private:
  MulticastReceiver(std::unique_ptr<detail::SocketCore> core, Endpoint group) noexcept;

  std::unique_ptr<detail::SocketCore> core_;
  Endpoint group_;
};

}  // namespace ssl::net
