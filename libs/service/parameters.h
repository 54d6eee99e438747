// Run-time parameters, the service's side (the console and `sslctl param` are the other): a
// ParameterEndpoint takes the requests on system.params addressed to this instance ("planner/blue"),
// hands them to the service, and publishes the instance's parameters and its answer on
// system.param_state (transient local: a console that starts later sees them). It is polled from the
// service's own loop, so a request is applied between two ticks, within one loop period (the services
// poll at least every 10 ms), and no user code runs on Fast DDS threads.
//
//   auto live = LiveConfig<PlannerServiceConfig>::create(participant, "planner/blue",
//                                                        std::move(*params), setup.saved_parameters);
//   while (running) { if (auto next = (*live)->poll()) planner.reconfigure(next->core); ... }
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "libs/common/result.h"
#include "libs/config/runtime_parameters.h"
#include "libs/dds/participant.h"

namespace ssl::service {

using ParameterChanges = std::span<const std::pair<std::string, std::string>>;

/// What a service does with requests.
struct ParameterHandler {
  std::function<std::vector<config::KeyInfo>()> describe;  // the run-time keys, current values
  std::function<Status(ParameterChanges)> apply;            // all or none; the Error says why not
  std::function<Result<std::string>()> save;                // writes them; the file written
};

class ParameterEndpoint {
 public:
  static Result<ParameterEndpoint> create(dds::Participant& participant, std::string target, ParameterHandler handler);

  /// Handles every request that arrived for this target (first call: publishes the state); true when one
  /// was handled.
  bool poll();

  struct Counters {
    std::uint64_t accepted = 0;
    std::uint64_t rejected = 0;
  };
  const Counters& counters() const { return counters_; }

 private:
  ParameterEndpoint(std::string target, ParameterHandler handler, dds::Reader<idl::system::ParameterSet> requests,
                    dds::Writer<idl::system::ParameterState> state);
  void publish(std::uint64_t revision, bool accepted, const std::string& reason);

  std::string target_;
  ParameterHandler handler_;
  dds::Reader<idl::system::ParameterSet> requests_;
  dds::Writer<idl::system::ParameterState> state_;
  bool published_ = false;
  std::string saved_file_;
  Counters counters_;
};

/// Writes `yaml` to `path` (its directory made first), atomically (a temporary file renamed over it).
Status write_parameters(const std::string& path, const std::string& yaml);

/// The handler of a service whose run-time keys are `params`: a change is applied to `params` and then
/// given to `on_change`; saving writes every run-time key's current value to `saved_file` (a config layer,
/// loaded at the next start by service::prepare with the same instance).
template <typename T>
ParameterHandler parameter_handler(config::RuntimeParameters<T>& params, std::string saved_file,
                                   std::function<void(const T&)> on_change) {
  ParameterHandler handler;
  handler.describe = [&params] { return params.describe(); };
  handler.apply = [&params, on_change](ParameterChanges changes) -> Status {
    Result<T> next = params.apply(changes);
    if (!next) return next.error();
    on_change(*next);
    return {};
  };
  handler.save = [&params, saved_file]() -> Result<std::string> {
    if (saved_file.empty()) return Error{"this instance has no saved-parameters file"};
    const std::vector<config::KeyInfo> keys = params.describe();
    if (Status written = write_parameters(saved_file, config::layer_yaml(keys)); !written) return written.error();
    return saved_file;
  };
  return handler;
}

/// A service's run-time parameters with their endpoint, for a loop that takes changes between two steps:
/// poll() answers the requests and returns the new config when one changed it. Made on the heap (the
/// endpoint's handler points into it), so that the service may move its own object.
template <typename T>
class LiveConfig {
 public:
  static Result<std::unique_ptr<LiveConfig>> create(dds::Participant& participant, std::string instance,
                                                    config::RuntimeParameters<T> params, std::string saved_file) {
    std::unique_ptr<LiveConfig> live(new LiveConfig(std::move(params)));
    auto endpoint = ParameterEndpoint::create(
        participant, std::move(instance),
        parameter_handler<T>(live->params_, std::move(saved_file),
                             [raw = live.get()](const T& next) { raw->pending_ = next; }));
    if (!endpoint) return endpoint.error();
    live->endpoint_.emplace(std::move(*endpoint));
    return live;
  }

  /// Handles every request that arrived; the config after them when they changed it.
  std::optional<T> poll() {
    endpoint_->poll();
    return std::exchange(pending_, std::nullopt);
  }

  const ParameterEndpoint::Counters& counters() const { return endpoint_->counters(); }

 private:
  explicit LiveConfig(config::RuntimeParameters<T> params) : params_(std::move(params)) {}

  config::RuntimeParameters<T> params_;
  std::optional<T> pending_;
  std::optional<ParameterEndpoint> endpoint_;
};

}  // namespace ssl::service
