// RuntimeParameters<T>: the keys of a service's config that may change while it runs (the console's and
// `sslctl param`'s dynamic parameters). The service declares them next to its schema; a change is laid
// over the current config as an override and loaded through that same schema, so it is checked exactly as
// at start (type, range, one-of, the whole-struct checks) and refused with the same message. All the
// changes of one request apply, or none.
//
//   auto params = RuntimeParameters<PlannerServiceConfig>::create(config, service_fields(),
//                                                                 {"planner.kick_speed"}, fill_derived);
//   Result<PlannerServiceConfig> next = params->apply({{"planner.kick_speed", "4.5"}});
//   if (!next) reply(next.error().message);   // "... key 'planner.kick_speed': 9 is out of range [1, 6.5]"
#pragma once

#include <algorithm>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "libs/config/config.h"

namespace ssl::config {

template <typename T>
class RuntimeParameters {
 public:
  /// Called on every loaded config (the initial one is assumed done): fills what the service derives
  /// from other keys.
  using Finish = std::function<void(T&)>;

  /// `keys` must each be a scalar key of `fields` (else an Error naming it: a schema mistake).
  static Result<RuntimeParameters> create(T initial, Fields<T> fields, std::vector<std::string> keys,
                                          Finish finish = {}) {
    const std::vector<KeyInfo> all = key_infos(initial, fields);
    for (const std::string& key : keys) {
      const bool known = std::any_of(all.begin(), all.end(), [&](const KeyInfo& info) { return info.key == key; });
      if (!known) return Error{"run-time parameter '" + key + "' is not a scalar key of the config"};
    }
    return RuntimeParameters(std::move(initial), std::move(fields), std::move(keys), std::move(finish));
  }

  const T& current() const { return current_; }
  const std::vector<std::string>& keys() const { return keys_; }

  /// The run-time keys with their schema and current values, in declaration order.
  std::vector<KeyInfo> describe() const { return select(key_infos(current_, fields_)); }

  /// Applies every (key, value text) change or none; returns the new config or why not.
  Result<T> apply(std::span<const std::pair<std::string, std::string>> changes) {
    std::vector<std::string> overrides;
    for (const auto& [key, value] : changes) {
      if (std::find(keys_.begin(), keys_.end(), key) == keys_.end()) {
        return Error{"'" + key + "' cannot change at run time (run-time keys: " + detail::join_list(keys_) + ")"};
      }
      if (value.find('\n') != std::string::npos) return Error{"the value of '" + key + "' must be one line"};
      overrides.push_back(key + "=" + value);
    }
    Result<T> next = load_string(to_yaml(current_, fields_), fields_, "run-time change", overrides);
    if (!next) return next.error();
    if (finish_) finish_(*next);
    current_ = *next;
    return next;
  }

  /// The run-time keys whose value differs from the initial config.
  std::vector<KeyInfo> changed() const {
    const std::vector<KeyInfo> now = describe();
    std::vector<KeyInfo> out;
    for (const KeyInfo& info : now) {
      if (initial_values_.at(info.key) != info.value) out.push_back(info);
    }
    return out;
  }

 private:
  RuntimeParameters(T initial, Fields<T> fields, std::vector<std::string> keys, Finish finish)
      : current_(std::move(initial)), fields_(std::move(fields)), keys_(std::move(keys)), finish_(std::move(finish)) {
    for (const KeyInfo& info : describe()) initial_values_[info.key] = info.value;
  }

  std::vector<KeyInfo> select(const std::vector<KeyInfo>& all) const {
    std::vector<KeyInfo> out;
    for (const std::string& key : keys_) {
      for (const KeyInfo& info : all) {
        if (info.key == key) out.push_back(info);
      }
    }
    return out;
  }

  T current_;
  Fields<T> fields_;
  std::vector<std::string> keys_;
  Finish finish_;
  std::map<std::string, std::string> initial_values_;
};

/// `keys` (dotted, with their values) as a YAML config layer of nested maps: what saving run-time
/// parameters writes, loadable by load_files over the defaults. Strings are quoted.
std::string layer_yaml(std::span<const KeyInfo> keys);

}  // namespace ssl::config
