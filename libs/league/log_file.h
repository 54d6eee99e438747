// The league's SSL log file format (ssl-go-tools recorder, ssl-logtools): a 16-byte header
// ("SSL_LOG_FILE" + big-endian int32 version 1) followed by records of big-endian int64 receive time
// in NANOSECONDS since the Unix epoch, int32 message type, int32 payload size N and N payload bytes
// (one datagram exactly as received). Files may be gzip-compressed (`.log.gz`). An uncompressed file
// may end with an INDEX_2021 record listing the absolute file offset of every other record.
//
// Contract: the reader never crashes or throws on a damaged file. A wrong header, an unsupported
// version, a negative size, a truncated record or corrupt gzip data each yield an ssl::Error naming
// the file and the byte offset; after an error the reader keeps returning it. The writer reports I/O
// failures as errors. Neither is thread-safe; use one object per thread.
//
//   auto reader = LogReader::open("match.log.gz");
//   if (!reader) return fail(reader.error());
//   for (;;) {
//     auto record = reader->next();
//     if (!record) return fail(record.error());
//     if (!*record) break;  // clean end of file
//     if ((*record)->type == MessageType::kVision2014) {
//       use(decode_vision_wrapper(byte_span((*record)->payload)));
//     }
//   }
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "libs/common/result.h"

namespace ssl::league {

/// Record type numbers of the log format. Values outside this list can occur in files written by
/// newer tools; the reader passes them through unchanged.
enum class MessageType : std::int32_t {
  kBlank = 0,              // ignore
  kUnknown = 1,            // payload type unknown, guess by parsing
  kVision2010 = 2,         // RoboCup2014Legacy::Wrapper::SSL_WrapperPacket (port 10005)
  kRefbox2013 = 3,         // Referee (port 10003)
  kVision2014 = 4,         // SSL_WrapperPacket (port 10006)
  kVisionTracker2020 = 5,  // TrackerWrapperPacket (port 10010)
  kIndex2021 = 6,          // index trailer (uncompressed files only)
};

/// The league's name of a type ("SSL_VISION_2014"), or "TYPE_<n>" for numbers outside the table.
std::string to_string(MessageType type);

inline constexpr std::string_view kLogFileMagic = "SSL_LOG_FILE";
inline constexpr std::int32_t kLogFileVersion = 1;
inline constexpr std::size_t kLogHeaderBytes = 16;
inline constexpr std::size_t kLogRecordHeaderBytes = 16;

struct LogRecord {
  std::int64_t timestamp_ns = 0;  // receive time, ns since the Unix epoch
  MessageType type = MessageType::kBlank;
  std::string payload;      // raw protobuf bytes; view with byte_span() from decode.h
  std::int64_t offset = 0;  // offset of the record header in the uncompressed stream
};

enum class Compression {
  kBySuffix,  // gzip when the path ends in ".gz"
  kNone,
  kGzip,
};

class LogWriter {
 public:
  struct Options {
    Compression compression = Compression::kBySuffix;
    /// Append an INDEX_2021 trailer on close(); only for uncompressed files.
    bool write_index = false;
  };

  /// Creates (truncates) the file and writes the header.
  static Result<LogWriter> open(const std::filesystem::path& path, Options options);
  static Result<LogWriter> open(const std::filesystem::path& path) { return open(path, Options{}); }

  LogWriter(LogWriter&&) noexcept;
  LogWriter& operator=(LogWriter&&) noexcept;
  ~LogWriter();  // closes the file if close() was not called; errors are then lost

  /// Appends one record. Payloads larger than INT32_MAX bytes are rejected.
  Status write(std::int64_t timestamp_ns, MessageType type, std::span<const std::uint8_t> payload);
  Status write(std::int64_t timestamp_ns, MessageType type, std::string_view payload);

  /// Writes the index (if asked), flushes and closes. Later writes fail.
  Status close();

  std::uint64_t records_written() const noexcept;

 private:
  struct Impl;
  explicit LogWriter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

class LogReader {
 public:
  /// Opens a log file and checks its header; gzip is recognised by its magic bytes, whatever the name.
  static Result<LogReader> open(const std::filesystem::path& path);
  /// Reads an uncompressed log held in memory (e.g. for tests and fuzzing).
  static Result<LogReader> from_bytes(std::string bytes);

  LogReader(LogReader&&) noexcept;
  LogReader& operator=(LogReader&&) noexcept;
  ~LogReader();

  /// The next record; std::nullopt at the clean end of the data; an Error on damaged data.
  /// The INDEX_2021 trailer, if present, is returned like any other record.
  Result<std::optional<LogRecord>> next();

  /// Continues reading at `offset` (e.g. one from read_log_index). Slow for gzip files.
  Status seek(std::int64_t offset);

 private:
  struct Impl;
  explicit LogReader(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Reads the INDEX_2021 trailer of an uncompressed log file: the absolute offsets of the records it
/// lists, in file order. Fails with a clear error when the file has no (or a damaged) index.
Result<std::vector<std::int64_t>> read_log_index(const std::filesystem::path& path);

}  // namespace ssl::league
