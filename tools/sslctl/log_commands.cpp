// sslctl log record | replay | info: the league's SSL log files (libs/league/log_file.h) against the
// league's multicast streams (libs/net/multicast.h).
#include <time.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>
#include <vector>

#include "libs/league/decode.h"
#include "libs/league/log_file.h"
#include "libs/net/multicast.h"
#include "libs/time/clock.h"
#include "tools/sslctl/commands.h"

namespace ssl::sslctl {
namespace {

using league::MessageType;
using Steady = std::chrono::steady_clock;
using std::chrono::duration;
using std::chrono::duration_cast;
using std::chrono::milliseconds;
using std::chrono::nanoseconds;

constexpr std::string_view kVisionGroup = "224.5.23.2";
constexpr std::string_view kRefereeGroup = "224.5.23.1";
// Larger than any UDP payload (65507 bytes), so a datagram is never truncated.
constexpr std::size_t kDatagramBufferBytes = 65536;
// How often waiting loops look at the stop request and worker failures.
constexpr auto kPollPeriod = milliseconds(100);
// Shortest pass of a looping replay.
constexpr auto kMinimumPass = milliseconds(10);

nanoseconds seconds_to_ns(double seconds) { return duration_cast<nanoseconds>(duration<double>(seconds)); }

/// One league stream: the record type it is logged as and where it is multicast.
struct Stream {
  std::string_view label;  // "vision", for messages
  std::string_view flag;   // "--vision-port", for usage errors
  MessageType type;
  std::string_view group;
  int port = 0;
};

std::vector<Stream> streams_of(const LogStreamPorts& ports, bool legacy) {
  std::vector<Stream> streams;
  streams.push_back({"vision", "--vision-port", MessageType::kVision2014, kVisionGroup, ports.vision});
  if (legacy) {
    streams.push_back({"legacy vision", "--legacy-vision-port", MessageType::kVision2010, kVisionGroup,
                       ports.legacy_vision});
  }
  streams.push_back({"referee", "--referee-port", MessageType::kRefbox2013, kRefereeGroup, ports.referee});
  streams.push_back(
      {"tracker", "--tracker-port", MessageType::kVisionTracker2020, kVisionGroup, ports.tracker});
  return streams;
}

std::string endpoint_text(const Stream& stream) {
  return std::string(stream.group) + ":" + std::to_string(stream.port);
}

/// Ports in range; for recording also no two streams on one group:port (each socket would get every
/// datagram of the other stream, and the log would hold them twice under different types).
Status check_streams(const std::vector<Stream>& streams, bool distinct) {
  for (const Stream& stream : streams) {
    if (stream.port < 1 || stream.port > 65535) {
      return Error{std::string(stream.flag) + " " + std::to_string(stream.port) + " is not a port (1-65535)"};
    }
  }
  if (!distinct) return Status::success();
  for (std::size_t i = 0; i < streams.size(); ++i) {
    for (std::size_t j = i + 1; j < streams.size(); ++j) {
      if (streams[i].group == streams[j].group && streams[i].port == streams[j].port) {
        return Error{"the " + std::string(streams[i].label) + " and " + std::string(streams[j].label) +
                     " streams cannot share " + endpoint_text(streams[i]) + " (" +
                     std::string(streams[i].flag) + ", " + std::string(streams[j].flag) + ")"};
      }
    }
  }
  return Status::success();
}

/// The stream counter of a record type; nullptr for types that are not one of the four streams.
std::uint64_t* counter_of(LogStreamCounts& counts, MessageType type) {
  switch (type) {
    case MessageType::kVision2014: return &counts.vision;
    case MessageType::kVision2010: return &counts.legacy_vision;
    case MessageType::kRefbox2013: return &counts.referee;
    case MessageType::kVisionTracker2020: return &counts.tracker;
    default: return nullptr;
  }
}

/// Whether `bytes` decode as the message a record of `type` holds.
bool decodes(MessageType type, std::span<const std::uint8_t> bytes) {
  switch (type) {
    case MessageType::kVision2014: return league::decode_vision_wrapper(bytes).ok();
    case MessageType::kVision2010: return league::decode_legacy_vision_wrapper(bytes).ok();
    case MessageType::kRefbox2013: return league::decode_referee(bytes).ok();
    case MessageType::kVisionTracker2020: return league::decode_tracker_wrapper(bytes).ok();
    default: return false;
  }
}

bool is_gzip_name(const std::string& file) {
  return file.size() >= 3 && file.compare(file.size() - 3, 3, ".gz") == 0;
}

std::string format_bytes(std::uint64_t bytes) {
  if (bytes < 1000) return std::to_string(bytes) + " B";
  std::ostringstream text;
  text << std::fixed << std::setprecision(2);
  if (bytes < 1000 * 1000) {
    text << static_cast<double>(bytes) / 1e3 << " kB";
  } else if (bytes < 1000ULL * 1000 * 1000) {
    text << static_cast<double>(bytes) / 1e6 << " MB";
  } else {
    text << static_cast<double>(bytes) / 1e9 << " GB";
  }
  return text.str();
}

/// `value` with `decimals` digits after the point, without touching the state of the caller's stream.
std::string fixed(double value, int decimals) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(decimals) << value;
  return text.str();
}

std::string format_seconds(double seconds) { return fixed(seconds, 1) + " s"; }

/// "2024-07-18 10:22:31.123 UTC".
std::string format_unix_ns(std::int64_t unix_ns) {
  constexpr std::int64_t kNsPerSecond = 1'000'000'000;
  std::int64_t seconds = unix_ns / kNsPerSecond;
  std::int64_t rest = unix_ns % kNsPerSecond;
  if (rest < 0) {
    rest += kNsPerSecond;
    --seconds;
  }
  const auto time = static_cast<std::time_t>(seconds);
  std::tm calendar{};
  if (gmtime_r(&time, &calendar) == nullptr) return std::to_string(unix_ns) + " ns";
  std::array<char, 32> text{};
  std::strftime(text.data(), text.size(), "%Y-%m-%d %H:%M:%S", &calendar);
  std::ostringstream out;
  out << text.data() << '.' << std::setw(3) << std::setfill('0') << rest / 1'000'000 << " UTC";
  return out.str();
}

std::string stream_counts_text(const LogStreamCounts& counts, bool legacy) {
  std::ostringstream text;
  text << "vision " << counts.vision;
  if (legacy) text << ", legacy vision " << counts.legacy_vision;
  text << ", referee " << counts.referee << ", tracker " << counts.tracker;
  return text.str();
}

// ---------------------------------------------------------------------------------------------------
// record

/// The file being written, shared by one receiving thread per stream.
class Recording {
 public:
  Recording(league::LogWriter writer, std::function<void(const LogStreamCounts&)> on_record)
      : writer_(std::move(writer)), on_record_(std::move(on_record)) {}

