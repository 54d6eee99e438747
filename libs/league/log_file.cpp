#include "libs/league/log_file.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <utility>

namespace ssl::league {
namespace {

constexpr std::string_view kIndexTrailer = "INDEXED";
// Fixed part of the index payload: int64 distance back + "INDEXED".
constexpr std::int64_t kIndexFixedBytes = 8 + static_cast<std::int64_t>(kIndexTrailer.size());
// Payloads are read in slices so that a damaged size field cannot make us allocate gigabytes before
// the missing data is noticed.
constexpr std::size_t kReadSliceBytes = std::size_t{1} << 16;

void put_be(std::string& out, std::uint64_t value, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) {
    out.push_back(static_cast<char>((value >> (8 * i)) & 0xFFU));
  }
}

std::uint64_t get_be(const char* in, int bytes) {
  std::uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) {
    value = (value << 8) | static_cast<unsigned char>(in[i]);
  }
  return value;
}

std::int64_t get_be64(const char* in) {
  return static_cast<std::int64_t>(get_be(in, 8));
}
std::int32_t get_be32(const char* in) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(get_be(in, 4)));
}

std::string errno_text() {
  return std::strerror(errno);
}

bool ends_with_gz(const std::filesystem::path& path) {
  const std::string name = path.filename().string();
  return name.size() >= 3 && name.compare(name.size() - 3, 3, ".gz") == 0;
}

// ---------------------------------------------------------------------------------------------------
// Byte sources and sinks: plain file, gzip file, memory.

class ByteSource {
 public:
  virtual ~ByteSource() = default;
  /// Reads up to n bytes; fewer only at the end of the data.
  virtual Result<std::size_t> read(char* out, std::size_t n) = 0;
  virtual Status seek(std::int64_t offset) = 0;
};

class FileSource final : public ByteSource {
 public:
  explicit FileSource(std::FILE* file) : file_(file) {}
  ~FileSource() override { std::fclose(file_); }
  FileSource(const FileSource&) = delete;
  FileSource& operator=(const FileSource&) = delete;

  Result<std::size_t> read(char* out, std::size_t n) override {
    const std::size_t got = std::fread(out, 1, n, file_);
    if (got < n && std::ferror(file_) != 0) {
      return Error{"read error: " + errno_text()};
    }
    return got;
  }
  Status seek(std::int64_t offset) override {
    if (offset < 0 || fseeko(file_, static_cast<off_t>(offset), SEEK_SET) != 0) {
      return Error{"cannot seek to offset " + std::to_string(offset)};
    }
    return Status::success();
  }

 private:
  std::FILE* file_;
};

class GzipSource final : public ByteSource {
 public:
  explicit GzipSource(gzFile file) : file_(file) {}
  ~GzipSource() override { gzclose(file_); }
  GzipSource(const GzipSource&) = delete;
  GzipSource& operator=(const GzipSource&) = delete;

  Result<std::size_t> read(char* out, std::size_t n) override {
    std::size_t total = 0;
    while (total < n) {
      const auto want = static_cast<unsigned>(std::min<std::size_t>(n - total, kReadSliceBytes));
      const int got = gzread(file_, out + total, want);
      if (got < 0) {
        int code = 0;
        return Error{std::string("gzip data corrupt: ") + gzerror(file_, &code)};
      }
      total += static_cast<std::size_t>(got);
      if (static_cast<unsigned>(got) < want) {
        int code = Z_OK;
        gzerror(file_, &code);
        if (code == Z_BUF_ERROR) {
          return Error{"gzip data truncated (unexpected end of the compressed stream)"};
        }
        break;  // clean end of the stream
      }
    }
    return total;
  }
  Status seek(std::int64_t offset) override {
    if (offset < 0 || gzseek(file_, static_cast<z_off_t>(offset), SEEK_SET) != offset) {
      return Error{"cannot seek to offset " + std::to_string(offset) + " in gzip data"};
    }
    return Status::success();
  }

 private:
  gzFile file_;
};

class MemorySource final : public ByteSource {
 public:
  explicit MemorySource(std::string data) : data_(std::move(data)) {}

