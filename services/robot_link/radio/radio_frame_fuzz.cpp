// libFuzzer target: feeds each input to the radio frame decoder, as one frame and as a serial byte stream
// cut into pieces (the radio backend's path). Bad input must give an error, never a crash, a sanitizer
// report or a leak. Beyond that it checks what the codec promises of every frame it accepts:
// - the frame re-encodes, and decoding that gives back the same frame (decoded values are exact wire
//   steps, so nothing drifts);
// - a command frame re-encodes to the very bytes it came from (every bit of it is meaningful: reserved
//   bits must be zero, every field an integer);
// - a stream holding exactly one valid frame yields exactly that frame, however it is cut.
// Seeds: tests/fuzz/corpus/radio_frame_decode_fuzz. Run with tests/fuzz/run.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <variant>
#include <vector>

#include "services/robot_link/radio/radio_frame.h"

namespace {

using namespace ssl::robot_link::radio;

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "radio_frame_decode_fuzz: %s\n", what);
  std::abort();
}

std::vector<std::uint8_t> encode(const RadioFrame& frame) {
  auto bytes = std::holds_alternative<CommandFrame>(frame)
                   ? encode_command_frame(std::get<CommandFrame>(frame))
                   : encode_status_frame(std::get<StatusFrame>(frame));
  if (!bytes) fail("a decoded frame does not encode again");
  return std::move(*bytes);
}

/// The bytes of an accepted frame re-encoded; aborts when the round trip is not stable.
std::vector<std::uint8_t> check_round_trip(const RadioFrame& frame) {
  std::vector<std::uint8_t> bytes = encode(frame);
  auto again = decode_frame(bytes);
  if (!again) fail("the re-encoding of a decoded frame does not decode");
  if (encode(*again) != bytes) fail("decode -> encode -> decode changed the frame");
  return bytes;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> input(data, size);

  auto frame = decode_frame(input);
  if (frame) {
    const std::vector<std::uint8_t> bytes = check_round_trip(*frame);
    if (std::holds_alternative<CommandFrame>(*frame) && !std::ranges::equal(bytes, input)) {
      fail("a command frame does not re-encode to its own bytes");
    }
  }

  // The same bytes as a serial line delivers them: in pieces of 1 to 7 bytes.
  FrameAssembler stream;
  std::vector<RadioFrame> frames;
  std::size_t piece = 1;
  for (std::size_t at = 0; at < input.size(); at += piece, piece = piece % 7 + 1) {
    for (RadioFrame& assembled : stream.push(input.subspan(at, std::min(piece, input.size() - at)))) {
      frames.push_back(std::move(assembled));
    }
  }
  if (stream.frames() != frames.size()) fail("the assembler's frame count is off");
  for (const RadioFrame& assembled : frames) check_round_trip(assembled);
  if (frame && (frames.size() != 1 || encode(frames.front()) != encode(*frame))) {
    fail("a stream of one valid frame did not yield exactly that frame");
  }
  return 0;
}
