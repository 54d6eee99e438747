// The sslctl commands, callable without the command-line parser. Each returns the process exit code
// (0 success, 1 failure, 2 usage error) and prints to the given streams: results to `out`, diagnostics to
// `err`, so that `sslctl topic echo ... | jq` sees only JSON.
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "libs/common/shutdown.h"
#include "libs/common/team.h"

namespace ssl::sslctl {

struct DdsOptions {
  int domain_id = 0;
  std::optional<TeamColor> team;   // required for team-scoped topics
  std::string site;                // --site (else $SSL_SITE): the site's DDS discovery
};

/// `sslctl topic list`: every topic with its type, scope and QoS profiles; `json` prints JSON lines.
int topic_list(bool json, std::ostream& out);

struct EchoOptions {
  DdsOptions dds;
  std::string topic;
  std::uint64_t count = 0;         // stop after this many samples; 0 = until interrupted
  double timeout_s = 0;            // fail if `count` samples did not arrive in time; 0 = no limit
  bool with_meta = false;          // wrap each sample with its DDS time stamps
};

/// `sslctl topic echo TOPIC`: prints each sample as one JSON object per line.
int topic_echo(const EchoOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err);

struct HzOptions {
  DdsOptions dds;
  std::string topic;
  double window_s = 1.0;           // report period and averaging window
  double duration_s = 0;           // stop after this long; 0 = until interrupted
};

/// `sslctl topic hz TOPIC`: prints the receive rate and interval statistics once per window.
int topic_hz(const HzOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err);

struct PubOptions {
  DdsOptions dds;
  std::string topic;
  std::vector<std::string> samples; // (partial) JSON objects, written in order; missing fields keep defaults
  std::uint64_t repeat = 1;        // how many times to write the sequence
  double rate_hz = 10;             // write rate when repeating
  std::uint64_t wait_readers = 0;  // first wait until this many readers matched
  double wait_timeout_s = 10;      // ... for at most this long
  double linger_s = 0;             // keep the writer alive this long afterwards (transient-local state);
                                   // negative = until interrupted
};

/// `sslctl topic pub TOPIC JSON...`: writes samples built from JSON. Prints "published N" on stdout once written
/// (and acknowledged by reliable readers), then lingers as asked.
int topic_pub(const PubOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err);

/// `sslctl estop on|off`: engages or releases the emergency stop, and keeps asserting it until
/// interrupted (an e-stop whose source disappears is noticed by its readers through liveliness).
int estop(bool engage, const std::string& reason, const DdsOptions& dds, double linger_s,
          ShutdownSignal& shutdown, std::ostream& out, std::ostream& err);

struct ParamOptions {
  DdsOptions dds;
  std::string target;                    // service instance, e.g. "planner/blue" ("" with list: all)
  std::string key;                       // get
  std::vector<std::string> assignments;  // set: "key=value"
  bool save = false;                     // set: then save the instance's run-time parameters
  bool json = false;                     // list: one JSON object per instance
  double timeout_s = 3;                  // how long to wait for the instance
};

/// `sslctl param list [TARGET]`: every instance's run-time parameters (value, type, limits, meaning).
int param_list(const ParamOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err);
/// `sslctl param get TARGET KEY`: one value.
int param_get(const ParamOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err);
/// `sslctl param set TARGET KEY=VALUE... [--save]`: applies them all or none, waits for the answer; exit 1
/// with the instance's reason when it refused.
int param_set(const ParamOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err);

/// `sslctl health`: listens to system.health for `listen_s` seconds and prints one line per service.
int health(const DdsOptions& dds, double listen_s, bool json, ShutdownSignal& shutdown, std::ostream& out,
           std::ostream& err);

struct LatencyOptions {
  int domain_id = 0;
  std::string site;       // --site (else $SSL_SITE): the site's DDS discovery
  double listen_s = 5.0;  // how long to collect samples
  bool json = false;      // one JSON object per stage
};

/// `sslctl latency`: the pipeline's latency per stage, from the VisionStamp every vision-derived sample
/// carries: for vision.detection, world.state and robot.commands (both teams) the time from vision_gateway
/// receiving the camera frame to this process receiving the sample (p50 / p99 / max, ms); the last stage,
/// "command out of robot_link" (both teams), to the command packet leaving robot_link (robot.sent, robot_link's
/// own stamp; the packet that first carried each sample, not heartbeat resends); and the vision delay
/// (capture -> gateway receive). Clocks: the gateway's and this host's wall clocks (on different
/// hosts they must be synchronised, e.g. by PTP or chrony). 1 when nothing arrived.
int latency(const LatencyOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err);

// ---------------------------------------------------------------------------------------------------
// SSL log files (the league's format, libs/league/log_file.h): record, replay, info.

/// Multicast ports of the league's streams. Vision, legacy vision and tracker use group 224.5.23.2,
/// the referee 224.5.23.1.
struct LogStreamPorts {
  int vision = 10006;         // SSL_WrapperPacket, logged as SSL_VISION_2014
  int legacy_vision = 10005;  // legacy SSL_WrapperPacket, SSL_VISION_2010
  int referee = 10003;        // Referee, SSL_REFBOX_2013
  int tracker = 10010;        // TrackerWrapperPacket, SSL_VISION_TRACKER_2020
};

/// Records per stream of a recording or a replay.
struct LogStreamCounts {
  std::uint64_t vision = 0;
  std::uint64_t legacy_vision = 0;
  std::uint64_t referee = 0;
  std::uint64_t tracker = 0;
  std::uint64_t bytes = 0;        // payload bytes of those records
  std::uint64_t undecodable = 0;  // payloads that do not decode as their type (still recorded / sent)

