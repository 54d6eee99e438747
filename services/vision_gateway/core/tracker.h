// TrackerMonitor: what the gateway learns from the optional tracked-vision stream (TrackerWrapperPacket on
// 224.5.23.2:10010, sent by autoRefs / trackers such as TIGERs' or ER-Force's). The design has no topic
// for tracked vision, so the gateway only decodes, counts and reports it on system.health (packets, frames,
// distinct sources, the last source's name); it publishes nothing from it.
//
// Units of the summary (the tracker protocol is already SI): seconds as ssl::time::Timestamp on the
// TRACKER HOST's wall clock (Unix). Pure: time is an argument; one thread calls it.
//
//   TrackerMonitor tracker;
//   tracker.on_packet(TrackerPacket{.uuid = "a1b2", .source_name = "TIGERs", .frame_number = 7}, received);
//   tracker.counters().packets;   // 1
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <string>

#include "libs/time/time.h"
#include "services/vision_gateway/core/types.h"

namespace ssl::vision_gateway {

/// The parts of a TrackerWrapperPacket the gateway looks at.
struct TrackerPacket {
  std::string uuid;                           // random per tracker instance, constant while it runs
  std::optional<std::string> source_name;     // e.g. "TIGERs"
  std::optional<std::uint32_t> frame_number;  // present when the packet carries a tracked frame
  std::optional<time::Timestamp> timestamp;   // tracked frame time, tracker host wall clock (Unix)
  std::size_t balls = 0;
  std::size_t robots = 0;
};

struct TrackerCounters {
  std::uint64_t packets = 0;  // decoded tracker packets
  std::uint64_t frames = 0;   // packets that carried a tracked frame
  std::uint64_t sources = 0;  // distinct uuids seen
};

class TrackerMonitor {
 public:
  void on_packet(const TrackerPacket& packet, const ReceiveTime& received);

  const TrackerCounters& counters() const noexcept { return counters_; }
  /// The source name (or uuid when it sent no name) of the newest packet; empty before the first.
  const std::string& last_source() const noexcept { return last_source_; }
  /// Time since the newest packet (monotonic); nullopt before the first.
  std::optional<time::Duration> age(time::Timestamp now_monotonic) const;

 private:
  TrackerCounters counters_;
  std::set<std::string> uuids_;
  std::string last_source_;
  std::optional<time::Timestamp> last_monotonic_;
};

}  // namespace ssl::vision_gateway
