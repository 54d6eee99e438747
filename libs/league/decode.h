// Safe decoders for every protobuf datagram the stack receives from the league's tools (SSL-Vision,
// trackers, the game controller, simulators, grSim), and a checked encoder for the ones it sends.
//
// Contract: a decoder never throws, never crashes and never reads outside `bytes`, whatever they hold
// (truncated, random, oversized). It returns either a message whose proto2 `required` fields are all
// set, or an ssl::Error that names the message type, the byte count and what failed; when the bytes
// parse but required fields are missing, the error lists them (e.g. "blue.goalkeeper").
// Datagrams larger than kMaxDatagramBytes (65507, the largest UDP payload) are rejected unparsed.
// Units are those of the wire formats themselves (see the comments in proto/*.proto).
//
//   auto packet = ssl::league::decode_vision_wrapper(bytes);
//   if (!packet) { counters.malformed++; log(packet.error().message); return; }
#pragma once

#include <google/protobuf/message.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "libs/common/result.h"
#include "proto/grsim_packet.pb.h"
#include "proto/grsim_robotstatus.pb.h"
#include "proto/ssl_gc_referee_message.pb.h"
#include "proto/ssl_simulation_control.pb.h"
#include "proto/ssl_simulation_robot_control.pb.h"
#include "proto/ssl_simulation_robot_feedback.pb.h"
#include "proto/ssl_vision_wrapper.pb.h"
#include "proto/ssl_vision_wrapper_legacy.pb.h"
#include "proto/ssl_vision_wrapper_tracked.pb.h"

namespace ssl::league {

/// Largest UDP payload over IPv4 (65535 - 8 UDP header - 20 IP header bytes).
inline constexpr std::size_t kMaxDatagramBytes = 65507;

/// Views text-like storage (std::string, log payloads) as bytes for the decoders.
inline std::span<const std::uint8_t> byte_span(std::string_view text) noexcept {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

/// Clears `message` and parses `bytes` into it. On error `message` holds whatever was parsed.
Status decode_into(std::span<const std::uint8_t> bytes, google::protobuf::Message& message);

/// Decodes one datagram of any generated message type.
template <typename Message>
Result<Message> decode(std::span<const std::uint8_t> bytes) {
  Message message;
  if (Status status = decode_into(bytes, message); !status) {
    return status.error();
  }
  return message;
}

/// Serializes `message` for sending as one datagram; fails (naming the fields) when required fields
/// are missing, and when the encoding would exceed kMaxDatagramBytes.
Result<std::string> encode_datagram(const google::protobuf::Message& message);

// Named decoders, one per stream (ports are the league defaults).

/// SSL-Vision and simulators, 224.5.23.2:10006 / :10020.
inline Result<SSL_WrapperPacket> decode_vision_wrapper(std::span<const std::uint8_t> bytes) {
  return decode<SSL_WrapperPacket>(bytes);
}
/// SSL-Vision legacy 2010 geometry stream, 224.5.23.2:10005.
inline Result<RoboCup2014Legacy::Wrapper::SSL_WrapperPacket> decode_legacy_vision_wrapper(
    std::span<const std::uint8_t> bytes) {
  return decode<RoboCup2014Legacy::Wrapper::SSL_WrapperPacket>(bytes);
}
/// Game controller, 224.5.23.1:10003.
inline Result<Referee> decode_referee(std::span<const std::uint8_t> bytes) {
  return decode<Referee>(bytes);
}
/// Trackers and autoRefs, 224.5.23.2:10010.
inline Result<TrackerWrapperPacket> decode_tracker_wrapper(std::span<const std::uint8_t> bytes) {
  return decode<TrackerWrapperPacket>(bytes);
}
/// Simulation control requests, simulator :10300.
inline Result<SimulatorCommand> decode_simulator_command(std::span<const std::uint8_t> bytes) {
  return decode<SimulatorCommand>(bytes);
}
/// Simulation control answers from :10300.
inline Result<SimulatorResponse> decode_simulator_response(std::span<const std::uint8_t> bytes) {
  return decode<SimulatorResponse>(bytes);
}
/// Robot commands, simulator :10301 (blue) / :10302 (yellow).
inline Result<RobotControl> decode_robot_control(std::span<const std::uint8_t> bytes) {
  return decode<RobotControl>(bytes);
}
/// Robot feedback answered from :10301 / :10302.
inline Result<RobotControlResponse> decode_robot_control_response(std::span<const std::uint8_t> bytes) {
  return decode<RobotControlResponse>(bytes);
}
/// grSim legacy commands and replacement, :20011.
inline Result<grSim_Packet> decode_grsim_packet(std::span<const std::uint8_t> bytes) {
  return decode<grSim_Packet>(bytes);
}
/// grSim legacy robot status, :30011 (blue) / :30012 (yellow).
inline Result<Robots_Status> decode_grsim_robots_status(std::span<const std::uint8_t> bytes) {
  return decode<Robots_Status>(bytes);
}

}  // namespace ssl::league
