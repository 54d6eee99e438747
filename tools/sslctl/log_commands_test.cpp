// Tests of `sslctl log record | replay | info`: the command functions called directly with string
// streams (recording and replaying over loopback multicast on ports 25100-25399), byte-level checks of
// the league's file layout, and the sslctl binary itself for Ctrl-C and the CLI.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "libs/league/decode.h"
#include "libs/league/log_file.h"
#include "libs/net/multicast.h"
#include "tests/support/process.h"
#include "tools/sslctl/commands.h"

namespace ssl::sslctl {
namespace {

namespace fs = std::filesystem;
using league::MessageType;
using Steady = std::chrono::steady_clock;
using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr std::string_view kVisionGroup = "224.5.23.2";
constexpr std::string_view kRefereeGroup = "224.5.23.1";
constexpr std::int64_t kStartNs = 1'700'000'000'000'000'000;  // 2023-11-14 22:13:20 UTC
constexpr std::int64_t kMs = 1'000'000;

// ---------------------------------------------------------------------------------------------------
// Payloads, files, bytes

std::string vision_frame(std::uint32_t camera, std::uint32_t frame_number) {
  SSL_WrapperPacket packet;
  SSL_DetectionFrame* frame = packet.mutable_detection();
  frame->set_frame_number(frame_number);
  frame->set_t_capture(1.7e9 + frame_number / 60.0);
  frame->set_t_sent(1.7e9 + frame_number / 60.0 + 0.001);
  frame->set_camera_id(camera);
  SSL_DetectionBall* ball = frame->add_balls();
  ball->set_confidence(0.9f);
  ball->set_x(100.0f * static_cast<float>(frame_number));
  ball->set_y(-50.0f);
  ball->set_pixel_x(10.0f);
  ball->set_pixel_y(20.0f);
  return packet.SerializeAsString();
}

std::string legacy_vision_frame(std::uint32_t camera, std::uint32_t frame_number) {
  RoboCup2014Legacy::Wrapper::SSL_WrapperPacket packet;
  SSL_DetectionFrame* frame = packet.mutable_detection();
  frame->set_frame_number(frame_number);
  frame->set_t_capture(1.7e9);
  frame->set_t_sent(1.7e9);
  frame->set_camera_id(camera);
  return packet.SerializeAsString();
}

std::string referee_message(std::uint32_t command_counter, Referee::Command command, Referee::Stage stage) {
  Referee referee;
  referee.set_packet_timestamp(1'700'000'000'000'000ULL + command_counter);
  referee.set_stage(stage);
  referee.set_command(command);
  referee.set_command_counter(command_counter);
  referee.set_command_timestamp(1'700'000'000'000'000ULL);
  for (Referee::TeamInfo* team : {referee.mutable_yellow(), referee.mutable_blue()}) {
    team->set_name(team == referee.mutable_yellow() ? "Yellow" : "Blue");
    team->set_score(0);
    team->set_red_cards(0);
    team->set_yellow_cards(0);
    team->set_timeouts(4);
    team->set_timeout_time(300'000'000);
    team->set_goalkeeper(1);
  }
  return referee.SerializeAsString();
}

std::string tracker_packet(std::uint32_t frame_number) {
  TrackerWrapperPacket packet;
  packet.set_uuid("sslctl-test-tracker");
  packet.set_source_name("test " + std::to_string(frame_number));
  return packet.SerializeAsString();
}

/// Bytes no decoder accepts (a truncated varint tag).
const std::string kGarbage = "\xff\xff\xff\xff";

std::string payload_of(std::uint8_t tag) {
  return std::string("payload-") + static_cast<char>('a' + tag % 26);
}

class TempFile {
 public:
  explicit TempFile(const std::string& name)
      : path_(fs::temp_directory_path() / ("sslctl_log_" + std::to_string(getpid()) + "_" + name)) {
    fs::remove(path_);
  }
  ~TempFile() { fs::remove(path_); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const fs::path& path() const { return path_; }
  std::string string() const { return path_.string(); }

 private:
  fs::path path_;
};

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::uint64_t be(const std::string& bytes, std::size_t at, int width) {
  std::uint64_t value = 0;
  for (int i = 0; i < width; ++i) value = (value << 8) | static_cast<unsigned char>(bytes.at(at + i));
  return value;
}

void put_be(std::string& out, std::uint64_t value, int width) {
  for (int i = width - 1; i >= 0; --i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xFF));
}

struct Written {
  std::int64_t timestamp_ns;
  MessageType type;
  std::string payload;
};

void write_log(const fs::path& path, const std::vector<Written>& records, bool index = false) {
  auto writer = league::LogWriter::open(path, {.write_index = index});
  ASSERT_TRUE(writer) << writer.error().message;
  for (const Written& record : records) {
    ASSERT_TRUE(writer->write(record.timestamp_ns, record.type, record.payload).ok());
  }
  ASSERT_TRUE(writer->close().ok());
}

std::vector<league::LogRecord> read_log(const fs::path& path) {
  std::vector<league::LogRecord> records;
  auto reader = league::LogReader::open(path);
  EXPECT_TRUE(reader) << reader.error().message;
  if (!reader) return records;
  for (;;) {
    auto record = reader->next();
    EXPECT_TRUE(record) << record.error().message;
    if (!record || !*record) break;
    records.push_back(std::move(**record));
  }
  return records;
}

// ---------------------------------------------------------------------------------------------------
// Concurrency helpers

/// What the recorder reported through its hooks.
class RecorderProbe {
 public:
  void hook(LogRecordOptions& options) {
    options.on_ready = [this] {
      std::lock_guard lock(mutex_);
      ready_ = true;
      changed_.notify_all();
    };
    options.on_record = [this](const LogStreamCounts& counts) {
      std::lock_guard lock(mutex_);
      counts_ = counts;
      changed_.notify_all();
    };
  }
  bool wait_ready(milliseconds timeout) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [this] { return ready_; });
  }
  bool wait_records(std::uint64_t total, milliseconds timeout) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] { return counts_.total() >= total; });
  }
  LogStreamCounts counts() {
    std::lock_guard lock(mutex_);
    return counts_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  bool ready_ = false;
  LogStreamCounts counts_;
};

