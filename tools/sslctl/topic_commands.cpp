#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "idl/idl_json.h"
#include "libs/dds/participant.h"
#include "tools/sslctl/commands.h"
#include "tools/sslctl/participant.h"

#include "libs/service/setup.h"

namespace ssl::sslctl {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::duration;
using std::chrono::duration_cast;
using std::chrono::milliseconds;
using std::chrono::nanoseconds;

constexpr auto kPollPeriod = milliseconds(100);

nanoseconds seconds_to_ns(double seconds) {
  return duration_cast<nanoseconds>(duration<double>(seconds));
}

std::string_view scope_name(dds::TopicScope scope) {
  switch (scope) {
    case dds::TopicScope::kShared: return "shared";
    case dds::TopicScope::kTeam: return "team";
    case dds::TopicScope::kTeamAddressed: return "team or all";
  }
  return "?";
}

/// The team argument for a topic: required for team-scoped topics, ignored for shared ones, optional for
/// team-addressed ones (none: every team).
Result<std::optional<TeamColor>> team_for(dds::TopicScope scope, std::string_view topic,
                                          const DdsOptions& options) {
  if (scope == dds::TopicScope::kTeam && !options.team) {
    return Error{"topic '" + std::string(topic) + "' is team-scoped: add --team blue|yellow"};
  }
  if (scope == dds::TopicScope::kShared) return std::optional<TeamColor>{};
  return options.team;
}

/// Opens a participant and, with `make(participant, spec, team)`, a reader or writer on `spec`'s topic.
/// On failure prints why to `err`, sets `status` (2 for a usage error, 1 otherwise) and returns nullopt.
template <typename Spec, typename Make>
auto open_endpoint(const Spec& spec, const DdsOptions& options, const std::string& participant_name,
                   std::ostream& err, int& status, Make make)
    -> std::optional<std::decay_t<decltype(*make(std::declval<dds::Participant&>(), spec, std::nullopt))>> {
  auto team = team_for(spec.scope, spec.name, options);
  if (!team) {
    err << "sslctl: " << team.error().message << '\n';
    status = 2;
    return std::nullopt;
  }
  auto participant = open_participant(options.domain_id, options.site, options.team, participant_name);
  if (!participant) {
    err << "sslctl: " << participant.error().message << '\n';
    status = 1;
    return std::nullopt;
  }
  auto endpoint = make(*participant, spec, *team);
  if (!endpoint) {
    err << "sslctl: " << endpoint.error().message << '\n';
    status = 1;
    return std::nullopt;
  }
  return std::move(*endpoint);
}

constexpr auto kMakeReader = [](dds::Participant& participant, const auto& spec, std::optional<TeamColor> team) {
  return participant.make_reader(spec, team);
};
constexpr auto kMakeWriter = [](dds::Participant& participant, const auto& spec, std::optional<TeamColor> team) {
  return participant.make_writer(spec, team);
};

int unknown_topic(const std::string& topic, std::ostream& err) {
  err << "sslctl: unknown topic '" << topic << "'; `sslctl topic list` shows them all\n";
  return 2;
}

}  // namespace

int topic_list(bool json, std::ostream& out) {
  const auto topics = dds::all_topics();
  if (json) {
    for (const auto& topic : topics) {
      out << nlohmann::json{{"name", topic.name},
                            {"type", topic.type_name},
                            {"scope", scope_name(topic.scope)},
                            {"writer_profile", topic.writer_profile},
                            {"reader_profile", topic.reader_profile},
                            {"description", topic.description}}
                 .dump()
          << '\n';
    }
    return 0;
  }
  out << std::left << std::setw(18) << "TOPIC" << std::setw(38) << "TYPE" << std::setw(8) << "SCOPE"
      << std::setw(34) << "QOS PROFILES" << "DESCRIPTION\n";
  for (const auto& topic : topics) {
    out << std::left << std::setw(18) << topic.name << std::setw(38) << topic.type_name << std::setw(8)
        << scope_name(topic.scope) << std::setw(34) << (topic.name + ".{writer,reader}") << topic.description
        << '\n';
  }
  return 0;
}

int topic_echo(const EchoOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err) {
  int status = 0;
  const bool known = dds::visit_topic(options.topic, [&](const auto& spec) {
    auto reader = open_endpoint(spec, options.dds, "sslctl/echo", err, status, kMakeReader);
    if (!reader) return;
    const auto deadline = Clock::now() + seconds_to_ns(options.timeout_s);
    std::uint64_t printed = 0;
    while (!shutdown.requested()) {
      reader->wait_for_data(kPollPeriod);
      for (const auto& sample : reader->take()) {
        nlohmann::json line = sample.data;
        if (options.with_meta) {
          line = nlohmann::json{{"topic", options.topic},
                                {"source_unix_ns", sample.source_unix_ns},
                                {"reception_unix_ns", sample.reception_unix_ns},
                                {"data", std::move(line)}};
        }
        out << line.dump() << '\n' << std::flush;
        if (options.count != 0 && ++printed >= options.count) return;
      }
      if (options.timeout_s > 0 && Clock::now() >= deadline) {
        err << "sslctl: timed out after " << options.timeout_s << " s with " << printed << " of "
            << options.count << " samples on '" << options.topic << "'\n";
        status = 1;
        return;
      }
    }
  });
  return known ? status : unknown_topic(options.topic, err);
}

