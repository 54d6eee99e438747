// SSL log files: exact byte layout, plain and gzip round trips, the INDEX_2021 trailer, and a clear
// error (never a crash) for every kind of damage.
#include "libs/league/log_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "libs/league/decode.h"
#include "libs/league/testing/hand_encoder.h"

namespace ssl::league {
namespace {

using ::testing::HasSubstr;

namespace fs = std::filesystem;

class LeagueLogFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("ssl_league_log_test_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path path(const std::string& name) const { return dir_ / name; }

  static std::string read_file(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  static void write_file(const fs::path& file, const std::string& bytes) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }

  fs::path dir_;
};

std::string be(std::uint64_t value, int bytes) {
  std::string out;
  for (int i = bytes - 1; i >= 0; --i) {
    out.push_back(static_cast<char>((value >> (8 * i)) & 0xFF));
  }
  return out;
}

std::string header(std::int32_t version = 1) {
  return "SSL_LOG_FILE" + be(static_cast<std::uint32_t>(version), 4);
}

std::string record(std::int64_t timestamp, std::int32_t type, std::int32_t size, const std::string& payload) {
  return be(static_cast<std::uint64_t>(timestamp), 8) + be(static_cast<std::uint32_t>(type), 4) +
         be(static_cast<std::uint32_t>(size), 4) + payload;
}

struct Sample {
  std::int64_t timestamp_ns;
  MessageType type;
  std::string payload;
};

std::vector<Sample> samples() {
  SSL_WrapperPacket vision;
  vision.set_source(SSL_SOURCE_SSL_VISION);
  auto* frame = vision.mutable_detection();
  frame->set_frame_number(1);
  frame->set_t_capture(1.0);
  frame->set_t_sent(1.0);
  frame->set_camera_id(0);
  TrackerWrapperPacket tracker;
  tracker.set_uuid("u-1");
  return {
      {1700000000000000000LL, MessageType::kVision2014, vision.SerializeAsString()},
      {1700000000016000000LL, MessageType::kVisionTracker2020, tracker.SerializeAsString()},
      {1700000000020000000LL, MessageType::kRefbox2013, std::string(300, '\x42')},
      {1700000000030000000LL, MessageType::kBlank, ""},
      {1700000000040000000LL, static_cast<MessageType>(42), std::string("\x00\x01\x02", 3)},
      {-5, MessageType::kVision2010, std::string(100000, 'z')},  // larger than any buffer slice of zlib
  };
}

void write_samples(const fs::path& file, LogWriter::Options options = {}) {
  auto writer = LogWriter::open(file, options);
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  for (const Sample& sample : samples()) {
    const Status status = writer->write(sample.timestamp_ns, sample.type, sample.payload);
    ASSERT_TRUE(status.ok()) << status.error().message;
  }
  EXPECT_EQ(writer->records_written(), samples().size());
  const Status closed = writer->close();
  ASSERT_TRUE(closed.ok()) << closed.error().message;
}

std::vector<LogRecord> read_all(LogReader& reader) {
  std::vector<LogRecord> records;
  for (;;) {
    auto next = reader.next();
    EXPECT_TRUE(next.ok()) << next.error().message;
    if (!next.ok() || !next->has_value()) {
      return records;
    }
    records.push_back(std::move(**next));
  }
}

/// Reads until the first error and returns its message ("" if the data ended cleanly).
std::string first_error(LogReader& reader) {
  for (int guard = 0; guard < 1000000; ++guard) {
    auto next = reader.next();
    if (!next.ok()) {
      return next.error().message;
    }
    if (!next->has_value()) {
      return "";
    }
  }
  return "runaway";
}

void expect_samples(const std::vector<LogRecord>& records) {
  const auto expected = samples();
  ASSERT_EQ(records.size(), expected.size());
  std::int64_t offset = 16;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(records[i].timestamp_ns, expected[i].timestamp_ns);
    EXPECT_EQ(records[i].type, expected[i].type);
    EXPECT_EQ(records[i].payload, expected[i].payload);
    EXPECT_EQ(records[i].offset, offset);
    offset += 16 + static_cast<std::int64_t>(expected[i].payload.size());
  }
}

TEST_F(LeagueLogFile, ExactByteLayoutIsBigEndian) {
  auto writer = LogWriter::open(path("layout.log"));
  ASSERT_TRUE(writer.ok());
  ASSERT_TRUE(writer->write(0x0102030405060708LL, MessageType::kVision2014, std::string("abc")).ok());
  ASSERT_TRUE(writer->close().ok());
  const std::string expected = std::string("SSL_LOG_FILE") + std::string("\x00\x00\x00\x01", 4) +
                               std::string("\x01\x02\x03\x04\x05\x06\x07\x08", 8) +
                               std::string("\x00\x00\x00\x04", 4) + std::string("\x00\x00\x00\x03", 4) +
                               "abc";
  EXPECT_EQ(testing::hex(read_file(path("layout.log"))), testing::hex(expected));
}

TEST_F(LeagueLogFile, PlainRoundTrip) {
  write_samples(path("match.log"));
  auto reader = LogReader::open(path("match.log"));
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  const auto records = read_all(*reader);
  expect_samples(records);
  auto vision = decode_vision_wrapper(byte_span(records[0].payload));
  ASSERT_TRUE(vision.ok()) << vision.error().message;
  EXPECT_EQ(vision->source(), SSL_SOURCE_SSL_VISION);
  // The end stays the end.
  auto after = reader->next();
  ASSERT_TRUE(after.ok());
  EXPECT_FALSE(after->has_value());
}

TEST_F(LeagueLogFile, GzipRoundTrip) {
  write_samples(path("match.log.gz"));
  const std::string raw = read_file(path("match.log.gz"));
  ASSERT_GE(raw.size(), 2U);
  EXPECT_EQ(static_cast<unsigned char>(raw[0]), 0x1F);  // gzip magic: compressed by suffix
  EXPECT_EQ(static_cast<unsigned char>(raw[1]), 0x8B);
  EXPECT_LT(raw.size(), 100000U);  // the 100 kB record compresses

  auto reader = LogReader::open(path("match.log.gz"));
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  expect_samples(read_all(*reader));
}

TEST_F(LeagueLogFile, GzipIsRecognisedByContentNotName) {
  write_samples(path("compressed.log"), {.compression = Compression::kGzip});
  EXPECT_EQ(static_cast<unsigned char>(read_file(path("compressed.log"))[0]), 0x1F);
  auto reader = LogReader::open(path("compressed.log"));
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  expect_samples(read_all(*reader));

  write_samples(path("plain.log.gz"), {.compression = Compression::kNone});
  EXPECT_EQ(read_file(path("plain.log.gz")).substr(0, 12), "SSL_LOG_FILE");
  auto plain = LogReader::open(path("plain.log.gz"));
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  expect_samples(read_all(*plain));
}

TEST_F(LeagueLogFile, WrongHeader) {
  write_file(path("bad.log"), "SSL_LOG_FILX" + be(1, 4) + record(0, 4, 0, ""));
  auto reader = LogReader::open(path("bad.log"));
  ASSERT_FALSE(reader.ok());
  EXPECT_THAT(reader.error().message, HasSubstr("bad.log"));
  EXPECT_THAT(reader.error().message, HasSubstr("not an SSL log file"));

  write_file(path("short.log"), "SSL_LOG");
  auto short_reader = LogReader::open(path("short.log"));
  ASSERT_FALSE(short_reader.ok());
  EXPECT_THAT(short_reader.error().message, HasSubstr("too short for the 16-byte header (7 bytes)"));

  auto empty = LogReader::from_bytes("");
  ASSERT_FALSE(empty.ok());
  EXPECT_THAT(empty.error().message, HasSubstr("(0 bytes)"));
}

TEST_F(LeagueLogFile, UnsupportedVersion) {
  auto reader = LogReader::from_bytes(header(2) + record(1, 4, 0, ""));
  ASSERT_FALSE(reader.ok());
  EXPECT_THAT(reader.error().message, HasSubstr("unsupported log format version 2"));
  auto negative = LogReader::from_bytes(header(-1));
  ASSERT_FALSE(negative.ok());
  EXPECT_THAT(negative.error().message, HasSubstr("version -1"));
}

TEST_F(LeagueLogFile, NegativeSize) {
  auto reader = LogReader::from_bytes(header() + record(1, 4, 3, "abc") + record(2, 4, -1, "xyz"));
  ASSERT_TRUE(reader.ok());
  auto first = reader->next();
  ASSERT_TRUE(first.ok());
  ASSERT_TRUE(first->has_value());
  EXPECT_EQ((*first)->payload, "abc");
  auto second = reader->next();
  ASSERT_FALSE(second.ok());
  EXPECT_THAT(second.error().message, HasSubstr("record at offset 35: negative payload size -1"));
  // Errors are sticky: the reader does not resynchronise on garbage.
  auto third = reader->next();
  ASSERT_FALSE(third.ok());
  EXPECT_EQ(third.error().message, second.error().message);
}

TEST_F(LeagueLogFile, TruncatedRecordHeaderAndPayload) {
  auto header_cut = LogReader::from_bytes(header() + record(1, 4, 0, "").substr(0, 10));
  ASSERT_TRUE(header_cut.ok());
  EXPECT_THAT(first_error(*header_cut),
              HasSubstr("record at offset 16: truncated record header (10 of 16 bytes)"));

  auto payload_cut = LogReader::from_bytes(header() + record(1, 4, 100, std::string(10, 'p')));
  ASSERT_TRUE(payload_cut.ok());
  EXPECT_THAT(first_error(*payload_cut), HasSubstr("truncated payload (10 of 100 bytes present)"));

  // A size near INT32_MAX on a short file is reported without allocating gigabytes first.
  auto huge = LogReader::from_bytes(header() + record(1, 4, 0x7FFFFFFF, "tiny"));
  ASSERT_TRUE(huge.ok());
  EXPECT_THAT(first_error(*huge), HasSubstr("truncated payload (4 of 2147483647 bytes present)"));
}

TEST_F(LeagueLogFile, EveryTruncationOfAPlainFileIsCleanEndOrError) {
  write_samples(path("full.log"));
  const std::string bytes = read_file(path("full.log"));
  std::vector<std::size_t> boundaries{16};
  for (const Sample& sample : samples()) {
    boundaries.push_back(boundaries.back() + 16 + sample.payload.size());
  }
  for (std::size_t length = 0; length < bytes.size(); length += (length < 1000 ? 1 : 997)) {
    auto reader = LogReader::from_bytes(bytes.substr(0, length));
    if (length < 16) {
      EXPECT_FALSE(reader.ok());
      continue;
    }
    ASSERT_TRUE(reader.ok()) << length;
    const std::string error = first_error(*reader);
    const bool at_boundary = std::find(boundaries.begin(), boundaries.end(), length) != boundaries.end();
    EXPECT_EQ(error.empty(), at_boundary) << "length " << length << ": " << error;
  }
}

TEST_F(LeagueLogFile, TruncatedGzipFile) {
  write_samples(path("cut.log.gz"));
  const std::string bytes = read_file(path("cut.log.gz"));
  for (const std::size_t length : {bytes.size() / 4, bytes.size() / 2, bytes.size() - 8, bytes.size() - 1}) {
    SCOPED_TRACE(length);
    write_file(path("cut.log.gz"), bytes.substr(0, length));
    auto reader = LogReader::open(path("cut.log.gz"));
    if (!reader.ok()) {
      continue;  // cut inside the header: already an error
    }
    EXPECT_THAT(first_error(*reader), ::testing::AnyOf(HasSubstr("truncated"), HasSubstr("gzip")));
  }
}

TEST_F(LeagueLogFile, CorruptGzipData) {
  write_samples(path("corrupt.log.gz"));
  std::string bytes = read_file(path("corrupt.log.gz"));
  for (std::size_t i = 40; i < bytes.size() - 20; i += 7) {
    bytes[i] = static_cast<char>(bytes[i] ^ 0x5A);
  }
  write_file(path("corrupt.log.gz"), bytes);
  auto reader = LogReader::open(path("corrupt.log.gz"));
  if (reader.ok()) {
    EXPECT_FALSE(first_error(*reader).empty());
  } else {
    EXPECT_THAT(reader.error().message, HasSubstr("corrupt.log.gz"));
  }
}

TEST_F(LeagueLogFile, MissingFile) {
  auto reader = LogReader::open(path("does-not-exist.log"));
  ASSERT_FALSE(reader.ok());
  EXPECT_THAT(reader.error().message, HasSubstr("does-not-exist.log"));
  EXPECT_THAT(reader.error().message, HasSubstr("cannot open"));
}

TEST_F(LeagueLogFile, IndexTrailer) {
  write_samples(path("indexed.log"), {.write_index = true});
  auto index = read_log_index(path("indexed.log"));
  ASSERT_TRUE(index.ok()) << index.error().message;

  auto reader = LogReader::open(path("indexed.log"));
  ASSERT_TRUE(reader.ok());
  auto records = read_all(*reader);
  ASSERT_EQ(records.size(), samples().size() + 1);
  const LogRecord& trailer = records.back();
  EXPECT_EQ(trailer.type, MessageType::kIndex2021);
  EXPECT_EQ(trailer.timestamp_ns, 0);
  EXPECT_EQ(trailer.payload.size(), 8 * samples().size() + 15);
  EXPECT_EQ(trailer.payload.substr(trailer.payload.size() - 7), "INDEXED");
  EXPECT_EQ(trailer.payload.substr(trailer.payload.size() - 15, 8), be(16 + trailer.payload.size(), 8));

  ASSERT_EQ(index->size(), samples().size());
  for (std::size_t i = 0; i < index->size(); ++i) {
    EXPECT_EQ((*index)[i], records[i].offset);
  }
  // Random access through the index.
  ASSERT_TRUE(reader->seek((*index)[2]).ok());
  auto third = reader->next();
  ASSERT_TRUE(third.ok());
  ASSERT_TRUE(third->has_value());
  EXPECT_EQ((*third)->type, MessageType::kRefbox2013);
  EXPECT_EQ((*third)->offset, (*index)[2]);
}

TEST_F(LeagueLogFile, IndexErrors) {
  auto gzip = LogWriter::open(path("x.log.gz"), {.write_index = true});
  ASSERT_FALSE(gzip.ok());
  EXPECT_THAT(gzip.error().message, HasSubstr("uncompressed"));

  write_samples(path("plain.log"));
  auto none = read_log_index(path("plain.log"));
  ASSERT_FALSE(none.ok());
  EXPECT_THAT(none.error().message, HasSubstr("no INDEX_2021 trailer"));

  write_samples(path("damaged.log"), {.write_index = true});
  std::string bytes = read_file(path("damaged.log"));
  const std::string good = bytes;
  bytes.replace(bytes.size() - 15, 8, be(5, 8));  // impossible distance back
  write_file(path("damaged.log"), bytes);
  auto damaged = read_log_index(path("damaged.log"));
  ASSERT_FALSE(damaged.ok());
  EXPECT_THAT(damaged.error().message, HasSubstr("damaged index"));

  bytes = good;
  bytes.replace(bytes.size() - 15 - 8, 8, be(999999999, 8));  // last entry points past the records
  write_file(path("damaged.log"), bytes);
  auto outside = read_log_index(path("damaged.log"));
  ASSERT_FALSE(outside.ok());
  EXPECT_THAT(outside.error().message, HasSubstr("outside the records"));
}

TEST_F(LeagueLogFile, WriteAfterCloseFails) {
  auto writer = LogWriter::open(path("closed.log"));
  ASSERT_TRUE(writer.ok());
  ASSERT_TRUE(writer->close().ok());
  const Status status = writer->write(1, MessageType::kBlank, std::string());
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.error().message, HasSubstr("write after close"));
}