  /// Appends one datagram as received (a recorder does not judge), counting it.
  void add(std::int64_t received_unix_ns, MessageType type, std::span<const std::uint8_t> datagram,
           bool decodable) {
    std::lock_guard lock(mutex_);
    if (failure_) return;
    if (Status written = writer_.write(received_unix_ns, type, datagram); !written) {
      failure_ = written.error();
      return;
    }
    if (std::uint64_t* counter = counter_of(counts_, type)) ++*counter;
    counts_.bytes += datagram.size();
    if (!decodable) ++counts_.undecodable;
    if (on_record_) on_record_(counts_);
  }

  void fail(Error error) {
    std::lock_guard lock(mutex_);
    if (!failure_) failure_ = std::move(error);
  }

  std::optional<Error> failure() const {
    std::lock_guard lock(mutex_);
    return failure_;
  }

  LogStreamCounts counts() const {
    std::lock_guard lock(mutex_);
    return counts_;
  }

  /// Writes the index (uncompressed files) and closes; call after every receiving thread ended.
  Status close() {
    std::lock_guard lock(mutex_);
    return writer_.close();
  }

 private:
  mutable std::mutex mutex_;
  league::LogWriter writer_;
  LogStreamCounts counts_;
  std::optional<Error> failure_;
  std::function<void(const LogStreamCounts&)> on_record_;
};

/// One thread per stream: receives until `stopping`, then takes what is already queued (everything sent
/// before the stop request is in the log) and returns.
void receive_stream(net::MulticastReceiver& receiver, const Stream& stream, Recording& recording,
                    const std::atomic<bool>& stopping) {
  time::RealClock wall_clock;
  std::vector<std::uint8_t> buffer(kDatagramBufferBytes);
  for (;;) {
    const bool draining = stopping.load();
    const net::ReceiveResult result = receiver.receive(buffer, draining ? nanoseconds(0) : kPollPeriod);
    switch (result.status) {
      case net::ReceiveStatus::kReceived: {
        const std::int64_t received_unix_ns = wall_clock.now().nanoseconds();
        const auto datagram = std::span<const std::uint8_t>(buffer).first(result.size);
        recording.add(received_unix_ns, stream.type, datagram, decodes(stream.type, datagram));
        break;
      }
      case net::ReceiveStatus::kTimeout:
        if (draining) return;
        break;
      case net::ReceiveStatus::kInterrupted: return;
      case net::ReceiveStatus::kTruncated:  // cannot happen with a 64 KiB buffer
        recording.fail(Error{"a datagram of " + std::to_string(result.size) + " bytes on " +
                             endpoint_text(stream) + " did not fit the receive buffer"});
        return;
      case net::ReceiveStatus::kError:
        recording.fail(Error{"receiving the " + std::string(stream.label) + " stream on " +
                             endpoint_text(stream) + " failed: " + result.error});
        return;
    }
  }
}

}  // namespace

