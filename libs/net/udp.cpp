#include "libs/net/udp.h"

#include "libs/net/socket_core.h"

namespace ssl::net {

std::string_view to_string(ReceiveStatus status) {
  switch (status) {
    case ReceiveStatus::kReceived:
      return "received";
    case ReceiveStatus::kTruncated:
      return "truncated";
    case ReceiveStatus::kTimeout:
      return "timeout";
    case ReceiveStatus::kInterrupted:
      return "interrupted";
    case ReceiveStatus::kError:
      return "error";
  }
  return "unknown";
}

Result<UdpSocket> UdpSocket::open(const Endpoint& local) {
  Result<std::unique_ptr<detail::SocketCore>> core = detail::SocketCore::create();
  if (!core) return core.error();
  if (Status bound = (*core)->bind(local); !bound) return bound.error();
  Result<Endpoint> bound_to = (*core)->local_endpoint();
  if (!bound_to) return bound_to.error();
  return UdpSocket(std::move(*core), *bound_to);
}

Result<UdpSocket> UdpSocket::open(std::string_view address, int port) {
  Result<Endpoint> local = Endpoint::from_parts(address, port);
  if (!local) return Error{"UDP socket: " + local.error().message};
  return open(*local);
}

UdpSocket::UdpSocket(std::unique_ptr<detail::SocketCore> core, Endpoint local) noexcept
    : core_(std::move(core)), local_(local) {}

UdpSocket::UdpSocket(UdpSocket&& other) noexcept = default;
UdpSocket& UdpSocket::operator=(UdpSocket&& other) noexcept = default;
UdpSocket::~UdpSocket() = default;

Status UdpSocket::send_to(const Endpoint& destination, std::span<const std::uint8_t> bytes) {
  if (!core_) return detail::closed_socket_error();
  return core_->send_to(destination, bytes);
}

ReceiveResult UdpSocket::receive(std::span<std::uint8_t> buffer, std::chrono::nanoseconds timeout) {
  if (!core_) return detail::closed_socket_receive();
  return core_->receive(buffer, timeout);
}

void UdpSocket::interrupt() noexcept {
  if (core_) core_->interrupt();
}

SocketCounters UdpSocket::counters() const noexcept { return core_ ? core_->counters() : SocketCounters{}; }

}  // namespace ssl::net
