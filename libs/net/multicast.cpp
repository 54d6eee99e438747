#include "libs/net/multicast.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include "libs/net/socket_core.h"

namespace ssl::net {
namespace {

Status check_group(const Endpoint& group) {
  if (!group.is_multicast()) {
    return Error{"group address " + group.address_string() +
                 " is not a multicast address (expected 224.0.0.0 to 239.255.255.255)"};
  }
  return Status::success();
}

in_addr to_in_addr(std::uint32_t address) {
  in_addr result{};
  result.s_addr = htonl(address);
  return result;
}

// Prefixes every error of open() with what was being opened, e.g. "multicast receiver 224.5.23.2:10006: ".
Error with_context(const std::string& context, const Error& error) {
  return Error{context + ": " + error.message};
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------
// MulticastSender

Result<MulticastSender> MulticastSender::open(const Endpoint& group, std::string_view interface_address,
                                              int ttl) {
  const std::string context = "multicast sender " + group.to_string();
  if (Status ok = check_group(group); !ok) return with_context(context, ok.error());
  if (group.port() == 0) return Error{context + ": port 0 is not a valid destination port"};
  if (ttl < 0 || ttl > 255)
    return Error{context + ": TTL " + std::to_string(ttl) + " is out of range [0, 255]"};
  Result<std::uint32_t> interface = parse_ipv4(interface_address);
  if (!interface) return with_context(context + " interface", interface.error());

  Result<std::unique_ptr<detail::SocketCore>> core = detail::SocketCore::create();
  if (!core) return with_context(context, core.error());
  const in_addr outgoing = to_in_addr(*interface);
  if (Status ok = (*core)->set_option(
          IPPROTO_IP, IP_MULTICAST_IF, &outgoing, sizeof outgoing,
          "set IP_MULTICAST_IF to " + format_ipv4(*interface) + " (must be an address of this host)");
      !ok) {
    return with_context(context, ok.error());
  }
  if (Status ok = (*core)->set_int_option(IPPROTO_IP, IP_MULTICAST_LOOP, 1, "set IP_MULTICAST_LOOP"); !ok) {
    return with_context(context, ok.error());
  }
  if (Status ok = (*core)->set_int_option(IPPROTO_IP, IP_MULTICAST_TTL, ttl, "set IP_MULTICAST_TTL"); !ok) {
    return with_context(context, ok.error());
  }
  return MulticastSender(std::move(*core), group);
}

Result<MulticastSender> MulticastSender::open(std::string_view group, int port,
                                              std::string_view interface_address, int ttl) {
  Result<Endpoint> endpoint = Endpoint::from_parts(group, port);
  if (!endpoint) return Error{"multicast sender: " + endpoint.error().message};
  return open(*endpoint, interface_address, ttl);
}

MulticastSender::MulticastSender(std::unique_ptr<detail::SocketCore> core, Endpoint group) noexcept
    : core_(std::move(core)), group_(group) {}

MulticastSender::MulticastSender(MulticastSender&& other) noexcept = default;
MulticastSender& MulticastSender::operator=(MulticastSender&& other) noexcept = default;
MulticastSender::~MulticastSender() = default;

Status MulticastSender::send(std::span<const std::uint8_t> bytes) {
  if (!core_) return detail::closed_socket_error();
  return core_->send_to(group_, bytes);
}

SocketCounters MulticastSender::counters() const noexcept {
  return core_ ? core_->counters() : SocketCounters{};
}

// ---------------------------------------------------------------------------------------------------------
// MulticastReceiver

Result<MulticastReceiver> MulticastReceiver::open(const Endpoint& group, std::string_view interface_address) {
  const std::string context = "multicast receiver " + group.to_string();
  if (Status ok = check_group(group); !ok) return with_context(context, ok.error());
  Result<std::uint32_t> interface = parse_ipv4(interface_address);
  if (!interface) return with_context(context + " interface", interface.error());

  Result<std::unique_ptr<detail::SocketCore>> core = detail::SocketCore::create();
  if (!core) return with_context(context, core.error());
  detail::SocketCore& socket = **core;
  if (Status ok = socket.set_int_option(SOL_SOCKET, SO_REUSEADDR, 1, "set SO_REUSEADDR"); !ok) {
    return with_context(context, ok.error());
  }
  if (Status ok = socket.set_int_option(SOL_SOCKET, SO_REUSEPORT, 1, "set SO_REUSEPORT"); !ok) {
    return with_context(context, ok.error());
  }
  if (Status ok = socket.set_int_option(SOL_SOCKET, SO_RCVBUF, kReceiveBufferRequest, "set SO_RCVBUF"); !ok) {
    return with_context(context, ok.error());
  }
  // Only the groups this socket joined, not every group joined on this port by any socket of the host.
  if (Status ok = socket.set_int_option(IPPROTO_IP, IP_MULTICAST_ALL, 0, "clear IP_MULTICAST_ALL"); !ok) {
    return with_context(context, ok.error());
  }
  if (Status ok = socket.bind(Endpoint(INADDR_ANY, group.port())); !ok)
    return with_context(context, ok.error());

  ip_mreq membership{};
  membership.imr_multiaddr = to_in_addr(group.address());
  membership.imr_interface = to_in_addr(*interface);
  if (Status ok = socket.set_option(
          IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof membership,
          "join multicast group " + group.address_string() + " on interface " + format_ipv4(*interface));
      !ok) {
    return with_context(context, ok.error());
  }
  Result<Endpoint> bound = socket.local_endpoint();
  if (!bound) return with_context(context, bound.error());
  return MulticastReceiver(std::move(*core), Endpoint(group.address(), bound->port()));
}

Result<MulticastReceiver> MulticastReceiver::open(std::string_view group, int port,
                                                  std::string_view interface_address) {
  Result<Endpoint> endpoint = Endpoint::from_parts(group, port);
  if (!endpoint) return Error{"multicast receiver: " + endpoint.error().message};
  return open(*endpoint, interface_address);
}

MulticastReceiver::MulticastReceiver(std::unique_ptr<detail::SocketCore> core, Endpoint group) noexcept
    : core_(std::move(core)), group_(group) {}

Result<int> MulticastReceiver::receive_buffer_bytes() const {
  return core_->int_option(SOL_SOCKET, SO_RCVBUF, "read SO_RCVBUF");
}

MulticastReceiver::MulticastReceiver(MulticastReceiver&& other) noexcept = default;
MulticastReceiver& MulticastReceiver::operator=(MulticastReceiver&& other) noexcept = default;
MulticastReceiver::~MulticastReceiver() = default;

ReceiveResult MulticastReceiver::receive(std::span<std::uint8_t> buffer, std::chrono::nanoseconds timeout) {
  if (!core_) return detail::closed_socket_receive();
  return core_->receive(buffer, timeout);
}

void MulticastReceiver::interrupt() noexcept {
  if (core_) core_->interrupt();
}

SocketCounters MulticastReceiver::counters() const noexcept {
  return core_ ? core_->counters() : SocketCounters{};
}

}  // namespace ssl::net
