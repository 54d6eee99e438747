// libFuzzer target: feeds each input to every datagram decoder and, as an in-memory log file, to the
// log reader. Any crash, sanitizer report or leak is a bug. Build with -DSSL_FUZZ=ON (clang) and run
//   build/fuzz/league_decode_fuzz -max_total_time=60
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "libs/league/decode.h"
#include "libs/league/log_file.h"

namespace {

template <typename Decoded>
void consume(const Decoded& decoded) {
  // Touch the result so that neither branch is optimised away.
  if (decoded.ok()) {
    volatile std::size_t size = decoded->ByteSizeLong();
    (void)size;
  } else {
    volatile std::size_t length = decoded.error().message.size();
    (void)length;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ssl::league;
  const std::span<const std::uint8_t> bytes(data, size);
  consume(decode_vision_wrapper(bytes));
  consume(decode_legacy_vision_wrapper(bytes));
  consume(decode_referee(bytes));
  consume(decode_tracker_wrapper(bytes));
  consume(decode_simulator_command(bytes));
  consume(decode_simulator_response(bytes));
  consume(decode_robot_control(bytes));
  consume(decode_robot_control_response(bytes));
  consume(decode_grsim_packet(bytes));
  consume(decode_grsim_robots_status(bytes));

  // The same bytes as the records of a log file (behind a valid header), and as a whole file.
  std::string with_header(kLogFileMagic);
  with_header.append("\x00\x00\x00\x01", 4);
  with_header.append(reinterpret_cast<const char*>(data), size);
  for (std::string file : {with_header, std::string(reinterpret_cast<const char*>(data), size)}) {
    auto reader = LogReader::from_bytes(std::move(file));
    if (!reader) {
      continue;
    }
    for (;;) {
      auto record = reader->next();
      if (!record || !*record) {
        break;
      }
    }
  }
  return 0;
}