  Result<std::size_t> read(char* out, std::size_t n) override {
    const std::size_t got = std::min(n, data_.size() - position_);
    std::memcpy(out, data_.data() + position_, got);
    position_ += got;
    return got;
  }
  Status seek(std::int64_t offset) override {
    if (offset < 0 || static_cast<std::uint64_t>(offset) > data_.size()) {
      return Error{"cannot seek to offset " + std::to_string(offset) + " of " + std::to_string(data_.size()) +
                   " bytes"};
    }
    position_ = static_cast<std::size_t>(offset);
    return Status::success();
  }

 private:
  std::string data_;
  std::size_t position_ = 0;
};

class ByteSink {
 public:
  virtual ~ByteSink() = default;
  virtual Status write(const char* data, std::size_t n) = 0;
  virtual Status close() = 0;
};

class FileSink final : public ByteSink {
 public:
  explicit FileSink(std::FILE* file) : file_(file) {}
  ~FileSink() override {
    if (file_ != nullptr) {
      std::fclose(file_);
    }
  }
  FileSink(const FileSink&) = delete;
  FileSink& operator=(const FileSink&) = delete;

  Status write(const char* data, std::size_t n) override {
    if (std::fwrite(data, 1, n, file_) != n) {
      return Error{"write error: " + errno_text()};
    }
    return Status::success();
  }
  Status close() override {
    std::FILE* file = std::exchange(file_, nullptr);
    if (std::fclose(file) != 0) {
      return Error{"close error: " + errno_text()};
    }
    return Status::success();
  }

 private:
  std::FILE* file_;
};

class GzipSink final : public ByteSink {
 public:
  explicit GzipSink(gzFile file) : file_(file) {}
  ~GzipSink() override {
    if (file_ != nullptr) {
      gzclose(file_);
    }
  }
  GzipSink(const GzipSink&) = delete;
  GzipSink& operator=(const GzipSink&) = delete;

  Status write(const char* data, std::size_t n) override {
    while (n > 0) {
      const auto chunk = static_cast<unsigned>(std::min<std::size_t>(n, kReadSliceBytes));
      if (gzwrite(file_, data, chunk) != static_cast<int>(chunk)) {
        int code = 0;
        return Error{std::string("gzip write error: ") + gzerror(file_, &code)};
      }
      data += chunk;
      n -= chunk;
    }
    return Status::success();
  }
  Status close() override {
    if (gzclose(std::exchange(file_, nullptr)) != Z_OK) {
      return Error{"gzip close error (data may be incomplete)"};
    }
    return Status::success();
  }

 private:
  gzFile file_;
};

Result<std::unique_ptr<ByteSource>> open_source(const std::filesystem::path& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) {
    return Error{"cannot open: " + errno_text()};
  }
  std::array<unsigned char, 2> magic{};
  const std::size_t got = std::fread(magic.data(), 1, magic.size(), file);
  const bool gzip = got == magic.size() && magic[0] == 0x1F && magic[1] == 0x8B;
  if (!gzip) {
    std::rewind(file);
    return std::unique_ptr<ByteSource>(std::make_unique<FileSource>(file));
  }
  std::fclose(file);
  gzFile gz = gzopen(path.c_str(), "rb");
  if (gz == nullptr) {
    return Error{"cannot open gzip file: " + errno_text()};
  }
  gzbuffer(gz, 1U << 16);
  return std::unique_ptr<ByteSource>(std::make_unique<GzipSource>(gz));
}

Result<std::unique_ptr<ByteSink>> open_sink(const std::filesystem::path& path, bool gzip) {
  if (gzip) {
    gzFile gz = gzopen(path.c_str(), "wb");
    if (gz == nullptr) {
      return Error{"cannot create gzip file: " + errno_text()};
    }
    gzbuffer(gz, 1U << 16);
    return std::unique_ptr<ByteSink>(std::make_unique<GzipSink>(gz));
  }
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    return Error{"cannot create: " + errno_text()};
  }
  return std::unique_ptr<ByteSink>(std::make_unique<FileSink>(file));
}

std::string record_header(std::int64_t timestamp_ns, std::int32_t type, std::int32_t size) {
  std::string header;
  header.reserve(kLogRecordHeaderBytes);
  put_be(header, static_cast<std::uint64_t>(timestamp_ns), 8);
  put_be(header, static_cast<std::uint32_t>(type), 4);
  put_be(header, static_cast<std::uint32_t>(size), 4);
  return header;
}

std::string describe_path(const std::filesystem::path& path) {
  return "log file '" + path.string() + "'";
}

}  // namespace

