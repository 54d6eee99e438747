// Multicast over real sockets on the loopback interface (127.0.0.1), which works without root and in a
// network namespace without a multicast route. Each test uses its own administratively scoped group
// (239.255.42.x) and the first receiver binds an ephemeral port that the others then share, so parallel
// tests do not see each other's traffic. Every wait has a timeout.
#include "libs/net/multicast.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <future>
#include <string>
#include <thread>
#include <vector>

namespace ssl::net {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

constexpr auto kReceiveTimeout = 5s;
// How long a receiver that must NOT get a datagram listens; loopback delivery takes microseconds.
constexpr auto kSilenceWindow = 200ms;

std::vector<std::uint8_t> bytes_of(std::string_view text) { return {text.begin(), text.end()}; }
std::string text_of(std::span<const std::uint8_t> bytes) { return {bytes.begin(), bytes.end()}; }

template <typename T>
T value_or_throw(Result<T> result) {
  if (!result) throw std::runtime_error(result.error().message);
  return std::move(*result);
}

TEST(MulticastTest, TwoReceiversOnTheSamePortBothGetEachDatagram) {
  MulticastReceiver first = value_or_throw(MulticastReceiver::open("239.255.42.1", 0));
  const Endpoint group = first.group();
  ASSERT_NE(group.port(), 0);
  EXPECT_EQ(group.address_string(), "239.255.42.1");
  MulticastReceiver second = value_or_throw(MulticastReceiver::open(group));  // SO_REUSEPORT
  MulticastSender sender = value_or_throw(MulticastSender::open(group));
  EXPECT_EQ(sender.group(), group);

  ASSERT_TRUE(sender.send(bytes_of("SSL_WrapperPacket")));
  for (MulticastReceiver* receiver : {&first, &second}) {
    std::array<std::uint8_t, 65536> buffer{};
    ReceiveResult result = receiver->receive(buffer, kReceiveTimeout);
    ASSERT_EQ(result.status, ReceiveStatus::kReceived) << result.error;
    EXPECT_EQ(text_of(std::span(buffer).first(result.size)), "SSL_WrapperPacket");
    EXPECT_EQ(result.sender.address_string(), "127.0.0.1");
    EXPECT_EQ(receiver->counters().received, 1u);
  }
  EXPECT_EQ(sender.counters().sent, 1u);
  EXPECT_EQ(sender.counters().bytes_sent, 17u);
}

TEST(MulticastTest, AReceiverOnlyGetsTheGroupItJoined) {
  MulticastReceiver vision = value_or_throw(MulticastReceiver::open("239.255.42.2", 0));
  const int port = vision.group().port();
  MulticastReceiver referee = value_or_throw(MulticastReceiver::open("239.255.42.3", port));
  MulticastSender to_referee = value_or_throw(MulticastSender::open("239.255.42.3", port));

  ASSERT_TRUE(to_referee.send(bytes_of("Referee")));
  std::array<std::uint8_t, 1500> buffer{};
  ReceiveResult got = referee.receive(buffer, kReceiveTimeout);
  ASSERT_EQ(got.status, ReceiveStatus::kReceived) << got.error;
  EXPECT_EQ(text_of(std::span(buffer).first(got.size)), "Referee");
  EXPECT_EQ(vision.receive(buffer, kSilenceWindow).status, ReceiveStatus::kTimeout);
}

TEST(MulticastTest, ReceiveTimesOutInBoundedTime) {
  MulticastReceiver receiver = value_or_throw(MulticastReceiver::open("239.255.42.4", 0));
  std::array<std::uint8_t, 1500> buffer{};
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(receiver.receive(buffer, 50ms).status, ReceiveStatus::kTimeout);
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_GE(elapsed, 50ms);
  EXPECT_LT(elapsed, 5s);
}

TEST(MulticastTest, InterruptWakesABlockedReceiveFromAnotherThread) {
  MulticastReceiver receiver = value_or_throw(MulticastReceiver::open("239.255.42.5", 0));
  std::future<ReceiveResult> blocked = std::async(std::launch::async, [&] {
    std::array<std::uint8_t, 1500> buffer{};
    return receiver.receive(buffer, 60s);
  });
  std::this_thread::sleep_for(20ms);  // not needed for correctness: the interrupt is latched
  receiver.interrupt();
  ASSERT_EQ(blocked.wait_for(10s), std::future_status::ready);
  EXPECT_EQ(blocked.get().status, ReceiveStatus::kInterrupted);
}

TEST(MulticastTest, TruncatedDatagramIsDetected) {
  MulticastReceiver receiver = value_or_throw(MulticastReceiver::open("239.255.42.6", 0));
  MulticastSender sender = value_or_throw(MulticastSender::open(receiver.group()));
  ASSERT_TRUE(sender.send(std::vector<std::uint8_t>(2000, 1)));
  std::array<std::uint8_t, 512> buffer{};
  ReceiveResult result = receiver.receive(buffer, kReceiveTimeout);
  EXPECT_EQ(result.status, ReceiveStatus::kTruncated);
  EXPECT_EQ(result.size, 2000u);
  EXPECT_EQ(receiver.counters().truncated, 1u);
  EXPECT_EQ(receiver.counters().received, 0u);
}

TEST(MulticastTest, MovedReceiverKeepsItsMembership) {
  MulticastReceiver original = value_or_throw(MulticastReceiver::open("239.255.42.7", 0));
  MulticastReceiver moved = std::move(original);
  MulticastSender sender = value_or_throw(MulticastSender::open(moved.group()));
  ASSERT_TRUE(sender.send(bytes_of("hello")));
  std::array<std::uint8_t, 64> buffer{};
  EXPECT_EQ(moved.receive(buffer, kReceiveTimeout).status, ReceiveStatus::kReceived);
}

TEST(MulticastTest, NonMulticastGroupIsRejected) {
  Result<MulticastReceiver> receiver = MulticastReceiver::open("10.0.0.1", 10006);
  ASSERT_FALSE(receiver);
  EXPECT_EQ(receiver.error().message,
            "multicast receiver 10.0.0.1:10006: group address 10.0.0.1 is not a multicast address "
            "(expected 224.0.0.0 to 239.255.255.255)");
  Result<MulticastSender> sender = MulticastSender::open("127.0.0.1", 10006);
  ASSERT_FALSE(sender);
  EXPECT_THAT(sender.error().message, HasSubstr("is not a multicast address"));
}

TEST(MulticastTest, BadPortTtlAndInterfaceAreRejected) {
  Result<MulticastReceiver> bad_port = MulticastReceiver::open("224.5.23.2", 100000);
  ASSERT_FALSE(bad_port);
  EXPECT_EQ(bad_port.error().message, "multicast receiver: port 100000 is out of range [0, 65535]");

  Result<MulticastSender> zero_port = MulticastSender::open("224.5.23.2", 0);
  ASSERT_FALSE(zero_port);
  EXPECT_THAT(zero_port.error().message, HasSubstr("port 0 is not a valid destination port"));

  Result<MulticastSender> bad_ttl = MulticastSender::open("224.5.23.2", 10006, "127.0.0.1", 256);
  ASSERT_FALSE(bad_ttl);
  EXPECT_EQ(bad_ttl.error().message, "multicast sender 224.5.23.2:10006: TTL 256 is out of range [0, 255]");

  Result<MulticastReceiver> bad_interface = MulticastReceiver::open("224.5.23.2", 10006, "eth0");
  ASSERT_FALSE(bad_interface);
  EXPECT_THAT(bad_interface.error().message, HasSubstr("multicast receiver 224.5.23.2:10006 interface: "
                                                       "bad IPv4 address 'eth0'"));
}

TEST(MulticastTest, InterfaceThatIsNotOnThisHostIsReportedWithTheErrnoText) {
  // 192.0.2.1 (TEST-NET-1) is never an address of the test host.
  Result<MulticastSender> sender = MulticastSender::open("239.255.42.8", 40000, "192.0.2.1");
  ASSERT_FALSE(sender);
  EXPECT_THAT(sender.error().message, HasSubstr("set IP_MULTICAST_IF to 192.0.2.1"));
  EXPECT_THAT(sender.error().message, HasSubstr("Cannot assign requested address"));

  Result<MulticastReceiver> receiver = MulticastReceiver::open("239.255.42.8", 0, "192.0.2.1");
  ASSERT_FALSE(receiver);
  EXPECT_THAT(receiver.error().message,
              HasSubstr("join multicast group 239.255.42.8 on interface 192.0.2.1 failed"));
}

TEST(MulticastTest, TheReceiveBufferHoldsBurstsAsLargeAsTheHostAllows) {
  // The kernel grants min(request, net.core.rmem_max) and reports twice that (its bookkeeping).
  int rmem_max = 0;
  if (std::FILE* file = std::fopen("/proc/sys/net/core/rmem_max", "r")) {
    if (std::fscanf(file, "%d", &rmem_max) != 1) rmem_max = 0;
    std::fclose(file);
  }
  if (rmem_max <= 0) GTEST_SKIP() << "net.core.rmem_max is not readable here";
  MulticastReceiver receiver = value_or_throw(MulticastReceiver::open("239.255.42.7", 0));
  const Result<int> bytes = receiver.receive_buffer_bytes();
  ASSERT_TRUE(bytes) << bytes.error().message;
  EXPECT_EQ(*bytes, 2 * std::min(rmem_max, MulticastReceiver::kReceiveBufferRequest));
}

}  // namespace
}  // namespace ssl::net
