// Test-only protobuf wire encoder, written from the encoding rules alone (no protobuf library code), so
// that tests can compare what the generated classes emit with bytes computed by hand from the league's
// field tables: tag = (field << 3) | wire type; varint; zigzag for sint; little-endian fixed32 (float)
// and fixed64 (double); length-delimited strings, bytes, sub-messages and packed repeated varints.
//
//   HandEncoder point;  point.f32(1, -1500.0f).f32(2, 2250.5f);
//   HandEncoder referee;  referee.message(9, point);   // designated_position
#pragma once

#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <string>
#include <string_view>

namespace ssl::league::testing {

class HandEncoder {
 public:
  enum WireType : std::uint32_t { kVarint = 0, kFixed64 = 1, kLengthDelimited = 2, kFixed32 = 5 };

  /// uint32, uint64, bool and non-negative enum values.
  HandEncoder& varint(std::uint32_t field, std::uint64_t value) {
    tag(field, kVarint);
    raw_varint(value);
    return *this;
  }
  /// int32 and int64 (and negative enums): negative values are sign-extended to ten bytes.
  HandEncoder& int64(std::uint32_t field, std::int64_t value) {
    return varint(field, static_cast<std::uint64_t>(value));
  }
  /// sint32 and sint64: zigzag, so small negative numbers stay short.
  HandEncoder& sint(std::uint32_t field, std::int64_t value) {
    const auto bits = static_cast<std::uint64_t>(value);
    return varint(field, (bits << 1) ^ (value < 0 ? ~std::uint64_t{0} : std::uint64_t{0}));
  }
  HandEncoder& f32(std::uint32_t field, float value) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    tag(field, kFixed32);
    little_endian(bits, 4);
    return *this;
  }
  HandEncoder& f64(std::uint32_t field, double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    tag(field, kFixed64);
    little_endian(bits, 8);
    return *this;
  }
  /// string and bytes.
  HandEncoder& bytes(std::uint32_t field, std::string_view value) {
    tag(field, kLengthDelimited);
    raw_varint(value.size());
    out_.append(value);
    return *this;
  }
  HandEncoder& message(std::uint32_t field, const HandEncoder& sub) { return bytes(field, sub.str()); }
  /// A packed repeated varint field (omitted by protobuf when empty; so is it here).
  HandEncoder& packed_varints(std::uint32_t field, std::initializer_list<std::uint64_t> values) {
    if (values.size() == 0) {
      return *this;
    }
    HandEncoder body;
    for (const std::uint64_t value : values) {
      body.raw_varint(value);
    }
    return bytes(field, body.str());
  }

  const std::string& str() const { return out_; }

 private:
  void tag(std::uint32_t field, WireType type) { raw_varint((std::uint64_t{field} << 3) | type); }
  void raw_varint(std::uint64_t value) {
    while (value >= 0x80) {
      out_.push_back(static_cast<char>((value & 0x7F) | 0x80));
      value >>= 7;
    }
    out_.push_back(static_cast<char>(value));
  }
  void little_endian(std::uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) {
      out_.push_back(static_cast<char>((value >> (8 * i)) & 0xFF));
    }
  }

  std::string out_;
};

/// "08 96 01" style rendering, so that a failed comparison shows where the bytes differ.
inline std::string hex(std::string_view bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text;
  for (const char c : bytes) {
    const auto byte = static_cast<unsigned char>(c);
    if (!text.empty()) {
      text.push_back(' ');
    }
    text.push_back(kDigits[byte >> 4]);
    text.push_back(kDigits[byte & 0x0F]);
  }
  return text;
}

}  // namespace ssl::league::testing
