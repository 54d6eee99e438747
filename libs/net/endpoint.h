// Endpoint: an IPv4 address and a UDP port, as a plain value. Parsed from and formatted as
// "127.0.0.1:10300" (dotted-quad literals only: no host names, no IPv6), so config files and logs use one
// spelling. Ports outside [0, 65535] and malformed addresses are reported with the offending text.
//
// League defaults: SSL-Vision 224.5.23.2:10006 (simulated vision 10020), referee 224.5.23.1:10003,
// simulation control 10300, robot control blue 10301 / yellow 10302, grSim legacy commands 20011.
//
//   ssl::Result<ssl::net::Endpoint> vision = ssl::net::Endpoint::parse("224.5.23.2:10006");
//   if (!vision) return vision.error();              // "bad endpoint 'x': ..."
//   vision->is_multicast();                          // true
//   vision->to_string();                             // "224.5.23.2:10006"
#pragma once

#include <compare>
#include <cstdint>
#include <string>
#include <string_view>

#include "libs/common/result.h"

namespace ssl::net {

/// Parses a dotted-quad IPv4 literal ("224.5.23.2") into a host-byte-order address.
/// Error: "bad IPv4 address 'x' (expected a dotted quad like 127.0.0.1)".
Result<std::uint32_t> parse_ipv4(std::string_view text);

/// Formats a host-byte-order IPv4 address as a dotted quad.
std::string format_ipv4(std::uint32_t address);

/// Checks a port number given as an int (e.g. from a config file). Error: "port 70000 is out of range
/// [0, 65535]". Port 0 means "any free port" when binding.
Result<std::uint16_t> check_port(int port);

class Endpoint {
 public:
  /// 0.0.0.0:0.
  constexpr Endpoint() noexcept = default;
  /// @param address IPv4 address in host byte order (e.g. 0x7F000001 for 127.0.0.1).
  constexpr Endpoint(std::uint32_t address, std::uint16_t port) noexcept : address_(address), port_(port) {}

  /// Parses "a.b.c.d:port".
  static Result<Endpoint> parse(std::string_view text);
  /// Validates an address literal and a port number given separately.
  static Result<Endpoint> from_parts(std::string_view address, int port);

  /// IPv4 address in host byte order.
  constexpr std::uint32_t address() const noexcept { return address_; }
  constexpr std::uint16_t port() const noexcept { return port_; }

  /// 224.0.0.0/4.
  constexpr bool is_multicast() const noexcept { return (address_ >> 28) == 0xE; }
  /// 127.0.0.0/8.
  constexpr bool is_loopback() const noexcept { return (address_ >> 24) == 127; }

  /// "a.b.c.d".
  std::string address_string() const { return format_ipv4(address_); }
  /// "a.b.c.d:port".
  std::string to_string() const;

  friend constexpr auto operator<=>(const Endpoint&, const Endpoint&) noexcept = default;

 private:
  std::uint32_t address_ = 0;
  std::uint16_t port_ = 0;
};

}  // namespace ssl::net