TEST_F(LeagueLogFile, UnwritableLocation) {
  auto writer = LogWriter::open(path("no-such-dir/out.log"));
  ASSERT_FALSE(writer.ok());
  EXPECT_THAT(writer.error().message, HasSubstr("cannot create"));
}

TEST(LeagueLogFileRandom, SeededRandomRecordsNeverCrash) {
  std::mt19937 random(99U);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<std::size_t> length(0, 400);
  for (int round = 0; round < 3000; ++round) {
    std::string bytes = header();
    bytes.resize(16 + length(random));
    for (std::size_t i = 16; i < bytes.size(); ++i) {
      bytes[i] = static_cast<char>(byte(random));
    }
    auto reader = LogReader::from_bytes(bytes);
    ASSERT_TRUE(reader.ok());
    (void)first_error(*reader);
  }
}

TEST(LeagueLogFileNames, MessageTypeNamesFollowTheTable) {
  EXPECT_EQ(to_string(MessageType::kBlank), "BLANK");
  EXPECT_EQ(to_string(MessageType::kUnknown), "UNKNOWN");
  EXPECT_EQ(to_string(MessageType::kVision2010), "SSL_VISION_2010");
  EXPECT_EQ(to_string(MessageType::kRefbox2013), "SSL_REFBOX_2013");
  EXPECT_EQ(to_string(MessageType::kVision2014), "SSL_VISION_2014");
  EXPECT_EQ(to_string(MessageType::kVisionTracker2020), "SSL_VISION_TRACKER_2020");
  EXPECT_EQ(to_string(MessageType::kIndex2021), "INDEX_2021");
  EXPECT_EQ(to_string(static_cast<MessageType>(77)), "TYPE_77");
  EXPECT_EQ(static_cast<int>(MessageType::kVision2014), 4);
  EXPECT_EQ(static_cast<int>(MessageType::kIndex2021), 6);
}

}  // namespace
}  // namespace ssl::league