int log_record(const LogRecordOptions& options, ShutdownSignal& shutdown, std::ostream& out,
               std::ostream& err) {
  if (options.file.empty()) {
    err << "sslctl: log record needs a FILE\n";
    return 2;
  }
  if (!std::isfinite(options.duration_s) || options.duration_s < 0) {
    err << "sslctl: --duration must be a non-negative number of seconds\n";
    return 2;
  }
  const std::vector<Stream> streams = streams_of(options.ports, options.legacy);
  if (Status valid = check_streams(streams, /*distinct=*/true); !valid) {
    err << "sslctl: " << valid.error().message << '\n';
    return 2;
  }

  // Join every group before creating the file, so that a bad interface leaves no empty log behind.
  std::vector<net::MulticastReceiver> receivers;
  receivers.reserve(streams.size());
  for (const Stream& stream : streams) {
    auto receiver = net::MulticastReceiver::open(stream.group, stream.port, options.interface_address);
    if (!receiver) {
      err << "sslctl: cannot receive the " << stream.label << " stream: " << receiver.error().message << '\n';
      return 1;
    }
    receivers.push_back(std::move(*receiver));
  }

  // Like ssl-go-tools' recorder + indexer: gzip by suffix; an uncompressed file gets the INDEX_2021 trailer.
  const bool gzip = is_gzip_name(options.file);
  auto writer = league::LogWriter::open(
      options.file, {.compression = league::Compression::kBySuffix, .write_index = !gzip});
  if (!writer) {
    err << "sslctl: " << writer.error().message << '\n';
    return 1;
  }
  Recording recording(std::move(*writer), options.on_record);

  out << "recording to " << options.file << " (" << (gzip ? "gzip" : "uncompressed, indexed") << "):";
  for (std::size_t i = 0; i < streams.size(); ++i) {
    out << (i == 0 ? " " : ", ") << streams[i].label << ' ' << endpoint_text(streams[i]);
  }
  out << " on interface " << options.interface_address << '\n' << std::flush;

  std::atomic<bool> stopping{false};
  std::vector<std::thread> threads;
  threads.reserve(streams.size());
  for (std::size_t i = 0; i < streams.size(); ++i) {
    threads.emplace_back(receive_stream, std::ref(receivers[i]), std::cref(streams[i]), std::ref(recording),
                         std::cref(stopping));
  }
  if (options.on_ready) options.on_ready();

  const auto start = Steady::now();
  const bool timed = options.duration_s > 0;
  const auto deadline = timed ? start + seconds_to_ns(options.duration_s) : Steady::time_point::max();
  const bool progress = options.progress_period_s > 0;
  const nanoseconds progress_period = progress ? seconds_to_ns(options.progress_period_s) : nanoseconds(0);
  auto next_progress = progress ? start + progress_period : Steady::time_point::max();
  for (;;) {
    const auto now = Steady::now();
    if (now >= deadline || recording.failure()) break;
    if (now >= next_progress) {
      const LogStreamCounts counts = recording.counts();
      err << "recording " << options.file << ": " << format_seconds(duration<double>(now - start).count())
          << ", " << counts.total() << " records (" << stream_counts_text(counts, options.legacy) << "), "
          << format_bytes(counts.bytes) << ", " << counts.undecodable << " undecodable\n"
          << std::flush;
      while (next_progress <= now) next_progress += progress_period;
    }
    const auto wake = std::min({deadline, next_progress, now + kPollPeriod});
    if (shutdown.wait_for(wake - now)) break;
  }
  const double elapsed_s = duration<double>(Steady::now() - start).count();

  stopping = true;
  for (std::thread& thread : threads) thread.join();
  const Status closed = recording.close();
  const LogStreamCounts counts = recording.counts();

  out << "recorded " << counts.total() << " records in " << format_seconds(elapsed_s) << " to "
      << options.file << ": " << stream_counts_text(counts, options.legacy) << "; "
      << format_bytes(counts.bytes) << " of payload; " << counts.undecodable << " undecodable\n"
      << std::flush;
  int status = 0;
  if (std::optional<Error> failure = recording.failure()) {
    err << "sslctl: recording stopped: " << failure->message << '\n';
    status = 1;
  }
  if (!closed) {
    err << "sslctl: " << closed.error().message << '\n';
    status = 1;
  }
  return status;
}

