#include "libs/net/endpoint.h"

#include <arpa/inet.h>

#include <charconv>

namespace ssl::net {

Result<std::uint32_t> parse_ipv4(std::string_view text) {
  // inet_pton(AF_INET) accepts exactly four decimal octets, unlike inet_aton ("1", "0x7f.1").
  const std::string terminated(text);
  in_addr parsed{};
  if (text.empty() || inet_pton(AF_INET, terminated.c_str(), &parsed) != 1) {
    return Error{"bad IPv4 address '" + terminated + "' (expected a dotted quad like 127.0.0.1)"};
  }
  return ntohl(parsed.s_addr);
}

std::string format_ipv4(std::uint32_t address) {
  return std::to_string(address >> 24) + "." + std::to_string((address >> 16) & 0xFF) + "." +
         std::to_string((address >> 8) & 0xFF) + "." + std::to_string(address & 0xFF);
}

Result<std::uint16_t> check_port(int port) {
  if (port < 0 || port > 65535) {
    return Error{"port " + std::to_string(port) + " is out of range [0, 65535]"};
  }
  return static_cast<std::uint16_t>(port);
}

Result<Endpoint> Endpoint::parse(std::string_view text) {
  const std::string quoted = "'" + std::string(text) + "'";
  const std::size_t colon = text.rfind(':');
  if (colon == std::string_view::npos) {
    return Error{"bad endpoint " + quoted + " (expected address:port like 127.0.0.1:10300)"};
  }
  Result<std::uint32_t> address = parse_ipv4(text.substr(0, colon));
  if (!address) return Error{"bad endpoint " + quoted + ": " + address.error().message};

  const std::string_view port_text = text.substr(colon + 1);
  long port = -1;
  const auto [end, ec] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (port_text.empty() || ec == std::errc::invalid_argument || end != port_text.data() + port_text.size()) {
    return Error{"bad endpoint " + quoted + ": port '" + std::string(port_text) + "' is not a number"};
  }
  if (ec == std::errc::result_out_of_range || port < 0 || port > 65535) {
    return Error{"bad endpoint " + quoted + ": port " + std::string(port_text) +
                 " is out of range [0, 65535]"};
  }
  return Endpoint(*address, static_cast<std::uint16_t>(port));
}

Result<Endpoint> Endpoint::from_parts(std::string_view address, int port) {
  Result<std::uint32_t> parsed = parse_ipv4(address);
  if (!parsed) return parsed.error();
  Result<std::uint16_t> checked = check_port(port);
  if (!checked) return checked.error();
  return Endpoint(*parsed, *checked);
}

std::string Endpoint::to_string() const { return address_string() + ":" + std::to_string(port_); }

}  // namespace ssl::net
