// The decode + convert + core path with hostile input: seeded random buffers, every truncation of a valid
// packet and random corruptions never crash, are counted as malformed (or, when they happen to be a valid
// Referee message, handled as one), and the gateway keeps working afterwards.
#include "services/referee_gateway/adapter/ingest.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "libs/league/decode.h"
#include "services/referee_gateway/testing/referee_packets.h"

namespace ssl::referee {
namespace {

using namespace std::chrono_literals;
using testing::encode;
using testing::full_referee_packet;
using testing::referee_packet;

const time::Timestamp kWall = time::Timestamp::from_seconds(1.7e9);
const time::Timestamp kStart = time::Timestamp::from_seconds(100.0);

std::span<const std::uint8_t> bytes_of(const std::string& text) { return league::byte_span(text); }

/// Every datagram is either malformed or a decoded packet; the two counters add up.
void expect_accounted(const RefereeIngest& ingest, std::uint64_t datagrams) {
  EXPECT_EQ(ingest.malformed() + ingest.core().counters().packets, datagrams);
}

TEST(RefereeGatewayIngest, AValidPacketIsDecodedConvertedAndPublished) {
  RefereeIngest ingest({});
  const IngestResult result = ingest.handle(bytes_of(encode(full_referee_packet())), kWall, kStart);
  ASSERT_FALSE(result.malformed);
  ASSERT_TRUE(result.output.state);
  EXPECT_EQ(result.output.state->command, Command::kBallPlacementBlue);
  EXPECT_EQ(result.output.state->receive_wall, kWall);
  ASSERT_TRUE(result.output.state->designated_position);
  EXPECT_DOUBLE_EQ(result.output.state->designated_position->x(), -1.2505);
  EXPECT_EQ(result.output.events.size(), 2u);
  EXPECT_EQ(ingest.malformed(), 0u);
}

TEST(RefereeGatewayIngest, ThousandsOfSeededRandomBuffersNeverCrashAndAreCounted) {
  RefereeIngest ingest({});
  std::mt19937 random(20240601);
  std::uniform_int_distribution<int> length(0, 600);
  std::uniform_int_distribution<int> byte(0, 255);
  constexpr int kBuffers = 5000;
  std::vector<std::uint8_t> buffer;
  for (int i = 0; i < kBuffers; ++i) {
    buffer.resize(static_cast<std::size_t>(length(random)));
    for (auto& b : buffer) b = static_cast<std::uint8_t>(byte(random));
    const IngestResult result = ingest.handle(buffer, kWall, kStart + i * 1ms);
    if (result.malformed) {
      EXPECT_FALSE(result.output.state);
      EXPECT_TRUE(result.output.events.empty());
      EXPECT_FALSE(result.malformed->message.empty());
    }
  }
  expect_accounted(ingest, kBuffers);
  // Random bytes almost never carry all eight required Referee fields.
  EXPECT_GT(ingest.malformed(), static_cast<std::uint64_t>(kBuffers * 0.99));
}

TEST(RefereeGatewayIngest, EveryTruncationOfAValidPacketIsSafeAndCounted) {
  const std::string whole = encode(full_referee_packet());
  ::Referee required_only = referee_packet(::Referee::STOP, 1);
  const std::size_t shortest_valid = encode(required_only).size();
  RefereeIngest ingest({});
  std::uint64_t malformed_before_complete = 0;
  for (std::size_t size = 0; size < whole.size(); ++size) {
    const std::string prefix = whole.substr(0, size);
    const IngestResult result = ingest.handle(bytes_of(prefix), kWall, kStart);
    if (size < shortest_valid / 2) {
      // Far too short to hold the required fields.
      EXPECT_TRUE(result.malformed) << size << " bytes";
      if (result.malformed) ++malformed_before_complete;
    }
  }
  expect_accounted(ingest, whole.size());
  EXPECT_GT(malformed_before_complete, 0u);
  EXPECT_GT(ingest.malformed(), whole.size() / 2);
  // After all that, a whole packet still goes through.
  const IngestResult result = ingest.handle(bytes_of(whole), kWall, kStart + 1s);
  EXPECT_FALSE(result.malformed);
}

TEST(RefereeGatewayIngest, RandomCorruptionsOfValidPacketsNeverCrash) {
  const std::string whole = encode(full_referee_packet());
  RefereeIngest ingest({});
  std::mt19937 random(7);
  std::uniform_int_distribution<std::size_t> position(0, whole.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> flips(1, 8);
  constexpr int kPackets = 3000;
  for (int i = 0; i < kPackets; ++i) {
    std::string corrupted = whole;
    for (int f = flips(random); f > 0; --f) corrupted[position(random)] = static_cast<char>(byte(random));
    (void)ingest.handle(bytes_of(corrupted), kWall, kStart + i * 1ms);
  }
  expect_accounted(ingest, kPackets);
  EXPECT_GT(ingest.malformed(), 0u);
}

TEST(RefereeGatewayIngest, OversizedAndEmptyDatagramsAreMalformed) {
  RefereeIngest ingest({});
  std::vector<std::uint8_t> huge(league::kMaxDatagramBytes + 1, 0x08);
  EXPECT_TRUE(ingest.handle(huge, kWall, kStart).malformed);
  EXPECT_TRUE(ingest.handle({}, kWall, kStart).malformed);
  ingest.count_truncated();
  EXPECT_EQ(ingest.malformed(), 3u);
}

TEST(RefereeGatewayIngest, MissingRequiredFieldsAreNamed) {
  ::Referee packet = referee_packet(::Referee::STOP, 1);
  packet.mutable_blue()->clear_goalkeeper();
  const std::string bytes = packet.SerializePartialAsString();
  RefereeIngest ingest({});
  const IngestResult result = ingest.handle(bytes_of(bytes), kWall, kStart);
  ASSERT_TRUE(result.malformed);
  EXPECT_NE(result.malformed->message.find("blue.goalkeeper"), std::string::npos)
      << result.malformed->message;
}

TEST(RefereeGatewayIngest, GarbageBetweenValidPacketsDoesNotDisturbTheState) {
  RefereeIngest ingest({.heartbeat_period = 1s});
  ASSERT_TRUE(
      ingest.handle(bytes_of(encode(referee_packet(::Referee::STOP, 1))), kWall, kStart).output.state);
  const std::string garbage = "\x0a\xff\xff\xff\xff\x0f garbage";
  for (int i = 0; i < 10; ++i)
    EXPECT_TRUE(ingest.handle(bytes_of(garbage), kWall, kStart + i * 10ms).malformed);
  const IngestResult next =
      ingest.handle(bytes_of(encode(referee_packet(::Referee::FORCE_START, 2))), kWall, kStart + 200ms);
  ASSERT_TRUE(next.output.state);
  EXPECT_EQ(next.output.state->command, Command::kForceStart);
  EXPECT_FALSE(next.output.counter_jump);
  EXPECT_EQ(ingest.malformed(), 10u);
}

TEST(RefereeGatewayIngest, BuiltinSourceIsStampedOnTheState) {
  RefereeIngest ingest({}, RefereeSource::kBuiltin);
  const IngestResult result =
      ingest.handle(bytes_of(encode(referee_packet(::Referee::HALT, 1))), kWall, kStart);
  ASSERT_TRUE(result.output.state);
  EXPECT_EQ(result.output.state->source, RefereeSource::kBuiltin);
}

}  // namespace
}  // namespace ssl::referee
