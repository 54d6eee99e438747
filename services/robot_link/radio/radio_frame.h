// The radio link's binary frames between robot_link and a base station (over UDP or a serial line), as
// pure functions: encode, decode, CRC, and a stream assembler for byte streams. The byte layout is
// documented in services/robot_link/README.md ("Radio frame format"); in short, little-endian:
//
//   sync 0xA5 0x5A | version 1 | type (1 command, 2 status) | sequence u16 | payload length u8 |
//   payload | CRC-16/CCITT-FALSE u16 over every byte before it
//
// A command frame carries one record per robot (robot local frame): velocities as signed fixed point
// (forward / left in mm/s, angular in mrad/s, int16), kick type and a safety-stop flag, kick speed in
// mm/s, chip angle in mrad, dribbler rpm (uint16). A status frame carries per-robot feedback: ball in
// dribbler, battery (mV), kicker charge (%), link quality (%), and the last command sequence received.
// Values outside a field's range saturate when encoding (NaN encodes as 0).
//
// Contract: decode_frame never throws, never crashes and never reads outside its input; any short,
// truncated, corrupt or random input gives an ssl::Error saying what is wrong (CRC-16 detects every
// single-bit and every burst error up to 16 bits).
//
//   std::vector<std::uint8_t> bytes = encode_command_frame({.sequence = 7, .robots = {...}});
//   ssl::Result<RadioFrame> frame = decode_frame(bytes);
//   if (!frame) { ++counters.bad_frames; log(frame.error().message); }
//   FrameAssembler stream;                                       // serial: frames split across reads
//   for (const RadioFrame& f : stream.push(read_bytes)) handle(f);
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include "libs/common/result.h"
#include "services/robot_link/core/types.h"

namespace ssl::robot_link::radio {

inline constexpr std::uint8_t kSync0 = 0xA5;
inline constexpr std::uint8_t kSync1 = 0x5A;
inline constexpr std::uint8_t kVersion = 1;
inline constexpr std::size_t kHeaderBytes = 7;  // sync(2) version type sequence(2) length
inline constexpr std::size_t kCrcBytes = 2;
inline constexpr std::size_t kMinFrameBytes = kHeaderBytes + kCrcBytes;
inline constexpr std::size_t kMaxPayloadBytes = 255;
inline constexpr std::size_t kMaxFrameBytes = kHeaderBytes + kMaxPayloadBytes + kCrcBytes;
inline constexpr std::size_t kCommandRecordBytes = 14;
inline constexpr std::size_t kStatusRecordBytes = 8;
inline constexpr std::size_t kMaxRecords = kMaxRobots;  // 16 records: 1 + 16 * 14 = 225 payload bytes

// Fixed-point scales (value on the wire = round(SI value * scale), saturated to the field's type).
inline constexpr double kVelocityScale = 1000.0;   // m/s -> mm/s (int16: +-32.767 m/s)
inline constexpr double kAngularScale = 1000.0;    // rad/s -> mrad/s (int16: +-32.767 rad/s)
inline constexpr double kKickSpeedScale = 1000.0;  // m/s -> mm/s (uint16: 0..65.535 m/s)
inline constexpr double kChipAngleScale = 1000.0;  // rad -> mrad (uint16)
inline constexpr double kBatteryScale = 1000.0;    // V -> mV (uint16)

enum class FrameType : std::uint8_t { kCommand = 1, kStatus = 2 };

/// One robot's entry of a command frame.
struct CommandRecord {
  RobotCommand command;  // id 0..15
  bool stop = false;     // safety stop (watchdog, HALT, e-stop): the robot may brake harder than usual
};

struct CommandFrame {
  std::uint16_t sequence = 0;         // increments per frame sent, wraps
  std::vector<CommandRecord> robots;  // at most kMaxRecords
};

/// One robot's entry of a status frame (robot -> base station -> robot_link).
struct StatusRecord {
  std::uint32_t robot_id = 0;
  bool ball_in_dribbler = false;
  std::optional<double> battery_voltage;  // V, 0..65.535
  std::optional<double> kicker_charge;    // 0..1, sent in whole percent
  std::optional<double> link_quality;     // 0..1, sent in whole percent
  std::uint16_t last_command_sequence = 0;

  friend bool operator==(const StatusRecord&, const StatusRecord&) = default;
};

struct StatusFrame {
  std::uint16_t sequence = 0;        // the base station's own counter
  std::vector<StatusRecord> robots;  // at most kMaxRecords
};

using RadioFrame = std::variant<CommandFrame, StatusFrame>;

/// CRC-16/CCITT-FALSE: polynomial 0x1021, initial value 0xFFFF, no reflection, no final XOR
/// (check value: 0x29B1 for the ASCII bytes "123456789").
std::uint16_t crc16_ccitt(std::span<const std::uint8_t> bytes) noexcept;

/// Encodes a command frame; an error when it has more than kMaxRecords robots or an id >= kMaxRobots.
Result<std::vector<std::uint8_t>> encode_command_frame(const CommandFrame& frame);

/// Encodes a status frame; an error when it has more than kMaxRecords robots or an id >= kMaxRobots.
Result<std::vector<std::uint8_t>> encode_status_frame(const StatusFrame& frame);

/// Decodes exactly one whole frame (no bytes before or after it).
Result<RadioFrame> decode_frame(std::span<const std::uint8_t> bytes);

/// Cuts a byte stream (serial line) into frames: bytes before a sync word and frames that fail to decode
/// are skipped and counted, and decoding resumes at the next sync word. Holds at most one partial frame.
class FrameAssembler {
 public:
  /// Appends `bytes` and returns every frame completed by them, in stream order.
  std::vector<RadioFrame> push(std::span<const std::uint8_t> bytes);

  std::uint64_t frames() const noexcept { return frames_; }
  std::uint64_t bad_frames() const noexcept { return bad_frames_; }        // sync found, decode failed
  std::uint64_t skipped_bytes() const noexcept { return skipped_bytes_; }  // not part of a good frame

 private:
  std::vector<std::uint8_t> buffer_;
  std::uint64_t frames_ = 0;
  std::uint64_t bad_frames_ = 0;
  std::uint64_t skipped_bytes_ = 0;
};

}  // namespace ssl::robot_link::radio
