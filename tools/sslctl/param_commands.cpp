// sslctl param list|get|set|save: the run-time parameters of the services (system.params requests,
// system.param_state answers).
#include <chrono>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "libs/dds/participant.h"
#include "libs/dds/topics.h"
#include "tools/sslctl/commands.h"
#include "tools/sslctl/participant.h"

namespace ssl::sslctl {
namespace {

using Clock = std::chrono::steady_clock;
using idl::system::ParameterState;

std::chrono::nanoseconds seconds(double s) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double>(s));
}

std::int64_t wall_clock_unix_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

nlohmann::json to_json(const ParameterState& state) {
  nlohmann::json params = nlohmann::json::array();
  for (const auto& p : state.params()) {
    params.push_back({{"key", p.key()},
                      {"value", p.value()},
                      {"type", p.type()},
                      {"min", p.has_min() ? nlohmann::json(p.min()) : nlohmann::json(nullptr)},
                      {"max", p.has_max() ? nlohmann::json(p.max()) : nlohmann::json(nullptr)},
                      {"allowed", p.allowed()},
                      {"unit", p.unit()},
                      {"description", p.description()}});
  }
  return {{"target", state.target()},   {"params", params},       {"revision", state.revision()},
          {"accepted", state.accepted()}, {"reason", state.reason()}, {"saved_file", state.saved_file()}};
}

std::string limits_text(const idl::system::ParameterInfo& p) {
  std::ostringstream text;
  text << p.type();
  if (p.has_min() && p.has_max()) {
    text << " in [" << p.min() << ", " << p.max() << "]";
  } else if (p.has_min()) {
    text << " >= " << p.min();
  } else if (p.has_max()) {
    text << " <= " << p.max();
  }
  if (!p.unit().empty()) text << " " << p.unit();
  return text.str();
}

/// Every target's state heard within `listen_s` (or, with `target`, until that one was heard).
std::map<std::string, ParameterState> collect(dds::Reader<ParameterState>& reader, const std::string& target,
                                              double listen_s, ShutdownSignal& shutdown) {
  std::map<std::string, ParameterState> states;
  const auto deadline = Clock::now() + seconds(listen_s);
  while (!shutdown.requested() && Clock::now() < deadline) {
    reader.wait_for_data(std::chrono::milliseconds(50));
    for (auto& sample : reader.take()) states[sample.data.target()] = sample.data;
    if (!target.empty() && states.contains(target)) break;
  }
  return states;
}

/// A participant's reader of system.param_state (and, with `writer`, a writer of system.params); nullopt
/// after printing why.
struct ParamEndpoints {
  dds::Reader<ParameterState> states;
  std::optional<dds::Writer<idl::system::ParameterSet>> requests;
};

std::optional<ParamEndpoints> open_endpoints(const ParamOptions& options, bool writer, std::ostream& err) {
  auto participant = open_participant(options.dds.domain_id, options.dds.site, options.dds.team, "sslctl/param");
  if (!participant) {
    err << "sslctl: " << participant.error().message << '\n';
    return std::nullopt;
  }
  auto reader = participant->make_reader(dds::topics::kSystemParamState);
  if (!reader) {
    err << "sslctl: " << reader.error().message << '\n';
    return std::nullopt;
  }
  ParamEndpoints endpoints{std::move(*reader), std::nullopt};
  if (writer) {
    auto requests = participant->make_writer(dds::topics::kSystemParams);
    if (!requests) {
      err << "sslctl: " << requests.error().message << '\n';
      return std::nullopt;
    }
    endpoints.requests.emplace(std::move(*requests));
  }
  return endpoints;
}

}  // namespace