/// Runs a command function on its own thread; join() returns its exit code.
class CommandThread {
 public:
  explicit CommandThread(std::function<int()> command)
      : thread_([this, command = std::move(command)] { code_ = command(); }) {}
  ~CommandThread() {
    if (thread_.joinable()) thread_.join();
  }
  CommandThread(const CommandThread&) = delete;
  CommandThread& operator=(const CommandThread&) = delete;
  int join() {
    thread_.join();
    return code_;
  }

 private:
  std::atomic<int> code_{-1};
  std::thread thread_;
};

net::MulticastSender open_sender(std::string_view group, int port) {
  auto sender = net::MulticastSender::open(group, port, "127.0.0.1");
  EXPECT_TRUE(sender) << sender.error().message;
  return std::move(sender).value();
}

net::MulticastReceiver open_receiver(std::string_view group, int port) {
  auto receiver = net::MulticastReceiver::open(group, port, "127.0.0.1");
  EXPECT_TRUE(receiver) << receiver.error().message;
  return std::move(receiver).value();
}

void send(net::MulticastSender& sender, const std::string& payload) {
  ASSERT_TRUE(sender.send(league::byte_span(payload)).ok());
}

struct Arrival {
  std::string payload;
  Steady::time_point at;
};

/// Receives up to `count` datagrams, each within `timeout` of the previous one.
std::vector<Arrival> receive_n(net::MulticastReceiver& receiver, std::size_t count, milliseconds timeout) {
  std::vector<Arrival> arrivals;
  std::vector<std::uint8_t> buffer(65536);
  while (arrivals.size() < count) {
    const net::ReceiveResult result = receiver.receive(buffer, timeout);
    if (!result.ok()) break;
    arrivals.push_back(
        {std::string(reinterpret_cast<const char*>(buffer.data()), result.size), Steady::now()});
  }
  return arrivals;
}

std::vector<std::string> payloads(const std::vector<Arrival>& arrivals) {
  std::vector<std::string> out;
  for (const Arrival& arrival : arrivals) out.push_back(arrival.payload);
  return out;
}

LogStreamPorts ports_from(int base) {
  return {.vision = base, .legacy_vision = base + 1, .referee = base + 2, .tracker = base + 3};
}

std::int64_t wall_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// ---------------------------------------------------------------------------------------------------
// record

/// The datagrams a recording test sends, per stream, in order.
struct SentStreams {
  std::map<MessageType, std::vector<std::string>> payloads;
  std::size_t total() const {
    std::size_t total = 0;
    for (const auto& [type, list] : payloads) total += list.size();
    return total;
  }
};

SentStreams send_every_stream(const LogStreamPorts& ports) {
  SentStreams sent;
  auto vision = open_sender(kVisionGroup, ports.vision);
  auto legacy = open_sender(kVisionGroup, ports.legacy_vision);
  auto referee = open_sender(kRefereeGroup, ports.referee);
  auto tracker = open_sender(kVisionGroup, ports.tracker);
  for (std::uint32_t i = 1; i <= 5; ++i)
    sent.payloads[MessageType::kVision2014].push_back(vision_frame(i % 2, i));
  sent.payloads[MessageType::kVision2014].push_back(kGarbage);  // recorded raw, counted as undecodable
  for (std::uint32_t i = 1; i <= 2; ++i)
    sent.payloads[MessageType::kVision2010].push_back(legacy_vision_frame(0, i));
  sent.payloads[MessageType::kRefbox2013] = {
      referee_message(1, Referee::HALT, Referee::NORMAL_FIRST_HALF_PRE),
      referee_message(2, Referee::STOP, Referee::NORMAL_FIRST_HALF_PRE),
      referee_message(3, Referee::FORCE_START, Referee::NORMAL_FIRST_HALF)};
  sent.payloads[MessageType::kVisionTracker2020] = {tracker_packet(1), tracker_packet(2)};
  // Interleaved, as on a real network.
  for (std::size_t i = 0; i < 6; ++i) {
    send(vision, sent.payloads[MessageType::kVision2014][i]);
    if (i < 2) send(legacy, sent.payloads[MessageType::kVision2010][i]);
    if (i < 3) send(referee, sent.payloads[MessageType::kRefbox2013][i]);
    if (i < 2) send(tracker, sent.payloads[MessageType::kVisionTracker2020][i]);
  }
  return sent;
}