std::string to_string(MessageType type) {
  switch (type) {
    case MessageType::kBlank: return "BLANK";
    case MessageType::kUnknown: return "UNKNOWN";
    case MessageType::kVision2010: return "SSL_VISION_2010";
    case MessageType::kRefbox2013: return "SSL_REFBOX_2013";
    case MessageType::kVision2014: return "SSL_VISION_2014";
    case MessageType::kVisionTracker2020: return "SSL_VISION_TRACKER_2020";
    case MessageType::kIndex2021: return "INDEX_2021";
  }
  return "TYPE_" + std::to_string(static_cast<std::int32_t>(type));
}

// ---------------------------------------------------------------------------------------------------
// Writer

struct LogWriter::Impl {
  std::string name;  // for error messages
  std::unique_ptr<ByteSink> sink;
  bool write_index = false;
  bool closed = false;
  std::int64_t position = 0;
  std::vector<std::int64_t> offsets;
  std::uint64_t records = 0;

  Status put(const std::string& bytes) { return put(bytes.data(), bytes.size()); }
  Status put(const char* data, std::size_t n) {
    if (Status status = sink->write(data, n); !status) {
      return Error{name + ": " + status.error().message};
    }
    position += static_cast<std::int64_t>(n);
    return Status::success();
  }
};

LogWriter::LogWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
LogWriter::LogWriter(LogWriter&&) noexcept = default;
LogWriter& LogWriter::operator=(LogWriter&&) noexcept = default;
LogWriter::~LogWriter() {
  if (impl_ && !impl_->closed) {
    (void)close();
  }
}

Result<LogWriter> LogWriter::open(const std::filesystem::path& path, Options options) {
  const bool gzip = options.compression == Compression::kGzip ||
                    (options.compression == Compression::kBySuffix && ends_with_gz(path));
  if (gzip && options.write_index) {
    return Error{describe_path(path) + ": an index can only be written to uncompressed files"};
  }
  auto sink = open_sink(path, gzip);
  if (!sink) {
    return Error{describe_path(path) + ": " + sink.error().message};
  }
  auto impl = std::make_unique<Impl>();
  impl->name = describe_path(path);
  impl->sink = std::move(*sink);
  impl->write_index = options.write_index;
  std::string header(kLogFileMagic);
  put_be(header, static_cast<std::uint32_t>(kLogFileVersion), 4);
  if (Status status = impl->put(header); !status) {
    return status.error();
  }
  return LogWriter(std::move(impl));
}

Status LogWriter::write(std::int64_t timestamp_ns, MessageType type, std::span<const std::uint8_t> payload) {
  if (impl_->closed) {
    return Error{impl_->name + ": write after close"};
  }
  if (payload.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    return Error{impl_->name + ": payload of " + std::to_string(payload.size()) +
                 " bytes does not fit the int32 size field"};
  }
  const std::int64_t offset = impl_->position;
  if (Status status = impl_->put(record_header(timestamp_ns, static_cast<std::int32_t>(type),
                                               static_cast<std::int32_t>(payload.size())));
      !status) {
    return status;
  }
  if (Status status = impl_->put(reinterpret_cast<const char*>(payload.data()), payload.size()); !status) {
    return status;
  }
  if (impl_->write_index) {
    impl_->offsets.push_back(offset);
  }
  ++impl_->records;
  return Status::success();
}

Status LogWriter::write(std::int64_t timestamp_ns, MessageType type, std::string_view payload) {
  return write(
      timestamp_ns, type,
      std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(payload.data()), payload.size()));
}

Status LogWriter::close() {
  if (impl_->closed) {
    return Status::success();
  }
  impl_->closed = true;
  Status index_status;
  if (impl_->write_index) {
    const auto count = static_cast<std::int64_t>(impl_->offsets.size());
    const std::int64_t payload_size = 8 * count + kIndexFixedBytes;
    if (payload_size > std::numeric_limits<std::int32_t>::max()) {
      index_status = Error{impl_->name + ": too many records for an index"};
    } else {
      std::string index = record_header(0, static_cast<std::int32_t>(MessageType::kIndex2021),
                                        static_cast<std::int32_t>(payload_size));
      for (const std::int64_t offset : impl_->offsets) {
        put_be(index, static_cast<std::uint64_t>(offset), 8);
      }
      put_be(index,
             static_cast<std::uint64_t>(static_cast<std::int64_t>(kLogRecordHeaderBytes) + payload_size), 8);
      index.append(kIndexTrailer);
      index_status = impl_->put(index);
    }
  }
  Status close_status = impl_->sink->close();
  if (!index_status) {
    return index_status;
  }
  if (!close_status) {
    return Error{impl_->name + ": " + close_status.error().message};
  }
  return Status::success();
}

