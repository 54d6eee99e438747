// LatencyWindow percentiles and the TrackerMonitor's counting.
#include "services/vision_gateway/core/latency_window.h"

#include <gtest/gtest.h>

#include "services/vision_gateway/core/tracker.h"

namespace ssl::vision_gateway {
namespace {

using namespace std::chrono_literals;

TEST(VisionGatewayLatency, EmptyWindowSummarisesToZero) {
  LatencyWindow window;
  const LatencySummary s = window.take();
  EXPECT_EQ(s.count, 0u);
  EXPECT_EQ(s.p50, 0ns);
  EXPECT_EQ(s.p99, 0ns);
}

TEST(VisionGatewayLatency, MedianAndP99AreNearestRankAndTakeStartsANewWindow) {
  LatencyWindow window;
  for (int i = 200; i >= 1; --i) window.add(std::chrono::microseconds(i));  // 1..200 us, any order
  const LatencySummary s = window.take();
  EXPECT_EQ(s.count, 200u);
  EXPECT_EQ(s.p50, 100us);
  EXPECT_EQ(s.p99, 198us);
  EXPECT_EQ(s.max, 200us);
  window.add(7us);
  const LatencySummary next = window.take();
  EXPECT_EQ(next.count, 1u);
  EXPECT_EQ(next.p50, 7us);
  EXPECT_EQ(next.p99, 7us);
}

TEST(VisionGatewayLatency, SamplesBeyondTheCapAreCountedNotKept) {
  LatencyWindow window(10);
  for (int i = 0; i < 25; ++i) window.add(1us);
  EXPECT_EQ(window.take().count, 25u);
}

TEST(VisionGatewayTracker, CountsPacketsFramesAndDistinctSources) {
  TrackerMonitor tracker;
  const ReceiveTime at{.wall = time::Timestamp::from_seconds(1.78e9),
                       .monotonic = time::Timestamp::from_seconds(5)};
  EXPECT_FALSE(tracker.age(at.monotonic));
  tracker.on_packet({.uuid = "a", .source_name = "TIGERs", .frame_number = 1}, at);
  tracker.on_packet({.uuid = "a", .source_name = "TIGERs", .frame_number = 2}, at);
  tracker.on_packet({.uuid = "b"}, at);
  EXPECT_EQ(tracker.counters().packets, 3u);
  EXPECT_EQ(tracker.counters().frames, 2u);
  EXPECT_EQ(tracker.counters().sources, 2u);
  EXPECT_EQ(tracker.last_source(), "b");  // no name: the uuid
  EXPECT_EQ(tracker.age(at.monotonic + 2s), 2s);
}

}  // namespace
}  // namespace ssl::vision_gateway