void expect_recorded(const std::vector<league::LogRecord>& records, const SentStreams& sent,
                     std::int64_t from_ns, std::int64_t to_ns) {
  std::map<MessageType, std::vector<std::string>> recorded;
  for (const league::LogRecord& record : records) {
    if (record.type == MessageType::kIndex2021) continue;
    recorded[record.type].push_back(record.payload);
    EXPECT_GE(record.timestamp_ns, from_ns);
    EXPECT_LE(record.timestamp_ns, to_ns);
  }
  EXPECT_EQ(recorded, sent.payloads);
}

TEST(SslctlLogRecord, RecordsEveryDatagramWithItsTypeAndPayloadAndAnIndex) {
  TempFile file("record.log");
  ShutdownSignal shutdown;
  LogRecordOptions options{.file = file.string(), .ports = ports_from(25110), .progress_period_s = 0.05};
  RecorderProbe probe;
  probe.hook(options);
  std::ostringstream out;
  std::ostringstream err;
  const std::int64_t before_ns = wall_ns();
  CommandThread recorder([&] { return log_record(options, shutdown, out, err); });
  ASSERT_TRUE(probe.wait_ready(seconds(10)));

  const SentStreams sent = send_every_stream(options.ports);
  ASSERT_TRUE(probe.wait_records(sent.total(), seconds(10)))
      << probe.counts().total() << " of " << sent.total();
  shutdown.request();
  ASSERT_EQ(recorder.join(), 0) << err.str();
  const std::int64_t after_ns = wall_ns();

  const LogStreamCounts counts = probe.counts();
  EXPECT_EQ(counts.vision, 6u);
  EXPECT_EQ(counts.legacy_vision, 2u);
  EXPECT_EQ(counts.referee, 3u);
  EXPECT_EQ(counts.tracker, 2u);
  EXPECT_EQ(counts.undecodable, 1u);
  EXPECT_NE(out.str().find("recording to " + file.string()), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("recorded 13 records"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("1 undecodable"), std::string::npos) << out.str();

  const auto records = read_log(file.path());
  expect_recorded(records, sent, before_ns, after_ns);
  auto index = league::read_log_index(file.path());
  ASSERT_TRUE(index) << index.error().message;
  EXPECT_EQ(index->size(), 13u);
}

TEST(SslctlLogRecord, FileHasTheLeaguesByteLayoutWithTheGoToolsIndexTrailer) {
  TempFile file("layout.log");
  ShutdownSignal shutdown;
  LogRecordOptions options{.file = file.string(), .ports = ports_from(25120), .progress_period_s = 0};
  RecorderProbe probe;
  probe.hook(options);
  std::ostringstream out;
  std::ostringstream err;
  CommandThread recorder([&] { return log_record(options, shutdown, out, err); });
  ASSERT_TRUE(probe.wait_ready(seconds(10)));
  const std::string vision = vision_frame(3, 77);
  const std::string referee = referee_message(9, Referee::STOP, Referee::NORMAL_HALF_TIME);
  auto vision_sender = open_sender(kVisionGroup, options.ports.vision);
  send(vision_sender, vision);
  ASSERT_TRUE(probe.wait_records(1, seconds(10)));
  auto referee_sender = open_sender(kRefereeGroup, options.ports.referee);
  send(referee_sender, referee);
  ASSERT_TRUE(probe.wait_records(2, seconds(10)));
  shutdown.request();
  ASSERT_EQ(recorder.join(), 0) << err.str();

  // Parsed by hand from section 12 of the protocol reference, not with LogReader.
  const std::string bytes = read_bytes(file.path());
  ASSERT_GE(bytes.size(), 16u);
  EXPECT_EQ(bytes.substr(0, 12), "SSL_LOG_FILE");
  EXPECT_EQ(be(bytes, 12, 4), 1u);
  std::size_t at = 16;
  std::vector<std::uint64_t> offsets;
  const std::vector<std::pair<std::uint64_t, std::string>> expected = {{4, vision}, {3, referee}};
  for (const auto& [type, payload] : expected) {
    offsets.push_back(at);
    const auto timestamp = static_cast<std::int64_t>(be(bytes, at, 8));
    EXPECT_GT(timestamp, kStartNs);  // receive time, ns since the Unix epoch
    EXPECT_EQ(be(bytes, at + 8, 4), type);
    ASSERT_EQ(be(bytes, at + 12, 4), payload.size());
    EXPECT_EQ(bytes.substr(at + 16, payload.size()), payload);
    at += 16 + payload.size();
  }
  // INDEX_2021 as ssl-go-tools writes it: timestamp 0, type 6, size 8n + 15, n offsets, the record's
  // total length, "INDEXED" at the very end.
  EXPECT_EQ(be(bytes, at, 8), 0u);
  EXPECT_EQ(be(bytes, at + 8, 4), 6u);
  EXPECT_EQ(be(bytes, at + 12, 4), 8 * offsets.size() + 15);
  for (std::size_t i = 0; i < offsets.size(); ++i) EXPECT_EQ(be(bytes, at + 16 + 8 * i, 8), offsets[i]);
  EXPECT_EQ(be(bytes, at + 16 + 8 * offsets.size(), 8), 16 + 8 * offsets.size() + 15);
  EXPECT_EQ(bytes.substr(at + 16 + 8 * offsets.size() + 8), "INDEXED");
}

TEST(SslctlLogRecord, GzipSuffixWritesAGzipFileWithoutIndex) {
  TempFile file("record.log.gz");
  ShutdownSignal shutdown;
  LogRecordOptions options{.file = file.string(), .ports = ports_from(25130), .progress_period_s = 0};
  RecorderProbe probe;
  probe.hook(options);
  std::ostringstream out;
  std::ostringstream err;
  const std::int64_t before_ns = wall_ns();
  CommandThread recorder([&] { return log_record(options, shutdown, out, err); });
  ASSERT_TRUE(probe.wait_ready(seconds(10)));
  const SentStreams sent = send_every_stream(options.ports);
  ASSERT_TRUE(probe.wait_records(sent.total(), seconds(10)));
  shutdown.request();
  ASSERT_EQ(recorder.join(), 0) << err.str();

  const std::string bytes = read_bytes(file.path());
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1F);
  EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8B);
  const auto records = read_log(file.path());
  EXPECT_EQ(records.size(), sent.total());  // no INDEX_2021 record
  expect_recorded(records, sent, before_ns, wall_ns());
}

