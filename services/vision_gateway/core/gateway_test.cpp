// The gateway core, driven with scripted packets and times: per-camera duplicates, out-of-order frames and
// restarts; source selection (auto lock, foreign senders, switching after silence, fixed address);
// geometry published on the first packet and on changes only.
#include "services/vision_gateway/core/gateway.h"

#include <gtest/gtest.h>

#include "services/vision_gateway/testing/builders.h"

namespace ssl::vision_gateway {
namespace {

using namespace std::chrono_literals;
using testing::full_geometry;
using testing::simple_frame;

const net::Endpoint kVision = *net::Endpoint::parse("10.0.0.5:40000");
const net::Endpoint kVisionOtherPort = *net::Endpoint::parse("10.0.0.5:40001");
const net::Endpoint kStray = *net::Endpoint::parse("10.0.0.9:50000");

/// Drives a gateway with a monotonic clock that the test advances.
class Driver {
 public:
  explicit Driver(GatewayOptions options = {}) : gateway(std::move(options)) {}

  PacketOutput frame(std::uint32_t camera, std::uint32_t number, const net::Endpoint& sender = kVision) {
    VisionPacket packet;
    packet.source = VisionSource::kSslVision;
    packet.detection = simple_frame(camera, number);
    return send(std::move(packet), sender);
  }
  PacketOutput geometry(GeometryInput geometry, const net::Endpoint& sender = kVision) {
    VisionPacket packet;
    packet.geometry = std::move(geometry);
    return send(std::move(packet), sender);
  }
  PacketOutput send(VisionPacket packet, const net::Endpoint& sender = kVision) {
    const ReceiveTime at{.wall = time::Timestamp::from_seconds(1.78e9) + (now - time::Timestamp()),
                         .monotonic = now};
    return gateway.on_packet(std::move(packet), sender, at);
  }
  void advance(time::Duration d) { now += d; }

