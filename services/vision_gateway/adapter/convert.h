// The vision gateway's only conversions between wire types and the core's SI types, done once here:
//
//   SSL_WrapperPacket (millimetres, Unix seconds as double)  --from_proto-->  VisionPacket (m, Timestamp)
//   PublishedFrame / PublishedGeometry (m, Timestamp)        --to_idl----->   idl::vision (m, Unix ns)
//   VisionPacket (m)                                          --to_proto--->   SSL_WrapperPacket (mm)
//   TrackerWrapperPacket (already SI)                         --from_proto-->  TrackerPacket
//
// Lengths: every SSL-Vision length (positions, heights, field sizes, line points and thicknesses, arc
// centres and radii, camera translations and derived positions) is millimetres on the wire and metres in
// the core; angles are radians on both sides; pixels, confidences, quaternions and ball-model parameters
// pass unchanged. Times: t_capture / t_sent / t_capture_camera (double seconds) become Timestamps rounded
// to the nearest nanosecond (libs/time), and Unix ns in the IDL. to_proto exists for round-trip tests,
// benchmarks and tools that replay core data; the gateway itself never sends packets.
//
// Validation (from_proto): on top of the decoder's protobuf checks (required fields, size), a packet is
// rejected with an Error naming the field when a number is NaN or infinite, a time is outside the
// representable range, or the field length/width is not positive. A line or arc without the optional
// `type` gets the type its ssl-vision name stands for (shape_type_from_name).
//
//   VisionDecoder decoder;                          // reuses one protobuf message between packets
//   Result<VisionPacket> packet = decoder.decode(bytes);
//   if (!packet) { ++malformed; log(packet.error().message); }
#pragma once

#include <cstdint>
#include <span>

#include "idl/vision.h"
#include "libs/common/result.h"
#include "proto/ssl_vision_wrapper.pb.h"
#include "proto/ssl_vision_wrapper_tracked.pb.h"
#include "services/vision_gateway/core/gateway.h"
#include "services/vision_gateway/core/tracker.h"
#include "services/vision_gateway/core/types.h"

namespace ssl::vision_gateway {

/// Millimetres (wire) -> metres (core).
constexpr double metres_from_mm(double millimetres) noexcept { return millimetres / 1000.0; }
/// Metres (core) -> millimetres (wire).
constexpr double mm_from_metres(double metres) noexcept { return metres * 1000.0; }

/// SSL_WrapperPacket -> core packet; see the validation rules above.
Result<VisionPacket> from_proto(const SSL_WrapperPacket& packet);

/// Core packet -> SSL_WrapperPacket (metres -> millimetres, float/int32 on the wire, rounded to nearest).
SSL_WrapperPacket to_proto(const VisionPacket& packet);

/// Decodes and converts datagrams, reusing one protobuf message (and its allocations) between calls.
/// Not thread-safe: one per receiving thread.
class VisionDecoder {
 public:
  /// Error when the bytes are not a valid SSL_WrapperPacket (ssl::league::decode_into) or fail from_proto.
  Result<VisionPacket> decode(std::span<const std::uint8_t> bytes);

 private:
  SSL_WrapperPacket message_;
};

/// TrackerWrapperPacket -> what the tracker monitor counts.
TrackerPacket from_proto(const TrackerWrapperPacket& packet);

/// Decodes a tracked-vision datagram (ssl::league::decode_tracker_wrapper) and converts it.
Result<TrackerPacket> decode_tracker_packet(std::span<const std::uint8_t> bytes);

/// Fills a vision.detection sample (overwriting every field; reusing `out`'s storage).
void to_idl(const PublishedFrame& frame, idl::vision::DetectionFrame& out);

/// Fills a vision.geometry sample (overwriting every field).
void to_idl(const PublishedGeometry& geometry, idl::vision::Geometry& out);

}  // namespace ssl::vision_gateway
