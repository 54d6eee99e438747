// The adapter's decode + core path under hostile input: thousands of seeded random buffers, every
// truncation of valid packets, bit flips, oversized datagrams and NaN-carrying packets never crash it; each
// is either counted as malformed or handled as a valid packet, and valid traffic keeps flowing. Also the
// malformed-packet log throttle.
#include "services/vision_gateway/adapter/pipeline.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "libs/league/decode.h"
#include "services/vision_gateway/testing/builders.h"

namespace ssl::vision_gateway {
namespace {

using namespace std::chrono_literals;

std::string wrapper_bytes(const VisionPacket& packet) { return to_proto(packet).SerializeAsString(); }

const net::Endpoint kSender = *net::Endpoint::parse("127.0.0.1:40000");

class PipelineDriver {
 public:
  DatagramResult feed(const std::string& bytes) {
    now += 1ms;
    return pipeline.on_datagram(league::byte_span(bytes), kSender, {.wall = now, .monotonic = now});
  }
  /// Every output sample is also converted to IDL, so conversions run on whatever got through.
  void convert(const DatagramResult& result) {
    if (result.output.frame) to_idl(*result.output.frame, frame_sample);
    if (result.output.geometry) to_idl(*result.output.geometry, geometry_sample);
  }

  VisionPipeline pipeline{GatewayOptions{}};
  time::Timestamp now = time::Timestamp::from_seconds(1.78e9);
  idl::vision::DetectionFrame frame_sample;
  idl::vision::Geometry geometry_sample;
};

std::vector<std::string> valid_packets() {
  std::vector<std::string> packets;
  for (const DetectionFrame& frame : testing::four_camera_frame(1)) {
    VisionPacket packet;
    packet.detection = frame;
    packet.source = VisionSource::kSslVision;
    packets.push_back(wrapper_bytes(packet));
  }
  VisionPacket geometry;
  geometry.geometry = testing::full_geometry();
  packets.push_back(wrapper_bytes(geometry));
  return packets;
}

TEST(VisionGatewayMalformed, SeededRandomBuffersNeverCrashAndAreCounted) {
  PipelineDriver d;
  std::mt19937 random(20260517);
  std::uint64_t rejected = 0;
  constexpr int kBuffers = 20000;
  for (int i = 0; i < kBuffers; ++i) {
    std::string bytes(random() % 600, '\0');
    for (char& byte : bytes) byte = static_cast<char>(random());
    const DatagramResult result = d.feed(bytes);
    if (result.malformed) {
      ++rejected;
      EXPECT_FALSE(result.output.frame);
      EXPECT_FALSE(result.malformed->empty());
    }
    d.convert(result);
  }
  // Random bytes are almost never a valid wrapper (the empty buffer is one: an empty packet).
  EXPECT_GT(rejected, kBuffers * 9 / 10);
  EXPECT_EQ(d.pipeline.malformed(), rejected);
  EXPECT_EQ(d.pipeline.malformed() + d.pipeline.gateway().counters().packets,
            static_cast<std::uint64_t>(kBuffers));
}

TEST(VisionGatewayMalformed, EveryTruncationOfValidPacketsIsHandled) {
  PipelineDriver d;
  std::uint64_t fed = 0;
  for (const std::string& packet : valid_packets()) {
    for (std::size_t length = 0; length < packet.size(); ++length) {
      d.convert(d.feed(packet.substr(0, length)));
      ++fed;
    }
  }
  EXPECT_GT(d.pipeline.malformed(), fed / 2);
  EXPECT_EQ(d.pipeline.malformed() + d.pipeline.gateway().counters().packets, fed);
}

TEST(VisionGatewayMalformed, BitFlipsOfValidPacketsNeverCrash) {
  PipelineDriver d;
  std::mt19937 random(7);
  const std::vector<std::string> packets = valid_packets();
  constexpr int kMutations = 20000;
  for (int i = 0; i < kMutations; ++i) {
    std::string bytes = packets[random() % packets.size()];
    const int flips = 1 + static_cast<int>(random() % 8);
    for (int f = 0; f < flips; ++f) bytes[random() % bytes.size()] ^= static_cast<char>(1u << (random() % 8));
    d.convert(d.feed(bytes));
  }
  EXPECT_EQ(d.pipeline.malformed() + d.pipeline.gateway().counters().packets,
            static_cast<std::uint64_t>(kMutations));
  EXPECT_GT(d.pipeline.malformed(), 0u);
}

TEST(VisionGatewayMalformed, OversizedDatagramIsRejectedUnparsed) {
  PipelineDriver d;
  const DatagramResult result = d.feed(std::string(league::kMaxDatagramBytes + 1, '\0'));
  ASSERT_TRUE(result.malformed);
  EXPECT_EQ(d.pipeline.malformed(), 1u);
}

TEST(VisionGatewayMalformed, PacketWithNaNCoordinatesIsMalformed) {
  PipelineDriver d;
  SSL_WrapperPacket wire;
  VisionPacket packet;
  packet.detection = testing::simple_frame(0, 1);
  wire = to_proto(packet);
  wire.mutable_detection()->mutable_balls(0)->set_x(std::numeric_limits<float>::quiet_NaN());
  const DatagramResult result = d.feed(wire.SerializeAsString());
  ASSERT_TRUE(result.malformed);
  EXPECT_NE(result.malformed->find("detection.balls[0].x"), std::string::npos) << *result.malformed;
  EXPECT_EQ(d.pipeline.gateway().counters().packets, 0u);
}

TEST(VisionGatewayMalformed, ValidTrafficFlowsBetweenGarbage) {
  PipelineDriver d;
  std::mt19937 random(3);
  std::uint64_t published = 0;
  for (std::uint32_t n = 1; n <= 200; ++n) {
    std::string garbage(1 + random() % 100, '\0');
    for (char& byte : garbage) byte = static_cast<char>(random() | 0x80);  // never a valid varint end
    EXPECT_TRUE(d.feed(garbage).malformed);
    VisionPacket packet;
    packet.detection = testing::simple_frame(n % 4, n);
    const DatagramResult result = d.feed(wrapper_bytes(packet));
    ASSERT_FALSE(result.malformed) << *result.malformed;
    if (result.output.frame) ++published;
  }
  EXPECT_EQ(published, 200u);
  EXPECT_EQ(d.pipeline.malformed(), 200u);
}

TEST(VisionGatewayMalformed, LogThrottleReportsOncePerIntervalWithTheCount) {
  LogThrottle throttle(1s);
  time::Timestamp t = time::Timestamp::from_seconds(10);
  EXPECT_EQ(throttle.on_event(t), 1u);  // the first one is logged at once
  for (int i = 0; i < 99; ++i) EXPECT_EQ(throttle.on_event(t + 5ms * i), 0u);
  EXPECT_EQ(throttle.on_event(t + 1s), 100u);  // 99 suppressed + this one
  EXPECT_EQ(throttle.on_event(t + 1500ms), 0u);
  EXPECT_EQ(throttle.on_event(t + 3s), 2u);
}

}  // namespace
}  // namespace ssl::vision_gateway
