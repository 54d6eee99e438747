#include "services/vision_gateway/core/gateway.h"

#include <algorithm>
#include <utility>

namespace ssl::vision_gateway {

VisionGateway::VisionGateway(GatewayOptions options) : options_(std::move(options)) {
  options_.camera_resync_after = std::max<std::uint32_t>(options_.camera_resync_after, 1);
}

bool VisionGateway::select_source(const net::Endpoint& sender, time::Timestamp now_monotonic,
                                  PacketOutput& output) {
  if (options_.source_address) {
    if (sender.address() != *options_.source_address) return false;
    source_ = sender;
    source_last_seen_monotonic_ = now_monotonic;
    return true;
  }
  if (!source_) {
    source_ = sender;  // the first sender seen: not a switch
  } else if (*source_ != sender) {
    if (now_monotonic - source_last_seen_monotonic_ < options_.source_timeout) return false;
    source_ = sender;
    cameras_.clear();  // frame numbers of another source are unrelated to the old ones
    ++counters_.source_switches;
    output.source_switched = true;
  }
  source_last_seen_monotonic_ = now_monotonic;
  return true;
}

FrameDecision VisionGateway::admit_frame(const DetectionFrame& frame, time::Timestamp now_monotonic,
                                         bool& restarted) {
  restarted = false;
  auto [it, first] = cameras_.try_emplace(frame.camera_id);
  CameraStatus& camera = it->second;
  const time::Duration silence = now_monotonic - camera.last_seen_monotonic;
  camera.camera_id = frame.camera_id;
  camera.last_seen_monotonic = now_monotonic;
  if (first || frame.frame_number > camera.newest_frame_number) {
    camera.newest_frame_number = frame.frame_number;
    camera.backwards_in_row = 0;
    return FrameDecision::kPublished;
  }
  if (frame.frame_number == camera.newest_frame_number) return FrameDecision::kDuplicate;

  const std::uint32_t jump = camera.newest_frame_number - frame.frame_number;
  ++camera.backwards_in_row;
  const bool restart_after_silence =
      jump >= options_.camera_restart_min_jump && silence >= options_.camera_restart_silence;
  const bool resync = camera.backwards_in_row >= options_.camera_resync_after;
  if (!restart_after_silence && !resync) return FrameDecision::kOutOfOrder;
  camera.newest_frame_number = frame.frame_number;
  camera.backwards_in_row = 0;
  restarted = true;
  return FrameDecision::kPublished;
}

PacketOutput VisionGateway::on_packet(VisionPacket packet, const net::Endpoint& sender,
                                      const ReceiveTime& received) {
  PacketOutput output;
  ++counters_.packets;
  if (!select_source(sender, received.monotonic, output)) {
    ++counters_.foreign_source;
    if (packet.detection) output.frame_decision = FrameDecision::kForeignSource;
    if (packet.geometry) output.geometry_decision = GeometryDecision::kForeignSource;
    return output;
  }
  if (!packet.detection && !packet.geometry) {
    ++counters_.empty_packets;
    return output;
  }

  if (packet.detection) {
    ++counters_.detection_frames;
    output.frame_decision = admit_frame(*packet.detection, received.monotonic, output.camera_restarted);
    switch (output.frame_decision) {
      case FrameDecision::kPublished:
        ++counters_.frames_published;
        if (output.camera_restarted) ++counters_.camera_restarts;
        last_published_monotonic_ = received.monotonic;
        output.frame = PublishedFrame{std::move(*packet.detection), packet.source, received.wall};
        break;
      case FrameDecision::kDuplicate:
        ++counters_.duplicates;
        break;
      case FrameDecision::kOutOfOrder:
        ++counters_.out_of_order;
        break;
      case FrameDecision::kNone:
      case FrameDecision::kForeignSource:
        break;
    }
  }

  if (packet.geometry) {
    ++counters_.geometry_packets;
    FieldGeometry resolved = resolve_geometry(*packet.geometry, options_.defaults_division);
    if (geometry_ && *geometry_ == resolved) {
      output.geometry_decision = GeometryDecision::kUnchanged;
    } else {
      ++counters_.geometry_updates;
      output.geometry_decision = GeometryDecision::kPublished;
      output.geometry = PublishedGeometry{resolved, packet.source, received.wall};
      geometry_ = std::move(resolved);
    }
  }
  return output;
}

std::optional<time::Duration> VisionGateway::vision_age(time::Timestamp now_monotonic) const {
  if (!last_published_monotonic_) return std::nullopt;
  return now_monotonic - *last_published_monotonic_;
}

std::vector<CameraStatus> VisionGateway::cameras() const {
  std::vector<CameraStatus> cameras;
  cameras.reserve(cameras_.size());
  for (const auto& [id, camera] : cameras_) cameras.push_back(camera);
  return cameras;
}

std::string_view to_string(FrameDecision decision) {
  switch (decision) {
    case FrameDecision::kNone:
      return "none";
    case FrameDecision::kPublished:
      return "published";
    case FrameDecision::kDuplicate:
      return "duplicate";
    case FrameDecision::kOutOfOrder:
      return "out_of_order";
    case FrameDecision::kForeignSource:
      return "foreign_source";
  }
  return "none";
}

}  // namespace ssl::vision_gateway
