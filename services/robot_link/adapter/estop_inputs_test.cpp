// The serial e-stop byte protocol and device handling (through a pseudo-terminal standing in for the
// button box): readings, repeated states, garbage, and fail-safe engagement when the device goes away.
#include "services/robot_link/adapter/estop_inputs.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <string_view>
#include <thread>

namespace ssl::robot_link {
namespace {

using std::chrono::milliseconds;

std::span<const std::uint8_t> bytes_of(std::string_view text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

TEST(RobotLinkEstopDeviceTest, ByteParserKeepsTheNewestStateAndCountsGarbage) {
  EstopByteParser parser;
  EXPECT_EQ(parser.feed(bytes_of("1\n")), true);
  EXPECT_EQ(parser.feed(bytes_of("0\r\n")), false);
  EXPECT_EQ(parser.feed(bytes_of("1 0 1")), true);
  EXPECT_EQ(parser.feed(bytes_of("\n\n")), std::nullopt);
  EXPECT_EQ(parser.feed(bytes_of("x0?")), false);
  EXPECT_EQ(parser.garbage_bytes(), 2u);
}

/// Polls until an event arrives (bounded), advancing a fake monotonic time.
std::optional<EstopEvent> poll_event(SerialEstop& device, time::Timestamp now) {
  for (int i = 0; i < 100; ++i) {
    if (auto event = device.poll(now)) return event;
    std::this_thread::sleep_for(milliseconds(5));
  }
  return std::nullopt;
}

TEST(RobotLinkEstopDeviceTest, SerialDeviceEngagesReleasesAndEngagesWhenItGoesAway) {
  int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  SerialEstop device(::ptsname(master), 9600);
  const time::Timestamp now = time::Timestamp::from_milliseconds(1000);
  EXPECT_FALSE(device.poll(now)) << "nothing said yet";
  EXPECT_TRUE(device.connected());

  ASSERT_EQ(::write(master, "1\n", 2), 2);
  auto engaged = poll_event(device, now);
  ASSERT_TRUE(engaged);
  EXPECT_TRUE(engaged->engaged);

  ASSERT_EQ(::write(master, "1\n1\n", 4), 4);  // a device repeating its state is not a new event
  std::this_thread::sleep_for(milliseconds(50));
  EXPECT_FALSE(device.poll(now));

  ASSERT_EQ(::write(master, "0\n", 2), 2);
  auto released = poll_event(device, now);
  ASSERT_TRUE(released);
  EXPECT_FALSE(released->engaged);

  ::close(master);  // unplugged
  auto lost = poll_event(device, now);
  ASSERT_TRUE(lost);
  EXPECT_TRUE(lost->engaged) << "fail-safe";
  EXPECT_NE(lost->reason.find("lost"), std::string::npos);
  EXPECT_FALSE(device.connected());
  EXPECT_EQ(device.device_losses(), 1u);
}

TEST(RobotLinkEstopDeviceTest, MissingDeviceEngagesOnceAndIsRetriedEverySecond) {
  SerialEstop device("/dev/does-not-exist-estop", 9600);
  const time::Timestamp start = time::Timestamp::from_milliseconds(1000);
  auto first = device.poll(start);
  ASSERT_TRUE(first);
  EXPECT_TRUE(first->engaged);
  EXPECT_FALSE(device.poll(start + milliseconds(500)));
  EXPECT_EQ(device.device_losses(), 1u) << "not retried before a second passed";
  EXPECT_FALSE(device.poll(start + milliseconds(1000))) << "retried, still missing, reported once";
  EXPECT_EQ(device.device_losses(), 2u);
}

TEST(RobotLinkEstopDeviceTest, KeyboardIsInactiveWithoutATerminal) {
  // ctest runs tests with stdin not a terminal (or redirected); the keyboard e-stop then stays off.
  if (::isatty(STDIN_FILENO) != 0) GTEST_SKIP() << "stdin is a terminal";
  KeyboardEstop keyboard;
  EXPECT_FALSE(keyboard.active());
  EXPECT_EQ(keyboard.poll(), 0);
}

}  // namespace
}  // namespace ssl::robot_link
