#include "services/robot_link/radio/radio_frame.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace ssl::robot_link::radio {
namespace {

/// round(value * scale) saturated to T's range; NaN -> 0.
template <typename T>
T to_fixed(double value, double scale) noexcept {
  if (std::isnan(value)) return 0;
  const double scaled = std::round(value * scale);
  constexpr double lowest = static_cast<double>(std::numeric_limits<T>::min());
  constexpr double highest = static_cast<double>(std::numeric_limits<T>::max());
  return static_cast<T>(std::clamp(scaled, lowest, highest));
}

std::uint8_t to_percent(double fraction) noexcept {
  if (std::isnan(fraction)) return 0;
  return static_cast<std::uint8_t>(std::clamp(std::round(fraction * 100.0), 0.0, 100.0));
}

class Writer {
 public:
  void u8(std::uint8_t value) { bytes_.push_back(value); }
  void u16(std::uint16_t value) {
    bytes_.push_back(static_cast<std::uint8_t>(value & 0xFF));
    bytes_.push_back(static_cast<std::uint8_t>(value >> 8));
  }
  void i16(std::int16_t value) { u16(static_cast<std::uint16_t>(value)); }
  std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

/// Reads little-endian fields; every read is bounds-checked by the caller's length checks first, and
/// here again (a failed read returns 0 and marks the reader bad, never reading past the end).
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  std::uint8_t u8() {
    if (at_ + 1 > bytes_.size()) {
      bad_ = true;
      return 0;
    }
    return bytes_[at_++];
  }
  std::uint16_t u16() {
    const std::uint16_t low = u8();
    const std::uint16_t high = u8();
    return static_cast<std::uint16_t>(low | (high << 8));
  }
  std::int16_t i16() { return static_cast<std::int16_t>(u16()); }
  bool bad() const { return bad_; }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
  bool bad_ = false;
};

std::string hex16(std::uint16_t value) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text = "0x";
  for (int shift = 12; shift >= 0; shift -= 4) text += kDigits[(value >> shift) & 0xF];
  return text;
}

void write_header(Writer& out, FrameType type, std::uint16_t sequence, std::size_t payload_bytes) {
  out.u8(kSync0);
  out.u8(kSync1);
  out.u8(kVersion);
  out.u8(static_cast<std::uint8_t>(type));
  out.u16(sequence);
  out.u8(static_cast<std::uint8_t>(payload_bytes));
}

std::vector<std::uint8_t> finish(Writer& out) {
  const std::uint16_t crc = crc16_ccitt(out.bytes());
  out.u16(crc);
  return std::move(out.bytes());
}

Result<CommandFrame> decode_command_payload(std::uint16_t sequence, std::span<const std::uint8_t> payload) {
  if (payload.empty()) return Error{"radio command frame: empty payload (expected a robot count)"};
  Reader in(payload);
  const std::size_t count = in.u8();
  if (count > kMaxRecords) {
    return Error{"radio command frame: " + std::to_string(count) + " robots, more than " +
                 std::to_string(kMaxRecords)};
  }
  const std::size_t expected = 1 + count * kCommandRecordBytes;
  if (payload.size() != expected) {
    return Error{"radio command frame: payload of " + std::to_string(payload.size()) + " bytes for " +
                 std::to_string(count) + " robots (expected " + std::to_string(expected) + ")"};
  }
  CommandFrame frame;
  frame.sequence = sequence;
  for (std::size_t i = 0; i < count; ++i) {
    CommandRecord record;
    RobotCommand& command = record.command;
    command.id = in.u8();
    command.forward = in.i16() / kVelocityScale;
    command.left = in.i16() / kVelocityScale;
    command.angular = in.i16() / kAngularScale;
    const std::uint8_t flags = in.u8();
    command.kick_speed = in.u16() / kKickSpeedScale;
    command.chip_angle = in.u16() / kChipAngleScale;
    command.dribbler_rpm = in.u16();
    if (command.id >= kMaxRobots) {
      return Error{"radio command frame: robot id " + std::to_string(command.id) + " is outside 0..15"};
    }
    switch (flags & 0x03) {
      case 0: command.kick = KickType::kNone; break;
      case 1: command.kick = KickType::kFlat; break;
      case 2: command.kick = KickType::kChip; break;
      default:
        return Error{"radio command frame: robot " + std::to_string(command.id) +
                     " has kick type 3 (invalid)"};
    }
    if ((flags & 0xF8) != 0) {
      return Error{"radio command frame: robot " + std::to_string(command.id) +
                   " has reserved flag bits set"};
    }
    record.stop = (flags & 0x04) != 0;
    frame.robots.push_back(record);
  }
  if (in.bad()) return Error{"radio command frame: truncated payload"};
  return frame;
}