TEST(SslctlLogRecord, StopsAfterDurationAndPrintsProgress) {
  TempFile file("duration.log");
  ShutdownSignal shutdown;
  LogRecordOptions options{.file = file.string(),
                           .ports = ports_from(25140),
                           .duration_s = 0.4,
                           .legacy = false,
                           .progress_period_s = 0.1};
  std::ostringstream out;
  std::ostringstream err;
  const auto start = Steady::now();
  EXPECT_EQ(log_record(options, shutdown, out, err), 0) << err.str();
  EXPECT_GE(Steady::now() - start, milliseconds(400));
  EXPECT_NE(err.str().find("recording " + file.string() + ": "), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("0 records (vision 0, referee 0, tracker 0)"), std::string::npos) << err.str();
  EXPECT_EQ(out.str().find("legacy"), std::string::npos) << out.str();
  EXPECT_TRUE(read_log(file.path()).size() == 1u);  // just the (empty) index
}

TEST(SslctlLogRecord, RejectsTwoStreamsOnOnePortAndBadInterfaces) {
  TempFile file("rejected.log");
  ShutdownSignal shutdown;
  std::ostringstream out;
  std::ostringstream err;
  LogRecordOptions shared{.file = file.string(), .ports = {.vision = 25150, .tracker = 25150}};
  EXPECT_EQ(log_record(shared, shutdown, out, err), 2);
  EXPECT_NE(err.str().find("cannot share 224.5.23.2:25150"), std::string::npos) << err.str();

  err.str("");
  LogRecordOptions bad_interface{
      .file = file.string(), .ports = ports_from(25151), .interface_address = "not-an-address"};
  EXPECT_EQ(log_record(bad_interface, shutdown, out, err), 1);
  EXPECT_NE(err.str().find("cannot receive the vision stream"), std::string::npos) << err.str();
  EXPECT_FALSE(fs::exists(file.path()));  // no empty log left behind
}

TEST(SslctlLogRecord, BinaryStopsOnSigintAndKeepsEveryDatagramSentBefore) {
  TempFile file("sigint.log");
  const LogStreamPorts ports = ports_from(25160);
  auto child = testing::ChildProcess::start(
      testing::bin_dir() / "sslctl",
      {"log", "record", file.string(), "--vision-port", std::to_string(ports.vision), "--legacy-vision-port",
       std::to_string(ports.legacy_vision), "--referee-port", std::to_string(ports.referee), "--tracker-port",
       std::to_string(ports.tracker), "--interface", "127.0.0.1"});
  ASSERT_TRUE(child) << child.error().message;
  // The first line is printed once every group is joined.
  auto line = child->read_line(seconds(10));
  ASSERT_TRUE(line) << child->drain_stderr();
  EXPECT_NE(line->find("recording to"), std::string::npos) << *line;

  const std::int64_t before_ns = wall_ns();
  const SentStreams sent = send_every_stream(ports);
  child->signal(SIGINT);
  ASSERT_EQ(child->wait(seconds(10)), 0) << child->drain_stderr();
  auto summary = child->read_line(seconds(1));
  ASSERT_TRUE(summary);
  EXPECT_NE(summary->find("recorded 13 records"), std::string::npos) << *summary;
  expect_recorded(read_log(file.path()), sent, before_ns, wall_ns());
  EXPECT_TRUE(league::read_log_index(file.path()));
}