std::uint64_t LogWriter::records_written() const noexcept {
  return impl_->records;
}

// ---------------------------------------------------------------------------------------------------
// Reader

struct LogReader::Impl {
  std::string name;  // for error messages
  std::unique_ptr<ByteSource> source;
  std::int64_t position = 0;  // offset in the uncompressed stream
  std::optional<Error> failure;

  Error fail(std::string what) {
    failure = Error{name + ": " + std::move(what)};
    return *failure;
  }

  /// Reads exactly n bytes unless the data ends first; returns the count read.
  Result<std::size_t> read(char* out, std::size_t n) {
    auto got = source->read(out, n);
    if (!got) {
      return fail("at offset " + std::to_string(position) + ": " + got.error().message);
    }
    position += static_cast<std::int64_t>(*got);
    return *got;
  }

  Status check_header() {
    std::array<char, kLogHeaderBytes> header{};
    auto got = read(header.data(), header.size());
    if (!got) {
      return got.error();
    }
    if (*got < header.size()) {
      return fail("too short for the " + std::to_string(kLogHeaderBytes) + "-byte header (" +
                  std::to_string(*got) + " bytes)");
    }
    if (std::string_view(header.data(), kLogFileMagic.size()) != kLogFileMagic) {
      return fail("not an SSL log file: does not start with \"SSL_LOG_FILE\"");
    }
    const std::int32_t version = get_be32(header.data() + kLogFileMagic.size());
    if (version != kLogFileVersion) {
      return fail("unsupported log format version " + std::to_string(version) + " (only " +
                  std::to_string(kLogFileVersion) + " is supported)");
    }
    return Status::success();
  }

  static Result<LogReader> make(std::string name, std::unique_ptr<ByteSource> source) {
    auto impl = std::make_unique<Impl>();
    impl->name = std::move(name);
    impl->source = std::move(source);
    if (Status status = impl->check_header(); !status) {
      return status.error();
    }
    return LogReader(std::move(impl));
  }
};

LogReader::LogReader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
LogReader::LogReader(LogReader&&) noexcept = default;
LogReader& LogReader::operator=(LogReader&&) noexcept = default;
LogReader::~LogReader() = default;

Result<LogReader> LogReader::open(const std::filesystem::path& path) {
  auto source = open_source(path);
  if (!source) {
    return Error{describe_path(path) + ": " + source.error().message};
  }
  return Impl::make(describe_path(path), std::move(*source));
}

Result<LogReader> LogReader::from_bytes(std::string bytes) {
  return Impl::make("log data", std::make_unique<MemorySource>(std::move(bytes)));
}

Result<std::optional<LogRecord>> LogReader::next() {
  Impl& self = *impl_;
  if (self.failure) {
    return *self.failure;
  }
  LogRecord record;
  record.offset = self.position;
  std::array<char, kLogRecordHeaderBytes> header{};
  auto got = self.read(header.data(), header.size());
  if (!got) {
    return got.error();
  }
  if (*got == 0) {
    return std::optional<LogRecord>();
  }
  const std::string where = "record at offset " + std::to_string(record.offset);
  if (*got < header.size()) {
    return self.fail(where + ": truncated record header (" + std::to_string(*got) + " of " +
                     std::to_string(kLogRecordHeaderBytes) + " bytes)");
  }
  record.timestamp_ns = get_be64(header.data());
  record.type = static_cast<MessageType>(get_be32(header.data() + 8));
  const std::int32_t size = get_be32(header.data() + 12);
  if (size < 0) {
    return self.fail(where + ": negative payload size " + std::to_string(size));
  }
  auto remaining = static_cast<std::size_t>(size);
  while (remaining > 0) {
    const std::size_t slice = std::min(remaining, kReadSliceBytes);
    const std::size_t old_size = record.payload.size();
    record.payload.resize(old_size + slice);
    auto slice_got = self.read(record.payload.data() + old_size, slice);
    if (!slice_got) {
      return slice_got.error();
    }
    if (*slice_got < slice) {
      return self.fail(where + ": truncated payload (" + std::to_string(old_size + *slice_got) + " of " +
                       std::to_string(size) + " bytes present)");
    }
    remaining -= slice;
  }
  return std::optional<LogRecord>(std::move(record));
}