// ---------------------------------------------------------------------------------------------------
// replay

namespace {

bool is_replayable(MessageType type) {
  return type == MessageType::kVision2014 || type == MessageType::kVision2010 ||
         type == MessageType::kRefbox2013 || type == MessageType::kVisionTracker2020;
}

/// The time span of the replayable records, found before replaying so that progress can show a
/// percentage.
struct ReplaySpan {
  std::int64_t first_ns = 0;
  std::int64_t last_ns = 0;
  bool any = false;
  std::optional<Error> damage;  // where a scan stopped early

  void add(std::int64_t timestamp_ns) {
    if (!any) first_ns = timestamp_ns;
    last_ns = timestamp_ns;
    any = true;
  }
};

/// Through the index of an uncompressed file: the first replayable record from the start, the last
/// from the end. nullopt if the file has no usable index.
std::optional<ReplaySpan> span_from_index(const std::string& file) {
  auto offsets = league::read_log_index(file);
  if (!offsets || offsets->empty()) return std::nullopt;
  auto reader = league::LogReader::open(file);
  if (!reader) return std::nullopt;
  ReplaySpan span;
  for (;;) {
    auto record = reader->next();
    if (!record || !*record) return std::nullopt;
    if (is_replayable((*record)->type)) {
      span.add((*record)->timestamp_ns);
      break;
    }
  }
  for (auto offset = offsets->rbegin(); offset != offsets->rend(); ++offset) {
    if (!reader->seek(*offset)) return std::nullopt;
    auto record = reader->next();
    if (!record || !*record) return std::nullopt;
    if (is_replayable((*record)->type)) {
      span.last_ns = (*record)->timestamp_ns;
      return span;
    }
  }
  return std::nullopt;
}

/// Reads the whole file (gzip, or no index), up to damage if any.
ReplaySpan span_by_scanning(league::LogReader& reader) {
  ReplaySpan span;
  for (;;) {
    auto record = reader.next();
    if (!record) {
      span.damage = record.error();
      return span;
    }
    if (!*record) return span;
    if (is_replayable((*record)->type)) span.add((*record)->timestamp_ns);
  }
}

}  // namespace