// ---------------------------------------------------------------------------------------------------
// replay

TEST(SslctlLogReplay, SendsEveryPayloadInOrderWithTheTimingScaledBySpeed) {
  TempFile file("replay.log");
  std::vector<Written> records;
  std::vector<std::string> expected;
  for (std::uint32_t i = 0; i <= 20; ++i) {  // 1 s of log time, 50 ms apart
    records.push_back({kStartNs + i * 50 * kMs, MessageType::kVision2014, vision_frame(i % 4, i + 1)});
    expected.push_back(records.back().payload);
  }
  write_log(file.path(), records);
  const LogStreamPorts ports = ports_from(25210);
  auto receiver = open_receiver(kVisionGroup, ports.vision);

  ShutdownSignal shutdown;
  std::ostringstream out;
  std::ostringstream err;
  LogReplayOptions options{.file = file.string(), .ports = ports, .speed = 10, .progress_period_s = 0.02};
  const auto started = Steady::now();
  CommandThread replay([&] { return log_replay(options, shutdown, out, err); });
  const auto arrivals = receive_n(receiver, expected.size(), seconds(5));
  ASSERT_EQ(replay.join(), 0) << err.str();

  ASSERT_EQ(payloads(arrivals), expected);
  // At speed 10, record i is due 5 i ms after the replay started: it never arrives earlier (a lower bound
  // that load cannot break), and the whole second of log time takes far less than a second.
  for (std::size_t i = 0; i < arrivals.size(); ++i) {
    EXPECT_GE(arrivals[i].at - started, milliseconds(5 * static_cast<int>(i)))
        << "record " << i << " came early";
  }
  EXPECT_LT(arrivals.back().at - started, milliseconds(800));
  EXPECT_NE(out.str().find("replayed 21 records"), std::string::npos) << out.str();
  EXPECT_NE(err.str().find("records sent"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("/ 1.0 s ("), std::string::npos) << err.str();
}

TEST(SslctlLogReplay, RoutesEachTypeToItsGroupAndPortAndSkipsOtherTypes) {
  TempFile file("routes.log");
  const std::string vision = vision_frame(0, 1);
  const std::string legacy = legacy_vision_frame(1, 2);
  const std::string referee = referee_message(4, Referee::STOP, Referee::NORMAL_FIRST_HALF);
  const std::string tracker = tracker_packet(3);
  write_log(file.path(),
            {{kStartNs, MessageType::kBlank, "blank"},
             {kStartNs + 1 * kMs, MessageType::kVision2014, vision},
             {kStartNs + 2 * kMs, MessageType::kUnknown, "unknown"},
             {kStartNs + 3 * kMs, MessageType::kVision2010, legacy},
             {kStartNs + 4 * kMs, MessageType::kRefbox2013, referee},
             {kStartNs + 5 * kMs, static_cast<MessageType>(42), "future type"},
             {kStartNs + 6 * kMs, MessageType::kVisionTracker2020, tracker}},
            /*index=*/true);
  const LogStreamPorts ports = ports_from(25220);
  auto vision_rx = open_receiver(kVisionGroup, ports.vision);
  auto legacy_rx = open_receiver(kVisionGroup, ports.legacy_vision);
  auto referee_rx = open_receiver(kRefereeGroup, ports.referee);
  auto tracker_rx = open_receiver(kVisionGroup, ports.tracker);

  ShutdownSignal shutdown;
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(log_replay({.file = file.string(), .ports = ports, .speed = 5}, shutdown, out, err), 0)
      << err.str();

  // The replay has ended: everything it sent is queued; one more receive must time out.
  EXPECT_EQ(payloads(receive_n(vision_rx, 2, milliseconds(200))), std::vector<std::string>{vision});
  EXPECT_EQ(payloads(receive_n(legacy_rx, 2, milliseconds(200))), std::vector<std::string>{legacy});
  EXPECT_EQ(payloads(receive_n(referee_rx, 2, milliseconds(200))), std::vector<std::string>{referee});
  EXPECT_EQ(payloads(receive_n(tracker_rx, 2, milliseconds(200))), std::vector<std::string>{tracker});
  EXPECT_NE(out.str().find("replayed 4 records (vision 1, legacy vision 1, referee 1, tracker 1"),
            std::string::npos)
      << out.str();
  EXPECT_NE(out.str().find("; 3 skipped"), std::string::npos) << out.str();
}

TEST(SslctlLogReplay, LoopStartsOverUntilStopped) {
  TempFile file("loop.log.gz");
  write_log(file.path(), {{kStartNs, MessageType::kRefbox2013, payload_of(0)},
                          {kStartNs + 10 * kMs, MessageType::kRefbox2013, payload_of(1)},
                          {kStartNs + 20 * kMs, MessageType::kRefbox2013, payload_of(2)}});
  const LogStreamPorts ports = ports_from(25230);
  auto receiver = open_receiver(kRefereeGroup, ports.referee);
  ShutdownSignal shutdown;
  std::ostringstream out;
  std::ostringstream err;
  LogReplayOptions options{.file = file.string(), .ports = ports, .loop = true, .progress_period_s = 0};
  CommandThread replay([&] { return log_replay(options, shutdown, out, err); });
  const auto arrivals = receive_n(receiver, 7, seconds(5));
  shutdown.request();
  ASSERT_EQ(replay.join(), 0) << err.str();
  EXPECT_EQ(payloads(arrivals),
            (std::vector<std::string>{payload_of(0), payload_of(1), payload_of(2), payload_of(0),
                                      payload_of(1), payload_of(2), payload_of(0)}));
  EXPECT_NE(out.str().find("full pass(es)"), std::string::npos) << out.str();
}

TEST(SslctlLogReplay, DamagedFileIsReplayedUpToTheDamageThenFailsWithTheOffset) {
  TempFile file("damaged.log");
  std::vector<Written> records;
  std::int64_t last_offset = 16;
  for (std::uint8_t i = 0; i < 5; ++i) {
    records.push_back({kStartNs + i * kMs, MessageType::kVision2014, payload_of(i)});
    if (i < 4) last_offset += 16 + static_cast<std::int64_t>(payload_of(i).size());
  }
  write_log(file.path(), records);
  const std::string bytes = read_bytes(file.path());
  write_bytes(file.path(), bytes.substr(0, bytes.size() - 3));  // cuts the last payload short

  const LogStreamPorts ports = ports_from(25240);
  auto receiver = open_receiver(kVisionGroup, ports.vision);
  ShutdownSignal shutdown;
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(log_replay({.file = file.string(), .ports = ports, .speed = 10}, shutdown, out, err), 1);
  EXPECT_EQ(payloads(receive_n(receiver, 5, milliseconds(200))),
            (std::vector<std::string>{payload_of(0), payload_of(1), payload_of(2), payload_of(3)}));
  EXPECT_NE(err.str().find("record at offset " + std::to_string(last_offset) + ": truncated payload"),
            std::string::npos)
      << err.str();
}

TEST(SslctlLogReplay, RejectsBadArgumentsAndFilesThatAreNotLogs) {
  TempFile file("not_a_log.log");
  write_bytes(file.path(), "this is not an SSL log file");
  ShutdownSignal shutdown;
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(log_replay({.file = file.string(), .speed = 0}, shutdown, out, err), 2);
  EXPECT_NE(err.str().find("--speed"), std::string::npos) << err.str();
  err.str("");
  EXPECT_EQ(log_replay({.file = file.string(), .ports = ports_from(25250)}, shutdown, out, err), 1);
  EXPECT_NE(err.str().find("not an SSL log file"), std::string::npos) << err.str();
  err.str("");
  EXPECT_EQ(log_replay({.file = file.string() + ".missing", .ports = ports_from(25250)}, shutdown, out, err),
            1);
  EXPECT_NE(err.str().find("cannot open"), std::string::npos) << err.str();
}

// ---------------------------------------------------------------------------------------------------
// info

/// 2.5 s: cameras 0 (6 frames) and 1 (4 frames), one undecodable vision payload, referee commands
/// HALT -> STOP -> FORCE_START (counters 1, 2, 3, each sent twice) over two stages, two tracker packets.
std::vector<Written> match_records() {
  std::vector<Written> records;
  for (std::uint32_t i = 0; i < 10; ++i) {
    records.push_back(
        {kStartNs + i * 100 * kMs, MessageType::kVision2014, vision_frame(i < 6 ? 0 : 1, i + 1)});
  }
  records.push_back({kStartNs + 1100 * kMs, MessageType::kVision2014, kGarbage});
  const std::array<std::pair<Referee::Command, Referee::Stage>, 3> commands = {
      std::pair{Referee::HALT, Referee::NORMAL_FIRST_HALF_PRE},
      std::pair{Referee::STOP, Referee::NORMAL_FIRST_HALF_PRE},
      std::pair{Referee::FORCE_START, Referee::NORMAL_FIRST_HALF}};
  for (std::uint32_t i = 0; i < 6; ++i) {
    const auto& [command, stage] = commands[i / 2];
    records.push_back({kStartNs + (1200 + i * 100) * kMs, MessageType::kRefbox2013,
                       referee_message(i / 2 + 1, command, stage)});
  }
  records.push_back({kStartNs + 2000 * kMs, MessageType::kVisionTracker2020, tracker_packet(1)});
  records.push_back({kStartNs + 2500 * kMs, MessageType::kVisionTracker2020, tracker_packet(2)});
  return records;
}

TEST(SslctlLogInfo, PrintsCountsDurationCamerasRefereeAndIndex) {
  TempFile file("info.log");
  write_log(file.path(), match_records(), /*index=*/true);
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(log_info(file.string(), false, out, err), 0) << err.str();
  const std::string text = out.str();
  for (const std::string& expected :
       {"(" + std::to_string(fs::file_size(file.path())) + " bytes, uncompressed)",
        std::string("index        yes (19 entries)"), std::string("records      19"),
        std::string("SSL_VISION_2014          11 (1 undecodable)"), std::string("SSL_REFBOX_2013          6"),
        std::string("SSL_VISION_TRACKER_2020  2"),
        std::string("first        2023-11-14 22:13:20.000 UTC (1700000000000000000 ns)"),
        std::string("last         2023-11-14 22:13:22.500 UTC"), std::string("duration     2.500 s"),
        std::string("cameras      2"), std::string("camera 0: 6 frames"), std::string("camera 1: 4 frames"),
        std::string("referee      3 commands"), std::string("commands: FORCE_START x1 HALT x1 STOP x1"),
        std::string("stages: NORMAL_FIRST_HALF_PRE NORMAL_FIRST_HALF")}) {
    EXPECT_NE(text.find(expected), std::string::npos) << "missing '" << expected << "' in\n" << text;
  }
  EXPECT_EQ(err.str(), "");
}

TEST(SslctlLogInfo, JsonHasEveryFigure) {
  TempFile file("info_json.log");
  write_log(file.path(), match_records(), /*index=*/true);
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(log_info(file.string(), true, out, err), 0) << err.str();
  const auto json = nlohmann::json::parse(out.str());
  EXPECT_EQ(json["file_bytes"], fs::file_size(file.path()));
  EXPECT_EQ(json["compression"], "none");
  EXPECT_EQ(json["data_bytes"], fs::file_size(file.path()));
  EXPECT_EQ(json["index"]["present"], true);
  EXPECT_EQ(json["index"]["entries"], 19);
  EXPECT_EQ(json["records"], 19);
  EXPECT_EQ(json["types"]["SSL_VISION_2014"], 11);
  EXPECT_EQ(json["types"]["SSL_REFBOX_2013"], 6);
  EXPECT_EQ(json["types"]["SSL_VISION_TRACKER_2020"], 2);
  EXPECT_EQ(json["undecodable"]["SSL_VISION_2014"], 1);
  EXPECT_EQ(json["first_timestamp_ns"], kStartNs);
  EXPECT_EQ(json["last_timestamp_ns"], kStartNs + 2500 * kMs);
  EXPECT_DOUBLE_EQ(json["duration_s"].get<double>(), 2.5);
  EXPECT_EQ(json["cameras"]["count"], 2);
  EXPECT_EQ(json["cameras"]["frames"]["0"], 6);
  EXPECT_EQ(json["cameras"]["frames"]["1"], 4);
  EXPECT_EQ(json["referee"]["commands"], 3);
  EXPECT_EQ(json["referee"]["stages"], nlohmann::json::array({"NORMAL_FIRST_HALF_PRE", "NORMAL_FIRST_HALF"}));
  EXPECT_TRUE(json["error"].is_null());
}

TEST(SslctlLogInfo, ReadsGzipLogs) {
  TempFile file("info.log.gz");
  write_log(file.path(), match_records());
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(log_info(file.string(), true, out, err), 0) << err.str();
  const auto json = nlohmann::json::parse(out.str());
  EXPECT_EQ(json["compression"], "gzip");
  EXPECT_EQ(json["index"]["present"], false);
  EXPECT_EQ(json["records"], 19);
  EXPECT_EQ(json["cameras"]["count"], 2);
  EXPECT_DOUBLE_EQ(json["duration_s"].get<double>(), 2.5);
  EXPECT_LT(json["file_bytes"].get<std::int64_t>(), json["data_bytes"].get<std::int64_t>());
}

TEST(SslctlLogInfo, DamagedFileReportsWhatWasReadableAndTheErrorWithItsOffset) {
  TempFile file("info_damaged.log");
  const auto records = match_records();
  write_log(file.path(), records);
  std::string bytes = read_bytes(file.path());
  // Record 3's size field becomes negative.
  std::size_t offset = 16;
  for (std::size_t i = 0; i < 3; ++i) offset += 16 + records[i].payload.size();
  bytes[offset + 12] = '\x80';
  write_bytes(file.path(), bytes);

  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(log_info(file.string(), false, out, err), 1);
  EXPECT_NE(err.str().find("record at offset " + std::to_string(offset) + ": negative payload size"),
            std::string::npos)
      << err.str();
  EXPECT_NE(out.str().find("records      3"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("damaged"), std::string::npos) << out.str();

  std::ostringstream json_out;
  EXPECT_EQ(log_info(file.string(), true, json_out, err), 1);
  EXPECT_NE(nlohmann::json::parse(json_out.str())["error"].get<std::string>().find("offset"),
            std::string::npos);
}

TEST(SslctlLogInfo, RejectsFilesThatAreNotLogs) {
  TempFile file("info_bad.log");
  write_bytes(file.path(), std::string("SSL_LOG_FILE") + std::string("\0\0\0\2", 4));
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(log_info(file.string(), false, out, err), 1);
  EXPECT_NE(err.str().find("unsupported log format version 2"), std::string::npos) << err.str();
  err.str("");
  EXPECT_EQ(log_info(file.string() + ".missing", false, out, err), 1);
  EXPECT_NE(err.str().find("cannot open"), std::string::npos) << err.str();
}

// ---------------------------------------------------------------------------------------------------
// Interoperability: a file laid out byte by byte as ssl-go-tools' recorder and indexer write it.

std::string go_tools_file(const std::vector<Written>& records) {
  std::string bytes = "SSL_LOG_FILE";
  put_be(bytes, 1, 4);
  std::vector<std::uint64_t> offsets;
  for (const Written& record : records) {
    offsets.push_back(bytes.size());
    put_be(bytes, static_cast<std::uint64_t>(record.timestamp_ns), 8);
    put_be(bytes, static_cast<std::uint32_t>(record.type), 4);
    put_be(bytes, record.payload.size(), 4);
    bytes += record.payload;
  }
  put_be(bytes, 0, 8);
  put_be(bytes, 6, 4);
  put_be(bytes, 8 * offsets.size() + 15, 4);
  for (const std::uint64_t offset : offsets) put_be(bytes, offset, 8);
  put_be(bytes, 16 + 8 * offsets.size() + 15, 8);
  bytes += "INDEXED";
  return bytes;
}

TEST(SslctlLogFormat, InfoAndReplayReadAHandBuiltIndexedFile) {
  TempFile file("go_tools.log");
  const std::vector<Written> records = {
      {kStartNs, MessageType::kVision2014, vision_frame(5, 1)},
      {kStartNs + 40 * kMs, MessageType::kRefbox2013, referee_message(7, Referee::HALT, Referee::POST_GAME)},
      {kStartNs + 80 * kMs, MessageType::kVision2014, vision_frame(5, 2)}};
  write_bytes(file.path(), go_tools_file(records));

  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(log_info(file.string(), true, out, err), 0) << err.str();
  const auto json = nlohmann::json::parse(out.str());
  EXPECT_EQ(json["index"]["present"], true);
  EXPECT_EQ(json["index"]["entries"], 3);
  EXPECT_FALSE(json["index"].contains("problem")) << json.dump();
  EXPECT_EQ(json["records"], 3);
  EXPECT_EQ(json["cameras"]["frames"]["5"], 2);
  EXPECT_EQ(json["referee"]["stages"], nlohmann::json::array({"POST_GAME"}));

  const LogStreamPorts ports = ports_from(25310);
  auto vision_rx = open_receiver(kVisionGroup, ports.vision);
  auto referee_rx = open_receiver(kRefereeGroup, ports.referee);
  ShutdownSignal shutdown;
  ASSERT_EQ(log_replay({.file = file.string(), .ports = ports, .speed = 4}, shutdown, out, err), 0)
      << err.str();
  EXPECT_EQ(payloads(receive_n(vision_rx, 3, milliseconds(200))),
            (std::vector<std::string>{records[0].payload, records[2].payload}));
  EXPECT_EQ(payloads(receive_n(referee_rx, 2, milliseconds(200))),
            std::vector<std::string>{records[1].payload});
}

TEST(SslctlLogFormat, InfoFlagsAnIndexThatDoesNotMatchTheRecords) {
  TempFile file("bad_index.log");
  const std::vector<Written> records = {{kStartNs, MessageType::kVision2014, vision_frame(0, 1)},
                                        {kStartNs + kMs, MessageType::kVision2014, vision_frame(0, 2)}};
  std::string bytes = go_tools_file(records);
  // The second index entry points into the header.
  const std::size_t entry = bytes.size() - 15 - 8;
  for (std::size_t i = 0; i < 8; ++i) bytes[entry + i] = i == 7 ? '\x04' : '\0';
  write_bytes(file.path(), bytes);
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(log_info(file.string(), false, out, err), 0) << err.str();
  EXPECT_NE(out.str().find("damaged index: entry 1 points to offset 4"), std::string::npos) << out.str();
}

// ---------------------------------------------------------------------------------------------------
// The binary

TEST(SslctlLogCli, InfoJsonAndUsageErrors) {
  TempFile file("cli.log");
  write_log(file.path(), match_records());
  auto info =
      testing::ChildProcess::start(testing::bin_dir() / "sslctl", {"log", "info", file.string(), "--json"});
  ASSERT_TRUE(info) << info.error().message;
  auto line = info->read_line(seconds(10));
  ASSERT_TRUE(line) << info->drain_stderr();
  EXPECT_EQ(nlohmann::json::parse(*line)["records"], 19);
  EXPECT_EQ(info->wait(seconds(10)), 0);

  auto bad_speed = testing::ChildProcess::start(testing::bin_dir() / "sslctl",
                                                {"log", "replay", file.string(), "--speed", "0"});
  ASSERT_TRUE(bad_speed);
  EXPECT_NE(bad_speed->wait(seconds(10)), 0);
  auto no_file = testing::ChildProcess::start(testing::bin_dir() / "sslctl", {"log", "record"});
  ASSERT_TRUE(no_file);
  EXPECT_NE(no_file->wait(seconds(10)), 0);
}

}  // namespace
}  // namespace ssl::sslctl
