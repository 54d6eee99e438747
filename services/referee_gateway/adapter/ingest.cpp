#include "services/referee_gateway/adapter/ingest.h"

#include <utility>

#include "libs/league/decode.h"
#include "services/referee_gateway/adapter/convert.h"

namespace ssl::referee {

IngestResult RefereeIngest::handle(std::span<const std::uint8_t> bytes, time::Timestamp receive_wall,
                                   time::Timestamp now) {
  IngestResult result;
  auto decoded = league::decode_referee(bytes);
  if (!decoded) {
    ++malformed_;
    result.malformed = decoded.error();
    return result;
  }
  result.output = core_.on_packet(from_proto(*decoded, receive_wall, source_), now);
  return result;
}

}  // namespace ssl::referee
