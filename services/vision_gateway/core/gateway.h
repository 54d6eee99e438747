// VisionGateway: the pure core of vision_gateway. It takes every decoded SSL-Vision packet (SI units, see
// types.h) with its sender and receive time, and says what to publish: the camera frame (or why it was
// dropped) and the field geometry when it changed. No sockets, no DDS, no threads, no clock: time is an
// argument, so the same inputs always give the same outputs. One thread calls it (not thread-safe).
//
// Contract, per packet (every drop is counted in GatewayCounters, nothing is dropped silently):
//  * Source selection. Two senders may share the multicast group (the real ssl-vision and a stray
//    simulator, or two ssl-vision PCs). The gateway uses ONE:
//      - fixed (`source_address` set): only packets whose sender IP equals it (any port);
//      - auto: the first sender seen (IP and port), until it has been silent for `source_timeout`; then
//        the next sender to speak becomes the source (`source_switches`) and per-camera frame tracking
//        restarts, because frame numbers of different sources are unrelated.
//    Packets of any other sender are counted in `foreign_source` and dropped whole.
//  * Frames, per camera id: a frame whose number equals the newest seen is a duplicate, an older one is
//    out of order; both are counted and dropped. A camera restart resets the numbers, which would
//    otherwise look like "out of order" for ever, so a backwards jump counts as a restart (frame
//    published, `camera_restarts` counted, tracking restarts from it) when EITHER
//      - it jumps back at least `camera_restart_min_jump` frames after the camera was silent for at least
//        `camera_restart_silence` (ssl-vision takes seconds to restart; network reordering is a few
//        frames within milliseconds), OR
//      - `camera_resync_after` backwards frames in a row were dropped (a restart whose silence or jump
//        was too small to see, e.g. a camera that restarted early in its numbering): the camera is
//        evidently counting again from a lower number.
//    Duplicates never trigger a resync (a frozen source repeating one frame stays dropped).
//  * Geometry: resolved (missing optional fields filled from the rulebook defaults of the detected or
//    configured division, see field_defaults.h) and published on the first packet and whenever the
//    resolved geometry differs from the last one published; identical repeats are only counted.
//
//   VisionGateway gateway(GatewayOptions{.source_timeout = 1s});
//   PacketOutput out = gateway.on_packet(std::move(packet), sender, {.wall = now_wall, .monotonic =
//   now_mono}); if (out.frame) publish(*out.frame); if (out.geometry) publish(*out.geometry);
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "libs/net/endpoint.h"
#include "libs/time/time.h"
#include "services/vision_gateway/core/field_defaults.h"
#include "services/vision_gateway/core/types.h"

