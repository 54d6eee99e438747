// Unicast sockets over real loopback sockets. Every socket binds 127.0.0.1:0 (an ephemeral port), so
// parallel tests cannot collide, and every wait has a timeout.
#include "libs/net/udp.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <future>
#include <string>
#include <thread>
#include <vector>

namespace ssl::net {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

// Loopback delivery takes microseconds; this only bounds a failing test.
constexpr auto kReceiveTimeout = 5s;

std::vector<std::uint8_t> bytes_of(std::string_view text) { return {text.begin(), text.end()}; }

std::string text_of(std::span<const std::uint8_t> bytes) { return {bytes.begin(), bytes.end()}; }

UdpSocket open_loopback() {
  Result<UdpSocket> socket = UdpSocket::open("127.0.0.1", 0);
  if (!socket) throw std::runtime_error(socket.error().message);
  return std::move(*socket);
}

TEST(UdpSocketTest, BindingPortZeroReportsTheEphemeralPort) {
  UdpSocket socket = open_loopback();
  EXPECT_EQ(socket.local_endpoint().address_string(), "127.0.0.1");
  EXPECT_NE(socket.local_endpoint().port(), 0);
}

TEST(UdpSocketTest, RequestResponseRepliesToTheSendersEphemeralPort) {
  UdpSocket simulator = open_loopback();
  UdpSocket client = open_loopback();
  std::array<std::uint8_t, 1500> buffer{};

  ASSERT_TRUE(client.send_to(simulator.local_endpoint(), bytes_of("SimulatorCommand")));
  ReceiveResult request = simulator.receive(buffer, kReceiveTimeout);
  ASSERT_EQ(request.status, ReceiveStatus::kReceived) << request.error;
  EXPECT_EQ(text_of(std::span(buffer).first(request.size)), "SimulatorCommand");
  EXPECT_EQ(request.sender, client.local_endpoint());

  // Like grSim and the ER-Force simulator: answer to wherever the request came from.
  ASSERT_TRUE(simulator.send_to(request.sender, bytes_of("SimulatorResponse")));
  ReceiveResult response = client.receive(buffer, kReceiveTimeout);
  ASSERT_EQ(response.status, ReceiveStatus::kReceived) << response.error;
  EXPECT_EQ(text_of(std::span(buffer).first(response.size)), "SimulatorResponse");
  EXPECT_EQ(response.sender, simulator.local_endpoint());

  EXPECT_EQ(client.counters().sent, 1u);
  EXPECT_EQ(client.counters().bytes_sent, 16u);
  EXPECT_EQ(client.counters().received, 1u);
  EXPECT_EQ(simulator.counters().received, 1u);
  EXPECT_EQ(simulator.counters().bytes_received, 16u);
}

TEST(UdpSocketTest, ReceiveTimesOutInBoundedTime) {
  UdpSocket socket = open_loopback();
  std::array<std::uint8_t, 64> buffer{};
  const auto start = std::chrono::steady_clock::now();
  ReceiveResult result = socket.receive(buffer, 50ms);
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_EQ(result.status, ReceiveStatus::kTimeout);
  EXPECT_FALSE(result.ok());
  EXPECT_GE(elapsed, 50ms);
  EXPECT_LT(elapsed, 5s);  // generous: a loaded 2-core machine
}

TEST(UdpSocketTest, ZeroTimeoutOnlyChecks) {
  UdpSocket socket = open_loopback();
  std::array<std::uint8_t, 64> buffer{};
  EXPECT_EQ(socket.receive(buffer, 0ms).status, ReceiveStatus::kTimeout);
  EXPECT_EQ(socket.receive(buffer, -1s).status, ReceiveStatus::kTimeout);
}

TEST(UdpSocketTest, InterruptWakesABlockedReceiveFromAnotherThread) {
  UdpSocket socket = open_loopback();
  std::future<ReceiveResult> blocked = std::async(std::launch::async, [&] {
    std::array<std::uint8_t, 64> buffer{};
    return socket.receive(buffer, 60s);
  });
  // Whether or not the receiver is already inside poll, the latched interrupt must end it.
  std::this_thread::sleep_for(20ms);
  socket.interrupt();
  ASSERT_EQ(blocked.wait_for(10s), std::future_status::ready);
  EXPECT_EQ(blocked.get().status, ReceiveStatus::kInterrupted);

  // Latched: later receives return at once, even with data pending.
  UdpSocket sender = open_loopback();
  ASSERT_TRUE(sender.send_to(socket.local_endpoint(), bytes_of("late")));
  std::array<std::uint8_t, 64> buffer{};
  EXPECT_EQ(socket.receive(buffer, 60s).status, ReceiveStatus::kInterrupted);
}

TEST(UdpSocketTest, OversizedDatagramIsReportedAsTruncatedAndCounted) {
  UdpSocket receiver = open_loopback();
  UdpSocket sender = open_loopback();
  const std::vector<std::uint8_t> big(1000, 0xAB);
  ASSERT_TRUE(sender.send_to(receiver.local_endpoint(), big));
  ASSERT_TRUE(sender.send_to(receiver.local_endpoint(), bytes_of("small")));

  std::array<std::uint8_t, 100> buffer{};
  ReceiveResult truncated = receiver.receive(buffer, kReceiveTimeout);
  EXPECT_EQ(truncated.status, ReceiveStatus::kTruncated);
  EXPECT_FALSE(truncated.ok());
  EXPECT_EQ(truncated.size, 1000u);  // the size on the wire, not what fit
  EXPECT_EQ(truncated.sender, sender.local_endpoint());

  // The next datagram is unaffected.
  ReceiveResult small = receiver.receive(buffer, kReceiveTimeout);
  ASSERT_EQ(small.status, ReceiveStatus::kReceived);
  EXPECT_EQ(text_of(std::span(buffer).first(small.size)), "small");

  const SocketCounters counters = receiver.counters();
  EXPECT_EQ(counters.truncated, 1u);
  EXPECT_EQ(counters.received, 1u);
  EXPECT_EQ(counters.receive_errors, 0u);
}

TEST(UdpSocketTest, EmptyDatagramIsReceived) {
  UdpSocket receiver = open_loopback();
  UdpSocket sender = open_loopback();
  ASSERT_TRUE(sender.send_to(receiver.local_endpoint(), {}));
  std::array<std::uint8_t, 16> buffer{};
  ReceiveResult result = receiver.receive(buffer, kReceiveTimeout);
  EXPECT_EQ(result.status, ReceiveStatus::kReceived);
  EXPECT_EQ(result.size, 0u);
}

TEST(UdpSocketTest, BindFailureNamesAddressPortAndReason) {
  UdpSocket first = open_loopback();
  const int port = first.local_endpoint().port();
  Result<UdpSocket> second = UdpSocket::open("127.0.0.1", port);
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().message,
            "bind 127.0.0.1:" + std::to_string(port) + " failed: Address already in use");