Status LogReader::seek(std::int64_t offset) {
  Impl& self = *impl_;
  if (Status status = self.source->seek(offset); !status) {
    return Error{self.name + ": " + status.error().message};
  }
  self.position = offset;
  self.failure.reset();
  return Status::success();
}

// ---------------------------------------------------------------------------------------------------
// Index

Result<std::vector<std::int64_t>> read_log_index(const std::filesystem::path& path) {
  const std::string name = describe_path(path);
  std::error_code error;
  const std::uintmax_t file_size = std::filesystem::file_size(path, error);
  if (error) {
    return Error{name + ": " + error.message()};
  }
  std::FILE* raw = std::fopen(path.c_str(), "rb");
  if (raw == nullptr) {
    return Error{name + ": cannot open: " + errno_text()};
  }
  FileSource source(raw);
  auto read_at = [&](std::int64_t offset, char* out, std::size_t n) -> Status {
    if (Status status = source.seek(offset); !status) {
      return status;
    }
    auto got = source.read(out, n);
    if (!got) {
      return got.error();
    }
    if (*got != n) {
      return Error{"short read at offset " + std::to_string(offset)};
    }
    return Status::success();
  };

  const auto size = static_cast<std::int64_t>(file_size);
  const std::int64_t min_index_record = static_cast<std::int64_t>(kLogRecordHeaderBytes) + kIndexFixedBytes;
  if (size < static_cast<std::int64_t>(kLogHeaderBytes) + min_index_record) {
    return Error{name + ": no INDEX_2021 trailer (file of " + std::to_string(size) + " bytes is too short)"};
  }
  std::array<char, 8 + kIndexTrailer.size()> tail{};
  if (Status status = read_at(size - static_cast<std::int64_t>(tail.size()), tail.data(), tail.size());
      !status) {
    return Error{name + ": " + status.error().message};
  }
  if (std::string_view(tail.data() + 8, kIndexTrailer.size()) != kIndexTrailer) {
    return Error{name +
                 ": no INDEX_2021 trailer (the file does not end with \"INDEXED\"; gzip files have none)"};
  }
  const std::int64_t distance = get_be64(tail.data());
  if (distance < min_index_record || distance > size - static_cast<std::int64_t>(kLogHeaderBytes) ||
      (distance - min_index_record) % 8 != 0) {
    return Error{name + ": damaged index: invalid length " + std::to_string(distance)};
  }
  const std::int64_t index_start = size - distance;
  std::array<char, kLogRecordHeaderBytes> header{};
  if (Status status = read_at(index_start, header.data(), header.size()); !status) {
    return Error{name + ": " + status.error().message};
  }
  const std::int32_t type = get_be32(header.data() + 8);
  const std::int32_t payload_size = get_be32(header.data() + 12);
  if (type != static_cast<std::int32_t>(MessageType::kIndex2021) ||
      payload_size != distance - static_cast<std::int64_t>(kLogRecordHeaderBytes)) {
    return Error{name + ": damaged index: record at offset " + std::to_string(index_start) +
                 " is not an INDEX_2021 record of the announced size"};
  }
  const auto count = static_cast<std::size_t>((distance - min_index_record) / 8);
  std::string raw_offsets(count * 8, '\0');
  if (Status status = read_at(index_start + static_cast<std::int64_t>(kLogRecordHeaderBytes),
                              raw_offsets.data(), raw_offsets.size());
      !status) {
    return Error{name + ": " + status.error().message};
  }
  std::vector<std::int64_t> offsets;
  offsets.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::int64_t offset = get_be64(raw_offsets.data() + 8 * i);
    if (offset < static_cast<std::int64_t>(kLogHeaderBytes) || offset >= index_start) {
      return Error{name + ": damaged index: entry " + std::to_string(i) + " points to offset " +
                   std::to_string(offset) + ", outside the records (16.." + std::to_string(index_start) +
                   ")"};
    }
    offsets.push_back(offset);
  }
  return offsets;
}

}  // namespace ssl::league