int topic_hz(const HzOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err) {
  if (!(options.window_s > 0)) {
    err << "sslctl: --window must be positive\n";
    return 2;
  }
  int status = 0;
  const bool known = dds::visit_topic(options.topic, [&](const auto& spec) {
    auto reader = open_endpoint(spec, options.dds, "sslctl/hz", err, status, kMakeReader);
    if (!reader) return;
    const auto window = seconds_to_ns(options.window_s);
    const auto start = Clock::now();
    auto next_report = start + window;
    std::deque<std::int64_t> arrivals;  // reception times (host wall clock, ns) inside the window
    while (!shutdown.requested()) {
      reader->wait_for_data(kPollPeriod);
      for (const auto& sample : reader->take()) arrivals.push_back(sample.reception_unix_ns);
      const auto now = Clock::now();
      if (now < next_report) continue;
      next_report += window;
      if (!arrivals.empty()) {
        const std::int64_t newest = arrivals.back();
        while (!arrivals.empty() && arrivals.front() < newest - window.count()) arrivals.pop_front();
      }
      if (arrivals.size() < 2) {
        out << options.topic << ": no rate (" << arrivals.size() << " samples in the last " << options.window_s
            << " s)\n" << std::flush;
      } else {
        double sum = 0, sum_sq = 0, min_interval = INFINITY, max_interval = 0;
        for (std::size_t i = 1; i < arrivals.size(); ++i) {
          const double interval = static_cast<double>(arrivals[i] - arrivals[i - 1]) * 1e-9;
          sum += interval;
          sum_sq += interval * interval;
          min_interval = std::min(min_interval, interval);
          max_interval = std::max(max_interval, interval);
        }
        const double n = static_cast<double>(arrivals.size() - 1);
        const double mean = sum / n;
        const double stddev = std::sqrt(std::max(0.0, sum_sq / n - mean * mean));
        out << std::fixed << std::setprecision(2) << options.topic << ": " << 1.0 / mean << " Hz  min "
            << min_interval * 1e3 << " ms  max " << max_interval * 1e3 << " ms  std " << stddev * 1e3
            << " ms  window " << arrivals.size() << '\n' << std::flush;
      }
      if (options.duration_s > 0 && now - start >= seconds_to_ns(options.duration_s)) return;
    }
  });
  return known ? status : unknown_topic(options.topic, err);
}

int topic_pub(const PubOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err) {
  int status = 0;
  const bool known = dds::visit_topic(options.topic, [&](const auto& spec) {
    using Sample = typename std::decay_t<decltype(spec)>::Sample;
    std::vector<Sample> samples(options.samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
      try {
        nlohmann::json::parse(options.samples[i]).get_to(samples[i]);
      } catch (const std::exception& error) {
        err << "sslctl: sample " << i + 1 << " is not a valid " << options.topic << " JSON object: " << error.what()
            << '\n';
        status = 2;
        return;
      }
    }
    auto writer = open_endpoint(spec, options.dds, "sslctl/pub", err, status, kMakeWriter);
    if (!writer) return;
    if (options.wait_readers > 0 &&
        !writer->wait_for_match(options.wait_readers, seconds_to_ns(options.wait_timeout_s))) {
      err << "sslctl: no " << options.wait_readers << " reader(s) on '" << options.topic << "' within "
          << options.wait_timeout_s << " s\n";
      status = 1;
      return;
    }
    const auto period = options.rate_hz > 0 ? seconds_to_ns(1.0 / options.rate_hz) : nanoseconds(0);
    auto next = Clock::now();
    for (std::uint64_t i = 0; i < options.repeat && !shutdown.requested(); ++i) {
      if (i > 0) {
        next += period;
        std::this_thread::sleep_until(next);
      }
      for (const Sample& sample : samples) {
        if (auto written = writer->write(sample); !written) {
          err << "sslctl: " << written.error().message << '\n';
          status = 1;
          return;
        }
      }
    }
    // Reliable readers get every sample before the writer goes away; best-effort ones need no wait.
    writer->wait_for_acknowledgments(std::chrono::seconds(5));
    out << "published " << writer->counters().written << '\n' << std::flush;
    if (options.linger_s < 0) {
      shutdown.wait();
    } else if (options.linger_s > 0) {
      shutdown.wait_for(seconds_to_ns(options.linger_s));
    }
  });
  return known ? status : unknown_topic(options.topic, err);
}

Result<dds::Participant> open_participant(int domain_id, const std::string& site, std::optional<TeamColor> team,
                                          std::string name) {
  auto setup = service::prepare("", site, "");
  if (!setup) return setup.error();
  return dds::Participant::create({.domain_id = domain_id, .name = std::move(name), .discovery = setup->discovery,
                                   .security = setup->security, .identity = dds::identity::operator_of(team)});
}

}  // namespace ssl::sslctl