  // 192.0.2.1 (TEST-NET-1) is not an address of this host.
  Result<UdpSocket> foreign = UdpSocket::open("192.0.2.1", 0);
  ASSERT_FALSE(foreign);
  EXPECT_EQ(foreign.error().message, "bind 192.0.2.1:0 failed: Cannot assign requested address");
}

TEST(UdpSocketTest, BadAddressOrPortIsRejectedBeforeOpening) {
  Result<UdpSocket> bad_port = UdpSocket::open("127.0.0.1", 65536);
  ASSERT_FALSE(bad_port);
  EXPECT_EQ(bad_port.error().message, "UDP socket: port 65536 is out of range [0, 65535]");
  Result<UdpSocket> bad_address = UdpSocket::open("127.0.0.300", 0);
  ASSERT_FALSE(bad_address);
  EXPECT_THAT(bad_address.error().message, HasSubstr("bad IPv4 address '127.0.0.300'"));
}

TEST(UdpSocketTest, SendFailureIsReturnedAndCounted) {
  UdpSocket socket = open_loopback();
  const std::vector<std::uint8_t> too_big(70'000, 0);  // larger than any UDP datagram
  Status sent = socket.send_to(Endpoint(0x7F000001u, 9), too_big);
  ASSERT_FALSE(sent);
  EXPECT_EQ(sent.error().message, "send 70000 bytes to 127.0.0.1:9 failed: Message too long");
  EXPECT_EQ(socket.counters().send_errors, 1u);
  EXPECT_EQ(socket.counters().sent, 0u);
}

TEST(UdpSocketTest, MovedSocketKeepsWorkingAndMovedFromReportsClosed) {
  UdpSocket original = open_loopback();
  const Endpoint local = original.local_endpoint();
  UdpSocket moved = std::move(original);
  EXPECT_EQ(moved.local_endpoint(), local);

  UdpSocket sender = open_loopback();
  ASSERT_TRUE(sender.send_to(local, bytes_of("x")));
  std::array<std::uint8_t, 16> buffer{};
  EXPECT_EQ(moved.receive(buffer, kReceiveTimeout).status, ReceiveStatus::kReceived);

  // NOLINTNEXTLINE(bugprone-use-after-move): documented behaviour of a moved-from socket.
  ReceiveResult closed = original.receive(buffer, 1s);
  EXPECT_EQ(closed.status, ReceiveStatus::kError);
  EXPECT_THAT(closed.error, HasSubstr("socket is closed"));
  EXPECT_FALSE(original.send_to(local, bytes_of("x")));
  original.interrupt();  // harmless
}

TEST(ReceiveStatusTest, HasNames) {
  EXPECT_EQ(to_string(ReceiveStatus::kReceived), "received");
  EXPECT_EQ(to_string(ReceiveStatus::kTruncated), "truncated");
  EXPECT_EQ(to_string(ReceiveStatus::kTimeout), "timeout");
  EXPECT_EQ(to_string(ReceiveStatus::kInterrupted), "interrupted");
  EXPECT_EQ(to_string(ReceiveStatus::kError), "error");
}

}  // namespace
}  // namespace ssl::net