int log_replay(const LogReplayOptions& options, ShutdownSignal& shutdown, std::ostream& out,
               std::ostream& err) {
  if (options.file.empty()) {
    err << "sslctl: log replay needs a FILE\n";
    return 2;
  }
  if (!std::isfinite(options.speed) || options.speed <= 0) {
    err << "sslctl: --speed must be a positive number\n";
    return 2;
  }
  const std::vector<Stream> streams = streams_of(options.ports, /*legacy=*/true);
  if (Status valid = check_streams(streams, /*distinct=*/false); !valid) {
    err << "sslctl: " << valid.error().message << '\n';
    return 2;
  }

  auto first_reader = league::LogReader::open(options.file);
  if (!first_reader) {
    err << "sslctl: " << first_reader.error().message << '\n';
    return 1;
  }
  std::optional<ReplaySpan> span = span_from_index(options.file);
  if (!span) span = span_by_scanning(*first_reader);
  if (!span->any && span->damage) {
    err << "sslctl: nothing to replay before the damaged data: " << span->damage->message << '\n';
    return 1;
  }
  if (!span->any) {
    err << "sslctl: " << options.file
        << " holds no record to replay (SSL_VISION_2014, SSL_VISION_2010, SSL_REFBOX_2013 or "
           "SSL_VISION_TRACKER_2020)\n";
    return 1;
  }
  const double duration_s = static_cast<double>(span->last_ns - span->first_ns) * 1e-9;

  std::map<MessageType, net::MulticastSender> senders;
  for (const Stream& stream : streams) {
    auto sender = net::MulticastSender::open(stream.group, stream.port, options.interface_address);
    if (!sender) {
      err << "sslctl: cannot send the " << stream.label << " stream: " << sender.error().message << '\n';
      return 1;
    }
    senders.emplace(stream.type, std::move(*sender));
  }

  out << "replaying " << options.file << " (" << format_seconds(duration_s) << " at speed " << options.speed
      << (options.loop ? ", looping" : "") << ") on interface " << options.interface_address << '\n'
      << std::flush;

  LogStreamCounts sent;
  std::uint64_t skipped = 0;
  std::uint64_t send_errors = 0;
  std::uint64_t loops = 0;
  double position_s = 0;
  bool stopped = false;
  std::optional<Error> damage;

  const auto replay_start = Steady::now();
  const bool progress = options.progress_period_s > 0;
  const nanoseconds progress_period = progress ? seconds_to_ns(options.progress_period_s) : nanoseconds(0);
  auto next_progress = progress ? replay_start + progress_period : Steady::time_point::max();
  auto report_progress_if_due = [&](Steady::time_point now) {
    if (now < next_progress) return;
    err << "replay " << options.file << ": " << format_seconds(position_s) << " / "
        << format_seconds(duration_s) << " ("
        << fixed(duration_s > 0 ? 100.0 * std::clamp(position_s / duration_s, 0.0, 1.0) : 100.0, 1) << "%), "
        << sent.total() << " records sent";
    if (skipped > 0) err << ", " << skipped << " skipped";
    if (options.loop) err << ", loop " << loops + 1;
    err << '\n' << std::flush;
    while (next_progress <= now) next_progress += progress_period;
  };

  while (!stopped && !damage) {
    auto reader = league::LogReader::open(options.file);
    if (!reader) {
      damage = reader.error();
      break;
    }
    // Every record is due at a fixed offset from this pass's start: sleeping never accumulates drift.
    const auto pass_start = Steady::now();
    for (;;) {
      auto record = reader->next();
      if (!record) {
        damage = record.error();
        break;
      }
      if (!*record) break;
      const league::LogRecord& entry = **record;
      if (entry.type == MessageType::kIndex2021) continue;
      if (!is_replayable(entry.type)) {
        ++skipped;
        continue;
      }
      const auto offset_ns = static_cast<double>(entry.timestamp_ns - span->first_ns);
      const auto due = pass_start + nanoseconds(static_cast<std::int64_t>(offset_ns / options.speed));
      for (auto now = Steady::now(); now < due && !stopped; now = Steady::now()) {
        report_progress_if_due(now);
        stopped = shutdown.wait_for(std::min(due, next_progress) - now);
      }
      if (stopped || shutdown.requested()) {
        stopped = true;
        break;
      }
      const auto payload = league::byte_span(entry.payload);
      if (Status sent_ok = senders.at(entry.type).send(payload); !sent_ok) {
        if (send_errors == 0) err << "sslctl: " << sent_ok.error().message << '\n';
        ++send_errors;
      } else {
        ++*counter_of(sent, entry.type);
        sent.bytes += payload.size();
      }
      position_s = offset_ns * 1e-9;
      report_progress_if_due(Steady::now());
    }
    if (!stopped && !damage) ++loops;
    if (!options.loop) break;
    // A log whose records all share one time stamp would otherwise be sent in a busy loop.
    const auto earliest_next_pass = pass_start + kMinimumPass;
    for (auto now = Steady::now(); now < earliest_next_pass && !stopped; now = Steady::now()) {
      stopped = shutdown.wait_for(earliest_next_pass - now);
    }
  }

  out << "replayed " << sent.total() << " records (" << stream_counts_text(sent, true) << ", "
      << format_bytes(sent.bytes) << ") in "
      << format_seconds(duration<double>(Steady::now() - replay_start).count());
  if (options.loop) out << ", " << loops << " full pass(es)";
  out << "; " << skipped << " skipped (not a vision, referee or tracker record)";
  if (send_errors > 0) out << "; " << send_errors << " send errors";
  out << '\n' << std::flush;
  if (damage) {
    err << "sslctl: replay stopped at damaged data: " << damage->message << '\n';
    return 1;
  }
  return send_errors > 0 ? 1 : 0;
}

