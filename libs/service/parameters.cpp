#include "libs/service/parameters.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "libs/dds/topics.h"

namespace ssl::service {
namespace {

std::int64_t wall_clock_unix_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

idl::system::ParameterInfo to_idl(const config::KeyInfo& key) {
  idl::system::ParameterInfo out;
  out.key(key.key);
  out.value(key.value);
  out.type(key.type);
  out.has_min(key.min.has_value());
  out.min(key.min.value_or(0.0));
  out.has_max(key.max.has_value());
  out.max(key.max.value_or(0.0));
  out.allowed(key.allowed);
  out.unit(key.unit);
  out.description(key.doc);
  return out;
}

}  // namespace

Status write_parameters(const std::string& path, const std::string& yaml) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), error);
  if (error) return Error{"cannot create " + target.parent_path().string() + ": " + error.message()};
  const fs::path temporary = target.string() + ".tmp";
  {
    std::ofstream out(temporary);
    out << "# Run-time parameters saved from the console or sslctl; a config layer loaded at start.\n" << yaml;
    if (!out) return Error{"cannot write " + temporary.string()};
  }
  fs::rename(temporary, target, error);
  if (error) return Error{"cannot write " + path + ": " + error.message()};
  return {};
}

Result<ParameterEndpoint> ParameterEndpoint::create(dds::Participant& participant, std::string target,
                                                    ParameterHandler handler) {
  auto requests = participant.make_reader(dds::topics::kSystemParams);
  if (!requests) return requests.error();
  auto state = participant.make_writer(dds::topics::kSystemParamState);
  if (!state) return state.error();
  return ParameterEndpoint(std::move(target), std::move(handler), std::move(*requests), std::move(*state));
}

ParameterEndpoint::ParameterEndpoint(std::string target, ParameterHandler handler,
                                     dds::Reader<idl::system::ParameterSet> requests,
                                     dds::Writer<idl::system::ParameterState> state)
    : target_(std::move(target)), handler_(std::move(handler)), requests_(std::move(requests)), state_(std::move(state)) {}

bool ParameterEndpoint::poll() {
  bool handled = false;
  for (const auto& sample : requests_.take()) {
    const idl::system::ParameterSet& request = sample.data;
    if (request.target() != target_) continue;
    handled = true;
    std::vector<std::pair<std::string, std::string>> changes;
    for (const auto& value : request.values()) changes.emplace_back(value.key(), value.value());
    Status result = changes.empty() ? Status{} : handler_.apply(changes);
    if (result && request.save()) {
      Result<std::string> saved = handler_.save();
      if (saved) {
        saved_file_ = *saved;
      } else {
        result = saved.error();
      }
    }
    if (result) {
      ++counters_.accepted;
    } else {
      ++counters_.rejected;
    }
    publish(request.revision(), static_cast<bool>(result), result ? "" : result.error().message);
  }
  if (!published_) publish(0, true, "");
  return handled;
}

void ParameterEndpoint::publish(std::uint64_t revision, bool accepted, const std::string& reason) {
  idl::system::ParameterState state;
  state.target(target_);
  std::vector<idl::system::ParameterInfo> params;
  for (const config::KeyInfo& key : handler_.describe()) params.push_back(to_idl(key));
  state.params(std::move(params));
  state.revision(revision);
  state.accepted(accepted);
  state.reason(reason);
  state.saved_file(saved_file_);
  state.stamp_unix_ns(wall_clock_unix_ns());
  published_ = static_cast<bool>(state_.write(state));
}

}  // namespace ssl::service
