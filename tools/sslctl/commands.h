// The sslctl commands, callable without the command-line parser. Each returns the process exit code
// (0 success, 1 failure, 2 usage error) and prints to the given streams: results to `out`, diagnostics to
// `err`, so that `sslctl topic echo ... | jq` sees only JSON.
#pragma once

#include <cstdint>
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

/// `sslctl health`: listens to system.health for `listen_s` seconds and prints one line per service.
int health(const DdsOptions& dds, double listen_s, bool json, ShutdownSignal& shutdown, std::ostream& out,
           std::ostream& err);

}  // namespace ssl::sslctl
