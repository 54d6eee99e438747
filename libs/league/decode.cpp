#include "libs/league/decode.h"

#include <google/protobuf/message.h>
#include <google/protobuf/stubs/logging.h>

#include <limits>
#include <string>

namespace ssl::league {
namespace {

std::string describe(const google::protobuf::Message& message, std::size_t byte_count) {
  return message.GetTypeName() + " (" + std::to_string(byte_count) + " bytes)";
}

}  // namespace

Status decode_into(std::span<const std::uint8_t> bytes, google::protobuf::Message& message) {
  message.Clear();
  if (bytes.size() > kMaxDatagramBytes) {
    return Error{describe(message, bytes.size()) + ": larger than the UDP maximum of " +
                 std::to_string(kMaxDatagramBytes) + " bytes, not parsed"};
  }
  static_assert(kMaxDatagramBytes <= static_cast<std::size_t>(std::numeric_limits<int>::max()));
  // Hostile input is expected here and reported through the result: keep protobuf from logging about
  // it (debug builds log every invalid UTF-8 string field).
  const google::protobuf::LogSilencer quiet;
  // Parse without the required-field check so that the check below can name what is missing.
  if (!message.ParsePartialFromArray(bytes.data(), static_cast<int>(bytes.size()))) {
    return Error{describe(message, bytes.size()) +
                 ": malformed protobuf encoding (truncated, corrupt or not this message type)"};
  }
  if (!message.IsInitialized()) {
    return Error{describe(message, bytes.size()) +
                 ": missing required fields: " + message.InitializationErrorString()};
  }
  return Status::success();
}

Result<std::string> encode_datagram(const google::protobuf::Message& message) {
  if (!message.IsInitialized()) {
    return Error{message.GetTypeName() +
                 ": cannot encode, missing required fields: " + message.InitializationErrorString()};
  }
  const std::size_t size = message.ByteSizeLong();
  if (size > kMaxDatagramBytes) {
    return Error{message.GetTypeName() + ": encoding of " + std::to_string(size) +
                 " bytes exceeds the UDP maximum of " + std::to_string(kMaxDatagramBytes) + " bytes"};
  }
  std::string bytes;
  if (!message.SerializePartialToString(&bytes)) {
    return Error{message.GetTypeName() + ": serialization failed"};
  }
  return bytes;
}

}  // namespace ssl::league