Result<StatusFrame> decode_status_payload(std::uint16_t sequence, std::span<const std::uint8_t> payload) {
  if (payload.empty()) return Error{"radio status frame: empty payload (expected a robot count)"};
  Reader in(payload);
  const std::size_t count = in.u8();
  if (count > kMaxRecords) {
    return Error{"radio status frame: " + std::to_string(count) + " robots, more than " +
                 std::to_string(kMaxRecords)};
  }
  const std::size_t expected = 1 + count * kStatusRecordBytes;
  if (payload.size() != expected) {
    return Error{"radio status frame: payload of " + std::to_string(payload.size()) + " bytes for " +
                 std::to_string(count) + " robots (expected " + std::to_string(expected) + ")"};
  }
  StatusFrame frame;
  frame.sequence = sequence;
  for (std::size_t i = 0; i < count; ++i) {
    StatusRecord record;
    record.robot_id = in.u8();
    const std::uint8_t flags = in.u8();
    const std::uint16_t millivolts = in.u16();
    const std::uint8_t kicker_percent = in.u8();
    const std::uint8_t link_percent = in.u8();
    record.last_command_sequence = in.u16();
    const std::string robot = "radio status frame: robot " + std::to_string(record.robot_id);
    if (record.robot_id >= kMaxRobots) {
      return Error{"radio status frame: robot id " + std::to_string(record.robot_id) + " is outside 0..15"};
    }
    if ((flags & 0xF0) != 0) return Error{robot + " has reserved flag bits set"};
    if (kicker_percent > 100)
      return Error{robot + ": kicker charge " + std::to_string(kicker_percent) + "% > 100%"};
    if (link_percent > 100)
      return Error{robot + ": link quality " + std::to_string(link_percent) + "% > 100%"};
    record.ball_in_dribbler = (flags & 0x01) != 0;
    if ((flags & 0x02) != 0) record.battery_voltage = millivolts / kBatteryScale;
    if ((flags & 0x04) != 0) record.kicker_charge = kicker_percent / 100.0;
    if ((flags & 0x08) != 0) record.link_quality = link_percent / 100.0;
    frame.robots.push_back(record);
  }
  if (in.bad()) return Error{"radio status frame: truncated payload"};
  return frame;
}

}  // namespace

std::uint16_t crc16_ccitt(std::span<const std::uint8_t> bytes) noexcept {
  std::uint16_t crc = 0xFFFF;
  for (const std::uint8_t byte : bytes) {
    crc = static_cast<std::uint16_t>(crc ^ (static_cast<std::uint16_t>(byte) << 8));
    for (int bit = 0; bit < 8; ++bit) {
      crc = (crc & 0x8000) != 0 ? static_cast<std::uint16_t>((crc << 1) ^ 0x1021)
                                : static_cast<std::uint16_t>(crc << 1);
    }
  }
  return crc;
}

Result<std::vector<std::uint8_t>> encode_command_frame(const CommandFrame& frame) {
  if (frame.robots.size() > kMaxRecords) {
    return Error{"radio command frame: " + std::to_string(frame.robots.size()) + " robots, more than " +
                 std::to_string(kMaxRecords)};
  }
  Writer out;
  write_header(out, FrameType::kCommand, frame.sequence, 1 + frame.robots.size() * kCommandRecordBytes);
  out.u8(static_cast<std::uint8_t>(frame.robots.size()));
  for (const CommandRecord& record : frame.robots) {
    const RobotCommand& command = record.command;
    if (command.id >= kMaxRobots) {
      return Error{"radio command frame: robot id " + std::to_string(command.id) + " is outside 0..15"};
    }
    out.u8(static_cast<std::uint8_t>(command.id));
    out.i16(to_fixed<std::int16_t>(command.forward, kVelocityScale));
    out.i16(to_fixed<std::int16_t>(command.left, kVelocityScale));
    out.i16(to_fixed<std::int16_t>(command.angular, kAngularScale));
    std::uint8_t flags = 0;
    if (command.kick == KickType::kFlat) flags = 1;
    if (command.kick == KickType::kChip) flags = 2;
    if (record.stop) flags |= 0x04;
    out.u8(flags);
    out.u16(to_fixed<std::uint16_t>(command.kick_speed, kKickSpeedScale));
    out.u16(to_fixed<std::uint16_t>(command.chip_angle, kChipAngleScale));
    out.u16(to_fixed<std::uint16_t>(command.dribbler_rpm, 1.0));
  }
  return finish(out);
}