namespace ssl::vision_gateway {

struct GatewayOptions {
  /// Fixed source: the IPv4 address (host byte order) of the one vision host to use; nullopt = auto.
  std::optional<std::uint32_t> source_address;
  /// Auto: silence of the current source after which another sender may take over.
  time::Duration source_timeout = std::chrono::seconds(1);
  /// A camera silent at least this long whose numbers then jump back is taken as restarted.
  time::Duration camera_restart_silence = std::chrono::milliseconds(500);
  /// ... if they jump back at least this many frames.
  std::uint32_t camera_restart_min_jump = 10;
  /// This many backwards frames in a row from one camera resynchronise it (>= 1).
  std::uint32_t camera_resync_after = 30;
  /// Whose rulebook defaults fill missing geometry fields.
  DivisionChoice defaults_division = DivisionChoice::kAuto;
};

/// What happened to the detection part of a packet.
enum class FrameDecision : std::uint8_t {
  kNone,           // the packet held no detection frame
  kPublished,      // newer than every frame of its camera (or the camera's first / restarted)
  kDuplicate,      // same frame number as the newest of its camera
  kOutOfOrder,     // older than the newest of its camera
  kForeignSource,  // from a sender other than the selected source
};

/// What happened to the geometry part of a packet.
enum class GeometryDecision : std::uint8_t { kNone, kPublished, kUnchanged, kForeignSource };

/// A frame to publish on vision.detection.
struct PublishedFrame {
  DetectionFrame frame;
  VisionSource source = VisionSource::kUnknown;
  time::Timestamp receive_wall;  // host wall clock, Unix
};

/// A geometry to publish on vision.geometry.
struct PublishedGeometry {
  FieldGeometry geometry;
  VisionSource source = VisionSource::kUnknown;
  time::Timestamp receive_wall;  // host wall clock, Unix
};

struct PacketOutput {
  FrameDecision frame_decision = FrameDecision::kNone;
  GeometryDecision geometry_decision = GeometryDecision::kNone;
  std::optional<PublishedFrame> frame;
  std::optional<PublishedGeometry> geometry;
  bool source_switched = false;   // auto mode: this packet's sender became the source
  bool camera_restarted = false;  // the frame was taken as its camera's restart
};

/// Totals since construction.
struct GatewayCounters {
  std::uint64_t packets = 0;           // packets given to on_packet
  std::uint64_t empty_packets = 0;     // from the source but with neither detection nor geometry (dropped)
  std::uint64_t foreign_source = 0;    // packets of another sender (dropped)
  std::uint64_t source_switches = 0;   // auto: new source after the old one went silent (first lock excluded)
  std::uint64_t detection_frames = 0;  // detection frames from the source
  std::uint64_t frames_published = 0;
  std::uint64_t duplicates = 0;        // dropped
  std::uint64_t out_of_order = 0;      // dropped
  std::uint64_t camera_restarts = 0;   // backwards jumps taken as restarts (those frames are published)
  std::uint64_t geometry_packets = 0;  // geometry parts from the source
  std::uint64_t geometry_updates = 0;  // geometries published (first one and changes)
};

/// One camera as the gateway tracks it.
struct CameraStatus {
  std::uint32_t camera_id = 0;
  std::uint32_t newest_frame_number = 0;
  time::Timestamp last_seen_monotonic;  // any frame of the camera, dropped ones included
  std::uint32_t backwards_in_row = 0;
};

class VisionGateway {
 public:
  explicit VisionGateway(GatewayOptions options);

  /// Handles one decoded packet from `sender`, received at `received`. Moves the frame into the output.
  PacketOutput on_packet(VisionPacket packet, const net::Endpoint& sender, const ReceiveTime& received);

  const GatewayCounters& counters() const noexcept { return counters_; }
  const GatewayOptions& options() const noexcept { return options_; }

  /// The sender currently used (fixed mode: the last accepted sender); nullopt before the first packet.
  std::optional<net::Endpoint> source() const noexcept { return source_; }

  /// Time since the last published frame (monotonic); nullopt if none was published yet.
  std::optional<time::Duration> vision_age(time::Timestamp now_monotonic) const;

  /// The cameras seen from the current source, by id.
  std::vector<CameraStatus> cameras() const;

  /// The last geometry published, if any.
  const std::optional<FieldGeometry>& geometry() const noexcept { return geometry_; }

 private:
  /// Whether `sender` is (or now becomes) the source; updates the lock and `output.source_switched`.
  bool select_source(const net::Endpoint& sender, time::Timestamp now_monotonic, PacketOutput& output);
  FrameDecision admit_frame(const DetectionFrame& frame, time::Timestamp now_monotonic, bool& restarted);

  GatewayOptions options_;
  GatewayCounters counters_;
  std::optional<net::Endpoint> source_;
  time::Timestamp source_last_seen_monotonic_;
  std::map<std::uint32_t, CameraStatus> cameras_;
  std::optional<time::Timestamp> last_published_monotonic_;
  std::optional<FieldGeometry> geometry_;
};

/// "published", "duplicate", "out_of_order", "foreign_source", "none".
std::string_view to_string(FrameDecision decision);

}  // namespace ssl::vision_gateway