// ---------------------------------------------------------------------------------------------------
// info

namespace {

struct LogSummary {
  std::uint64_t file_bytes = 0;
  bool gzip = false;
  std::int64_t data_bytes = 0;  // uncompressed bytes read
  std::map<std::int32_t, std::uint64_t> records_by_type;
  std::map<std::int32_t, std::uint64_t> undecodable_by_type;
  std::uint64_t records = 0;  // every record but the index
  std::optional<std::int64_t> first_ns;
  std::int64_t last_ns = 0;
  std::map<std::uint32_t, std::uint64_t> frames_by_camera;
  std::uint64_t geometry_packets = 0;
  std::map<std::uint32_t, Referee::Command> command_by_counter;
  std::vector<Referee::Stage> stages;  // in order of first appearance
  bool index_record = false;
  std::optional<std::uint64_t> index_entries;
  std::optional<std::string> index_problem;
  std::optional<Error> error;
};

bool file_is_gzip(const std::string& file) {
  std::FILE* handle = std::fopen(file.c_str(), "rb");
  if (handle == nullptr) return false;
  std::array<unsigned char, 2> magic{};
  const bool gzip = std::fread(magic.data(), 1, magic.size(), handle) == magic.size() && magic[0] == 0x1F &&
                    magic[1] == 0x8B;
  std::fclose(handle);
  return gzip;
}

void inspect_payload(const league::LogRecord& record, LogSummary& summary) {
  const auto bytes = league::byte_span(record.payload);
  const auto type_number = static_cast<std::int32_t>(record.type);
  bool ok = true;
  switch (record.type) {
    case MessageType::kVision2014: {
      auto packet = league::decode_vision_wrapper(bytes);
      ok = packet.ok();
      if (ok && packet->has_detection()) ++summary.frames_by_camera[packet->detection().camera_id()];
      if (ok && packet->has_geometry()) ++summary.geometry_packets;
      break;
    }
    case MessageType::kRefbox2013: {
      auto referee = league::decode_referee(bytes);
      ok = referee.ok();
      if (ok) {
        summary.command_by_counter.emplace(referee->command_counter(), referee->command());
        if (std::find(summary.stages.begin(), summary.stages.end(), referee->stage()) ==
            summary.stages.end()) {
          summary.stages.push_back(referee->stage());
        }
      }
      break;
    }
    case MessageType::kVision2010:
    case MessageType::kVisionTracker2020: ok = decodes(record.type, bytes); break;
    default: return;
  }
  if (!ok) ++summary.undecodable_by_type[type_number];
}

LogSummary summarize(const std::string& file, league::LogReader& reader) {
  LogSummary summary;
  std::error_code size_error;
  summary.file_bytes = std::filesystem::file_size(file, size_error);
  if (size_error) summary.file_bytes = 0;
  summary.gzip = file_is_gzip(file);
  summary.data_bytes = static_cast<std::int64_t>(league::kLogHeaderBytes);  // the reader checked it
  for (;;) {
    auto record = reader.next();
    if (!record) {
      summary.error = record.error();
      break;
    }
    if (!*record) break;
    const league::LogRecord& entry = **record;
    summary.data_bytes =
        entry.offset + static_cast<std::int64_t>(league::kLogRecordHeaderBytes + entry.payload.size());
    if (entry.type == MessageType::kIndex2021) {
      summary.index_record = true;
      // The trailer's payload is 8 bytes per entry plus 8 + "INDEXED".
      if (entry.payload.size() >= 15) summary.index_entries = (entry.payload.size() - 15) / 8;
      continue;
    }
    ++summary.records;
    ++summary.records_by_type[static_cast<std::int32_t>(entry.type)];
    if (!summary.first_ns) summary.first_ns = entry.timestamp_ns;
    summary.last_ns = entry.timestamp_ns;
    inspect_payload(entry, summary);
  }
  if (summary.index_record && !summary.gzip) {
    // Check the trailer the way a seeking reader uses it.
    auto offsets = league::read_log_index(file);
    if (!offsets) {
      summary.index_problem = offsets.error().message;
    } else {
      summary.index_entries = offsets->size();
      if (!summary.error && offsets->size() != summary.records) {
        summary.index_problem = "it lists " + std::to_string(offsets->size()) + " records, the file holds " +
                                std::to_string(summary.records);
      }
    }
  }
  return summary;
}

std::string type_name(std::int32_t type) { return league::to_string(static_cast<MessageType>(type)); }

std::map<std::string, std::uint64_t> commands_seen(const LogSummary& summary) {
  std::map<std::string, std::uint64_t> commands;
  for (const auto& [counter, command] : summary.command_by_counter) {
    ++commands[Referee::Command_Name(command)];
  }
  return commands;
}

double duration_of(const LogSummary& summary) {
  return summary.first_ns ? static_cast<double>(summary.last_ns - *summary.first_ns) * 1e-9 : 0.0;
}

void print_json(const std::string& file, const LogSummary& summary, std::ostream& out) {
  nlohmann::ordered_json json;
  json["file"] = file;
  json["file_bytes"] = summary.file_bytes;
  json["compression"] = summary.gzip ? "gzip" : "none";
  json["data_bytes"] = summary.data_bytes;
  nlohmann::ordered_json index;
  index["present"] = summary.index_record;
  if (summary.index_entries) index["entries"] = *summary.index_entries;
  if (summary.index_problem) index["problem"] = *summary.index_problem;
  json["index"] = index;
  json["records"] = summary.records;
  nlohmann::ordered_json types = nlohmann::ordered_json::object();
  for (const auto& [type, count] : summary.records_by_type) types[type_name(type)] = count;
  json["types"] = types;
  nlohmann::ordered_json undecodable = nlohmann::ordered_json::object();
  for (const auto& [type, count] : summary.undecodable_by_type) undecodable[type_name(type)] = count;
  json["undecodable"] = undecodable;
  if (summary.first_ns) {
    json["first_timestamp_ns"] = *summary.first_ns;
    json["last_timestamp_ns"] = summary.last_ns;
  } else {
    json["first_timestamp_ns"] = nullptr;
    json["last_timestamp_ns"] = nullptr;
  }
  json["duration_s"] = duration_of(summary);
  nlohmann::ordered_json frames = nlohmann::ordered_json::object();
  for (const auto& [camera, count] : summary.frames_by_camera) frames[std::to_string(camera)] = count;
  json["cameras"] = {{"count", summary.frames_by_camera.size()}, {"frames", frames}};
  json["geometry_packets"] = summary.geometry_packets;
  nlohmann::ordered_json stages = nlohmann::ordered_json::array();
  for (const Referee::Stage stage : summary.stages) stages.push_back(Referee::Stage_Name(stage));
  nlohmann::ordered_json commands = nlohmann::ordered_json::object();
  for (const auto& [name, count] : commands_seen(summary)) commands[name] = count;
  json["referee"] = {
      {"commands", summary.command_by_counter.size()}, {"command_types", commands}, {"stages", stages}};
  if (summary.error) {
    json["error"] = summary.error->message;
  } else {
    json["error"] = nullptr;
  }
  out << json.dump() << '\n';
}

void print_text(const std::string& file, const LogSummary& summary, std::ostream& out) {
  constexpr int kLabel = 13;
  auto label = [&](std::string_view name) -> std::ostream& {
    return out << std::left << std::setw(kLabel) << name << std::right;
  };
  label("file") << file << " (" << summary.file_bytes << " bytes, "
                << (summary.gzip ? "gzip, " + std::to_string(summary.data_bytes) + " bytes uncompressed"
                                 : std::string("uncompressed"))
                << ")\n";
  label("index");
  if (!summary.index_record) {
    out << "no\n";
  } else {
    out << "yes";
    if (summary.index_entries) out << " (" << *summary.index_entries << " entries)";
    if (summary.index_problem) out << ", damaged: " << *summary.index_problem;
    out << '\n';
  }
  label("records") << summary.records << '\n';
  std::size_t width = 0;
  for (const auto& [type, count] : summary.records_by_type) width = std::max(width, type_name(type).size());
  for (const auto& [type, count] : summary.records_by_type) {
    out << "  " << std::left << std::setw(static_cast<int>(width) + 2) << type_name(type) << std::right
        << count;
    if (auto bad = summary.undecodable_by_type.find(type); bad != summary.undecodable_by_type.end()) {
      out << " (" << bad->second << " undecodable)";
    }
    out << '\n';
  }
  if (summary.first_ns) {
    label("first") << format_unix_ns(*summary.first_ns) << " (" << *summary.first_ns << " ns)\n";
    label("last") << format_unix_ns(summary.last_ns) << " (" << summary.last_ns << " ns)\n";
  }
  label("duration") << fixed(duration_of(summary), 3) << " s\n";
  label("cameras") << summary.frames_by_camera.size() << '\n';
  for (const auto& [camera, count] : summary.frames_by_camera) {
    out << "  camera " << camera << ": " << count << " frames\n";
  }
  label("geometry") << summary.geometry_packets << " packets\n";
  label("referee") << summary.command_by_counter.size() << " commands (distinct command_counter values)\n";
  if (!summary.command_by_counter.empty()) {
    out << "  commands:";
    for (const auto& [name, count] : commands_seen(summary)) out << ' ' << name << " x" << count;
    out << '\n';
  }
  if (!summary.stages.empty()) {
    out << "  stages:";
    for (const Referee::Stage stage : summary.stages) out << ' ' << Referee::Stage_Name(stage);
    out << '\n';
  }
  if (summary.error) label("damaged") << "yes: only the records before the damage are counted above\n";
}

}  // namespace

int log_info(const std::string& file, bool json, std::ostream& out, std::ostream& err) {
  auto reader = league::LogReader::open(file);
  if (!reader) {
    err << "sslctl: " << reader.error().message << '\n';
    return 1;
  }
  const LogSummary summary = summarize(file, *reader);
  if (json) {
    print_json(file, summary, out);
  } else {
    print_text(file, summary, out);
  }
  out << std::flush;
  if (summary.error) {
    err << "sslctl: " << summary.error->message << '\n';
    return 1;
  }
  return 0;
}

}  // namespace ssl::sslctl