int param_list(const ParamOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err) {
  auto endpoints = open_endpoints(options, false, err);
  if (!endpoints) return 1;
  const auto states = collect(endpoints->states, options.target, options.timeout_s, shutdown);
  if (!options.target.empty() && !states.contains(options.target)) {
    err << "sslctl: no parameters from '" << options.target << "' within " << options.timeout_s
        << " s (is it running on domain " << options.dds.domain_id << "?)\n";
    return 1;
  }
  for (const auto& [target, state] : states) {
    if (!options.target.empty() && target != options.target) continue;
    if (options.json) {
      out << to_json(state).dump() << '\n';
      continue;
    }
    out << target << (state.saved_file().empty() ? "" : "  (saved in " + state.saved_file() + ")") << '\n';
    for (const auto& p : state.params()) {
      out << "  " << std::left << std::setw(44) << p.key() << std::setw(10) << p.value() << std::setw(34)
          << limits_text(p) << p.description() << '\n';
    }
  }
  return 0;
}

int param_get(const ParamOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err) {
  auto endpoints = open_endpoints(options, false, err);
  if (!endpoints) return 1;
  const auto states = collect(endpoints->states, options.target, options.timeout_s, shutdown);
  const auto state = states.find(options.target);
  if (state == states.end()) {
    err << "sslctl: no parameters from '" << options.target << "' within " << options.timeout_s << " s\n";
    return 1;
  }
  for (const auto& p : state->second.params()) {
    if (p.key() == options.key) {
      out << p.value() << '\n';
      return 0;
    }
  }
  err << "sslctl: '" << options.target << "' has no run-time parameter '" << options.key << "' (sslctl param list "
      << options.target << ")\n";
  return 1;
}

int param_set(const ParamOptions& options, ShutdownSignal& shutdown, std::ostream& out, std::ostream& err) {
  idl::system::ParameterSet request;
  request.target(options.target);
  std::vector<idl::system::Parameter> values;
  for (const std::string& assignment : options.assignments) {
    const auto equals = assignment.find('=');
    if (equals == std::string::npos || equals == 0) {
      err << "sslctl: '" << assignment << "' is not key=value\n";
      return 2;
    }
    idl::system::Parameter value;
    value.key(assignment.substr(0, equals));
    value.value(assignment.substr(equals + 1));
    values.push_back(value);
  }
  if (values.empty() && !options.save) {
    err << "sslctl: nothing to set (key=value ..., or --save)\n";
    return 2;
  }
  request.values(values);
  request.save(options.save);
  request.revision(static_cast<std::uint64_t>(wall_clock_unix_ns()));
  request.author("sslctl@" + std::to_string(getpid()));
  request.stamp_unix_ns(wall_clock_unix_ns());

  auto endpoints = open_endpoints(options, true, err);
  if (!endpoints) return 1;
  dds::Reader<ParameterState>* reader = &endpoints->states;
  dds::Writer<idl::system::ParameterSet>* writer = &*endpoints->requests;
  // The target's answer carries our revision; its state before (transient local) tells it is there.
  const auto before = collect(*reader, options.target, options.timeout_s, shutdown);
  if (!before.contains(options.target)) {
    err << "sslctl: no parameters from '" << options.target << "' within " << options.timeout_s
        << " s (is it running on domain " << options.dds.domain_id << "?)\n";
    return 1;
  }
  const auto sent = Clock::now();
  if (Status written = writer->write(request); !written) {
    err << "sslctl: " << written.error().message << '\n';
    return 1;
  }
  const auto deadline = sent + seconds(options.timeout_s);
  while (!shutdown.requested() && Clock::now() < deadline) {
    reader->wait_for_data(std::chrono::milliseconds(50));
    for (const auto& sample : reader->take()) {
      const ParameterState& state = sample.data;
      if (state.target() != options.target || state.revision() != request.revision()) continue;
      if (!state.accepted()) {
        err << "sslctl: " << options.target << " refused: " << state.reason() << '\n';
        return 1;
      }
      const double answered_ms = std::chrono::duration<double, std::milli>(Clock::now() - sent).count();
      out << options.target << ": " << (values.empty() ? "" : "set") << (values.empty() || !options.save ? "" : ", ")
          << (options.save ? "saved in " + state.saved_file() : "") << " (answered in " << std::fixed
          << std::setprecision(1) << answered_ms << " ms)\n";
      return 0;
    }
  }
  err << "sslctl: no answer from '" << options.target << "' within " << options.timeout_s << " s\n";
  return 1;
}

}  // namespace ssl::sslctl
