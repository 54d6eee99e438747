// NetNamespace: a network namespace of a test (`ip netns add`, loopback up and multicast-capable), deleted
// with the object. Needs root; tests that need one skip with a clear message where it cannot be made.
//
//   auto ns = NetNamespace::create("ssl-test-sites");
//   if (!ns) GTEST_SKIP() << ns.error().message;
//   auto child = ChildProcess::start(ns->ip(), ns->exec_args(bin_dir() / "vision_gateway", {"--site", "sim"}));
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "libs/common/result.h"

namespace ssl::testing {

class NetNamespace {
 public:
  /// Creates the namespace `name` (any stale one of that name is removed first). Error when not root or
  /// when `ip netns` fails, saying why.
  static Result<NetNamespace> create(std::string name);

  NetNamespace(NetNamespace&& other) noexcept : name_(std::move(other.name_)) { other.name_.clear(); }
  NetNamespace& operator=(NetNamespace&&) = delete;
  NetNamespace(const NetNamespace&) = delete;
  ~NetNamespace();

  const std::string& name() const { return name_; }
  /// The `ip` program.
  static std::filesystem::path ip();
  /// Arguments of `ip` that run `program args...` inside the namespace.
  std::vector<std::string> exec_args(const std::filesystem::path& program, const std::vector<std::string>& args) const;
  /// Runs `ip args...` (e.g. {"-n", name, "link", "set", ...}); error with its output when it fails.
  static Status run_ip(const std::vector<std::string>& args);

 private:
  explicit NetNamespace(std::string name) : name_(std::move(name)) {}
  std::string name_;
};

/// The UDP ports bound by process `pid`, from /proc/<pid>/net/udp (that process's namespace) and its
/// socket inodes.
std::vector<int> bound_udp_ports(int pid);

}  // namespace ssl::testing