  std::uint64_t total() const noexcept { return vision + legacy_vision + referee + tracker; }
};

struct LogRecordOptions {
  std::string file;                              // ".gz" suffix: gzip; otherwise uncompressed with index
  LogStreamPorts ports;
  std::string interface_address = "127.0.0.1";  // the NIC on the vision network at a match
  double duration_s = 0;                         // stop after this long; 0 = until interrupted
  bool legacy = true;                            // also record the legacy vision stream
  double progress_period_s = 1.0;                // progress line on `err` this often; 0 = never
  /// Called on the calling thread once every group is joined and the file is open (tests).
  std::function<void()> on_ready;
  /// Called after each record is written, from a receiving thread, with a lock held (tests).
  std::function<void(const LogStreamCounts&)> on_record;
};

/// `sslctl log record FILE`: writes every datagram of the vision, legacy vision, referee and tracker
/// streams, as received, into FILE with its receive time. Prints "recording ..." on `out` once the groups
/// are joined, progress on `err`, a summary on `out` after Ctrl-C / --duration. 1 on socket or I/O errors.
int log_record(const LogRecordOptions& options, ShutdownSignal& shutdown, std::ostream& out,
               std::ostream& err);

struct LogReplayOptions {
  std::string file;
  LogStreamPorts ports;
  std::string interface_address = "127.0.0.1";
  double speed = 1.0;              // > 0; 2 = twice as fast as recorded
  bool loop = false;               // start over at the end until interrupted
  double progress_period_s = 1.0;  // progress line on `err` this often; 0 = never
};

/// `sslctl log replay FILE`: sends every vision, legacy vision, referee and tracker record to its group
/// and port with the recorded timing divided by `speed`; other record types are skipped and counted.
/// A damaged file is replayed up to the damage, then the error (with its offset) is printed and 1 returned.
int log_replay(const LogReplayOptions& options, ShutdownSignal& shutdown, std::ostream& out,
               std::ostream& err);

/// `sslctl log info FILE`: records per type, first/last time stamp and duration, cameras and frames per
/// camera, referee commands and stages, index, file size; `json` prints one JSON object. On a damaged
/// file it prints what was readable, then the error (with its offset) on `err`, and returns 1.
int log_info(const std::string& file, bool json, std::ostream& out, std::ostream& err);

// ---------------------------------------------------------------------------------------------------
// Match report (tools/sslctl/match_report.h): what a match was, from its referee stream.

struct MatchReportOptions {
  std::string file;                              // an SSL log file; empty: the live streams
  int referee_port = 10003;                      // group 224.5.23.1
  int vision_port = 10006;                       // group 224.5.23.2 (the ball, the robots, the field's size)
  std::string interface_address = "127.0.0.1";  // the NIC on the league's network
  double duration_s = 0;                         // live: stop after this long; 0 = until Ctrl-C
  bool until_final_whistle = false;              // live: stop once the referee says POST_GAME
  bool json = false;                             // one JSON object
  /// Called once both groups are joined (live; tests).
  std::function<void()> on_ready;
};

/// `sslctl match report [FILE]`: reads Referee packets (and SSL-Vision: the ball, the robots, the field's
/// size) live from the multicast groups until --duration / Ctrl-C, or every record of an SSL log file, and
/// prints the match report (score and goals with their times, time in play / stopped and in play from vision,
/// commands, game events by type and team, placements and balls out per team, the longest stall, the closest
/// robots and contact frames, stages and sides). Malformed packets are counted in the report. 1 when no
/// referee packet came or
/// the file cannot be read (a damaged file: the report of what was read, then the error).
int match_report(const MatchReportOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err);

}  // namespace ssl::sslctl