  VisionGateway gateway;
  time::Timestamp now = time::Timestamp::from_seconds(100.0);
};

TEST(VisionGatewayCore, FirstFrameOfEachCameraIsPublishedWithItsSourceAndReceiveTime) {
  Driver d;
  const PacketOutput out = d.frame(3, 500);
  EXPECT_EQ(out.frame_decision, FrameDecision::kPublished);
  ASSERT_TRUE(out.frame);
  EXPECT_EQ(out.frame->frame, simple_frame(3, 500));
  EXPECT_EQ(out.frame->source, VisionSource::kSslVision);
  EXPECT_EQ(out.frame->receive_wall, time::Timestamp::from_seconds(1.78e9 + 100.0));
  EXPECT_FALSE(out.geometry);
  EXPECT_EQ(d.gateway.counters().frames_published, 1u);
  EXPECT_EQ(d.gateway.counters().packets, 1u);
}

TEST(VisionGatewayCore, DuplicateFrameNumberIsCountedAndDropped) {
  Driver d;
  ASSERT_TRUE(d.frame(0, 10).frame);
  d.advance(1ms);
  const PacketOutput again = d.frame(0, 10);
  EXPECT_EQ(again.frame_decision, FrameDecision::kDuplicate);
  EXPECT_FALSE(again.frame);
  EXPECT_EQ(d.gateway.counters().duplicates, 1u);
  EXPECT_EQ(d.gateway.counters().frames_published, 1u);
  EXPECT_EQ(d.gateway.counters().detection_frames, 2u);
}

TEST(VisionGatewayCore, OlderFrameNumberIsOutOfOrderAndDropped) {
  Driver d;
  ASSERT_TRUE(d.frame(0, 10).frame);
  ASSERT_TRUE(d.frame(0, 12).frame);
  const PacketOutput late = d.frame(0, 11);
  EXPECT_EQ(late.frame_decision, FrameDecision::kOutOfOrder);
  EXPECT_FALSE(late.frame);
  EXPECT_EQ(d.gateway.counters().out_of_order, 1u);
  EXPECT_TRUE(d.frame(0, 13).frame);  // tracking continues from 12
}

TEST(VisionGatewayCore, CamerasAreTrackedIndependently) {
  Driver d;
  EXPECT_TRUE(d.frame(0, 100).frame);
  EXPECT_TRUE(d.frame(1, 5).frame);  // lower number, other camera: not out of order
  EXPECT_TRUE(d.frame(2, 100).frame);
  EXPECT_EQ(d.frame(1, 5).frame_decision, FrameDecision::kDuplicate);
  EXPECT_TRUE(d.frame(0, 101).frame);
  ASSERT_EQ(d.gateway.cameras().size(), 3u);
  EXPECT_EQ(d.gateway.cameras()[0].newest_frame_number, 101u);
  EXPECT_EQ(d.gateway.cameras()[1].newest_frame_number, 5u);
}

TEST(VisionGatewayCore, LargeBackwardJumpAfterSilenceIsACameraRestart) {
  Driver d({.camera_restart_silence = 500ms, .camera_restart_min_jump = 10});
  ASSERT_TRUE(d.frame(0, 90000).frame);
  d.advance(2s);  // ssl-vision restarting
  const PacketOutput restarted = d.frame(0, 0);
  EXPECT_EQ(restarted.frame_decision, FrameDecision::kPublished);
  EXPECT_TRUE(restarted.camera_restarted);
  ASSERT_TRUE(restarted.frame);
  EXPECT_EQ(d.gateway.counters().camera_restarts, 1u);
  EXPECT_EQ(d.gateway.counters().out_of_order, 0u);
  d.advance(13ms);
  EXPECT_TRUE(d.frame(0, 1).frame);  // counting on from the restart
  EXPECT_EQ(d.frame(0, 0).frame_decision, FrameDecision::kOutOfOrder);
}

TEST(VisionGatewayCore, BackwardJumpWithoutSilenceIsOutOfOrderNotARestart) {
  Driver d({.camera_restart_silence = 500ms, .camera_restart_min_jump = 10});
  ASSERT_TRUE(d.frame(0, 1000).frame);
  d.advance(10ms);
  EXPECT_EQ(d.frame(0, 0).frame_decision, FrameDecision::kOutOfOrder);
  EXPECT_EQ(d.gateway.counters().camera_restarts, 0u);
}

TEST(VisionGatewayCore, SmallBackwardJumpAfterSilenceIsOutOfOrder) {
  Driver d({.camera_restart_silence = 500ms, .camera_restart_min_jump = 10});
  ASSERT_TRUE(d.frame(0, 1000).frame);
  d.advance(1s);
  EXPECT_EQ(d.frame(0, 995).frame_decision, FrameDecision::kOutOfOrder);
}

TEST(VisionGatewayCore, ManyBackwardFramesInARowResynchroniseTheCamera) {
  // A camera that restarted without a visible silence (or with a small jump) must not stay dropped.
  Driver d({.camera_restart_silence = 500ms, .camera_restart_min_jump = 10, .camera_resync_after = 5});
  ASSERT_TRUE(d.frame(0, 1000).frame);
  for (std::uint32_t n = 0; n < 4; ++n) {
    d.advance(13ms);
    EXPECT_EQ(d.frame(0, n).frame_decision, FrameDecision::kOutOfOrder) << n;
  }
  d.advance(13ms);
  const PacketOutput fifth = d.frame(0, 4);
  EXPECT_TRUE(fifth.camera_restarted);
  EXPECT_TRUE(fifth.frame);
  EXPECT_TRUE(d.frame(0, 5).frame);
  EXPECT_EQ(d.gateway.counters().out_of_order, 4u);
  EXPECT_EQ(d.gateway.counters().camera_restarts, 1u);
}

TEST(VisionGatewayCore, RepeatedDuplicatesNeverResynchronise) {
  Driver d({.camera_resync_after = 3});
  ASSERT_TRUE(d.frame(0, 7).frame);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(d.frame(0, 7).frame_decision, FrameDecision::kDuplicate);
  EXPECT_EQ(d.gateway.counters().duplicates, 10u);
  EXPECT_EQ(d.gateway.counters().camera_restarts, 0u);
}

TEST(VisionGatewayCore, AutoLocksOntoTheFirstSenderAndCountsOthersAsForeign) {
  Driver d;
  EXPECT_TRUE(d.frame(0, 1, kVision).frame);
  const PacketOutput stray = d.frame(0, 2, kStray);
  EXPECT_EQ(stray.frame_decision, FrameDecision::kForeignSource);
  EXPECT_FALSE(stray.frame);
  const PacketOutput stray_geometry = d.geometry(full_geometry(), kStray);
  EXPECT_EQ(stray_geometry.geometry_decision, GeometryDecision::kForeignSource);
  EXPECT_FALSE(stray_geometry.geometry);
  // Same host, other port: a different sender in auto mode.
  EXPECT_EQ(d.frame(0, 3, kVisionOtherPort).frame_decision, FrameDecision::kForeignSource);
  EXPECT_TRUE(d.frame(0, 2, kVision).frame);
  EXPECT_EQ(d.gateway.counters().foreign_source, 3u);
  EXPECT_EQ(d.gateway.source(), kVision);
  EXPECT_EQ(d.gateway.counters().source_switches, 0u);
}

TEST(VisionGatewayCore, AutoSwitchesOnlyAfterTheSourceWasSilentForTheTimeout) {
  Driver d({.source_timeout = 1s});
  ASSERT_TRUE(d.frame(0, 5000, kVision).frame);
  d.advance(900ms);
  EXPECT_EQ(d.frame(0, 1, kStray).frame_decision, FrameDecision::kForeignSource);  // 0.9 s: not yet
  d.advance(200ms);  // the stray's packets do not keep the old source alive: 1.1 s since kVision
  const PacketOutput switched = d.frame(0, 2, kStray);
  EXPECT_TRUE(switched.source_switched);
  // Frame tracking restarted with the new source: its lower numbers are not "out of order".
  EXPECT_EQ(switched.frame_decision, FrameDecision::kPublished);
  EXPECT_EQ(d.gateway.source(), kStray);
  EXPECT_EQ(d.gateway.counters().source_switches, 1u);
  // Now the old source is the foreign one.
  EXPECT_EQ(d.frame(0, 5001, kVision).frame_decision, FrameDecision::kForeignSource);
}

TEST(VisionGatewayCore, ActiveSourceIsNeverReplacedWhileItKeepsSending) {
  Driver d({.source_timeout = 100ms});
  for (std::uint32_t n = 1; n <= 50; ++n) {
    EXPECT_TRUE(d.frame(0, n, kVision).frame);
    EXPECT_FALSE(d.frame(0, n, kStray).frame);
    d.advance(60ms);
  }
  EXPECT_EQ(d.gateway.counters().source_switches, 0u);
  EXPECT_EQ(d.gateway.counters().foreign_source, 50u);
}

TEST(VisionGatewayCore, FixedSourceAcceptsOnlyThatAddressOnAnyPort) {
  Driver d({.source_address = kVision.address(), .source_timeout = 10ms});
  EXPECT_EQ(d.frame(0, 1, kStray).frame_decision, FrameDecision::kForeignSource);  // first, but not ours
  EXPECT_TRUE(d.frame(0, 2, kVision).frame);
  EXPECT_TRUE(d.frame(0, 3, kVisionOtherPort).frame);  // ssl-vision restarted on another port
  d.advance(5s);                                       // silence never lets a stray take over in fixed mode
  EXPECT_EQ(d.frame(0, 4, kStray).frame_decision, FrameDecision::kForeignSource);
  EXPECT_EQ(d.gateway.counters().foreign_source, 2u);
  EXPECT_EQ(d.gateway.counters().source_switches, 0u);
}

TEST(VisionGatewayCore, GeometryIsPublishedFirstTimeAndOnChangeOnly) {
  Driver d;
  const PacketOutput first = d.geometry(full_geometry());
  EXPECT_EQ(first.geometry_decision, GeometryDecision::kPublished);
  ASSERT_TRUE(first.geometry);
  EXPECT_EQ(first.geometry->geometry.field.field_length, 12.0);
  EXPECT_TRUE(first.geometry->geometry.defaulted_fields.empty());
  for (int i = 0; i < 5; ++i) {
    const PacketOutput same = d.geometry(full_geometry());
    EXPECT_EQ(same.geometry_decision, GeometryDecision::kUnchanged);
    EXPECT_FALSE(same.geometry);
  }
  GeometryInput moved_camera = full_geometry();
  moved_camera.calibrations[2].tz = 4.5;
  const PacketOutput changed = d.geometry(moved_camera);
  ASSERT_TRUE(changed.geometry);
  EXPECT_EQ(changed.geometry->geometry.calibrations[2].tz, 4.5);
  GeometryInput wider_line = moved_camera;
  wider_line.field.lines[0].thickness = 0.02;
  EXPECT_TRUE(d.geometry(wider_line).geometry);
  EXPECT_FALSE(d.geometry(wider_line).geometry);
  EXPECT_EQ(d.gateway.counters().geometry_packets, 9u);
  EXPECT_EQ(d.gateway.counters().geometry_updates, 3u);
  ASSERT_TRUE(d.gateway.geometry());
  EXPECT_EQ(d.gateway.geometry()->field.lines[0].thickness, 0.02);
}

TEST(VisionGatewayCore, PacketWithFrameAndGeometryYieldsBoth) {
  Driver d;
  VisionPacket packet;
  packet.detection = simple_frame(1, 1);
  packet.geometry = full_geometry();
  packet.source = VisionSource::kGrsim;
  const PacketOutput out = d.send(std::move(packet));
  ASSERT_TRUE(out.frame);
  ASSERT_TRUE(out.geometry);
  EXPECT_EQ(out.geometry->source, VisionSource::kGrsim);
}

TEST(VisionGatewayCore, EmptyPacketIsCountedAndDropped) {
  Driver d;
  const PacketOutput out = d.send(VisionPacket{});
  EXPECT_FALSE(out.frame);
  EXPECT_FALSE(out.geometry);
  EXPECT_EQ(d.gateway.counters().empty_packets, 1u);
}

TEST(VisionGatewayCore, VisionAgeMeasuresTimeSinceTheLastPublishedFrame) {
  Driver d;
  EXPECT_FALSE(d.gateway.vision_age(d.now));
  d.geometry(full_geometry());
  EXPECT_FALSE(d.gateway.vision_age(d.now));  // geometry is not vision
  d.frame(0, 1);
  d.advance(300ms);
  d.frame(0, 1);  // a duplicate does not refresh it
  d.advance(200ms);
  EXPECT_EQ(d.gateway.vision_age(d.now), 500ms);
}

TEST(VisionGatewayCore, SameInputsGiveSameOutputs) {
  auto run = [] {
    Driver d({.source_timeout = 50ms, .camera_resync_after = 3});
    std::vector<FrameDecision> decisions;
    const std::uint32_t numbers[] = {5, 6, 6, 4, 9, 0, 1, 2, 3, 10};
    for (std::uint32_t n : numbers) {
      decisions.push_back(d.frame(n % 2, n, n == 9 ? kStray : kVision).frame_decision);
      d.advance(20ms);
    }
    return decisions;
  };
  EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace ssl::vision_gateway