Result<std::vector<std::uint8_t>> encode_status_frame(const StatusFrame& frame) {
  if (frame.robots.size() > kMaxRecords) {
    return Error{"radio status frame: " + std::to_string(frame.robots.size()) + " robots, more than " +
                 std::to_string(kMaxRecords)};
  }
  Writer out;
  write_header(out, FrameType::kStatus, frame.sequence, 1 + frame.robots.size() * kStatusRecordBytes);
  out.u8(static_cast<std::uint8_t>(frame.robots.size()));
  for (const StatusRecord& record : frame.robots) {
    if (record.robot_id >= kMaxRobots) {
      return Error{"radio status frame: robot id " + std::to_string(record.robot_id) + " is outside 0..15"};
    }
    std::uint8_t flags = record.ball_in_dribbler ? 0x01 : 0x00;
    if (record.battery_voltage) flags |= 0x02;
    if (record.kicker_charge) flags |= 0x04;
    if (record.link_quality) flags |= 0x08;
    out.u8(static_cast<std::uint8_t>(record.robot_id));
    out.u8(flags);
    out.u16(to_fixed<std::uint16_t>(record.battery_voltage.value_or(0), kBatteryScale));
    out.u8(to_percent(record.kicker_charge.value_or(0)));
    out.u8(to_percent(record.link_quality.value_or(0)));
    out.u16(record.last_command_sequence);
  }
  return finish(out);
}

Result<RadioFrame> decode_frame(std::span<const std::uint8_t> bytes) {
  const std::string size = std::to_string(bytes.size()) + " bytes";
  if (bytes.size() < kMinFrameBytes) {
    return Error{"radio frame: " + size + ", shorter than the " + std::to_string(kMinFrameBytes) +
                 "-byte minimum"};
  }
  if (bytes[0] != kSync0 || bytes[1] != kSync1)
    return Error{"radio frame: " + size + " without the sync word A5 5A"};
  const std::size_t payload_bytes = bytes[6];
  const std::size_t expected = kHeaderBytes + payload_bytes + kCrcBytes;
  if (bytes.size() != expected) {
    return Error{"radio frame: " + size + " but its length field announces " + std::to_string(expected)};
  }
  const std::uint16_t crc_wire = static_cast<std::uint16_t>(
      bytes[expected - 2] | (static_cast<std::uint16_t>(bytes[expected - 1]) << 8));
  const std::uint16_t crc = crc16_ccitt(bytes.first(expected - kCrcBytes));
  if (crc != crc_wire) {
    return Error{"radio frame: CRC mismatch (frame says " + hex16(crc_wire) + ", bytes give " + hex16(crc) +
                 ")"};
  }
  if (bytes[2] != kVersion) return Error{"radio frame: unsupported version " + std::to_string(bytes[2])};
  const std::uint16_t sequence =
      static_cast<std::uint16_t>(bytes[4] | (static_cast<std::uint16_t>(bytes[5]) << 8));
  const std::span<const std::uint8_t> payload = bytes.subspan(kHeaderBytes, payload_bytes);
  switch (bytes[3]) {
    case static_cast<std::uint8_t>(FrameType::kCommand): {
      auto frame = decode_command_payload(sequence, payload);
      if (!frame) return frame.error();
      return RadioFrame{std::move(*frame)};
    }
    case static_cast<std::uint8_t>(FrameType::kStatus): {
      auto frame = decode_status_payload(sequence, payload);
      if (!frame) return frame.error();
      return RadioFrame{std::move(*frame)};
    }
    default: return Error{"radio frame: unknown frame type " + std::to_string(bytes[3])};
  }
}

std::vector<RadioFrame> FrameAssembler::push(std::span<const std::uint8_t> bytes) {
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
  std::vector<RadioFrame> frames;
  std::size_t start = 0;  // bytes before `start` are consumed
  while (true) {
    // Find the next sync word (a trailing A5 may be the start of one).
    std::size_t at = start;
    while (at < buffer_.size() &&
           !(buffer_[at] == kSync0 && (at + 1 == buffer_.size() || buffer_[at + 1] == kSync1))) {
      ++at;
    }
    skipped_bytes_ += at - start;
    start = at;
    if (buffer_.size() - start < kHeaderBytes) break;
    const std::size_t total = kHeaderBytes + buffer_[start + 6] + kCrcBytes;
    if (buffer_.size() - start < total) break;
    auto frame = decode_frame(std::span(buffer_).subspan(start, total));
    if (frame) {
      ++frames_;
      frames.push_back(std::move(*frame));
      start += total;
    } else {
      ++bad_frames_;
      ++skipped_bytes_;
      start += 1;  // resynchronise after this false or corrupt sync word
    }
  }
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start));
  return frames;
}

}  // namespace ssl::robot_link::radio
