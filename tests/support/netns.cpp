#include "tests/support/netns.h"

#include "tests/support/process.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

namespace ssl::testing {

namespace fs = std::filesystem;

namespace {

// `ip args...` as one shell command line (the arguments quoted).
std::string ip_command(const std::vector<std::string>& args) {
  std::string command = "'" + NetNamespace::ip().string() + "'";
  for (const std::string& arg : args) command += " '" + arg + "'";
  return command;
}

}  // namespace

fs::path NetNamespace::ip() {
  for (const char* candidate : {"/usr/sbin/ip", "/sbin/ip", "/usr/bin/ip", "/bin/ip"}) {
    if (::access(candidate, X_OK) == 0) return candidate;
  }
  return "ip";
}

Status NetNamespace::run_ip(const std::vector<std::string>& args) {
  const std::string command = ip_command(args);
  const ShellRun run = shell(command);
  if (run.status != 0) return Error{command + " failed: " + run.output};
  return Status::success();
}

Result<NetNamespace> NetNamespace::create(std::string name) {
  if (::geteuid() != 0) return Error{"network namespaces need root (this test runs as uid " + std::to_string(::geteuid()) + ")"};
  (void)shell(ip_command({"netns", "del", name}));
  if (Status added = run_ip({"netns", "add", name}); !added) return added.error();
  NetNamespace ns(std::move(name));
  for (const std::vector<std::string>& step : std::vector<std::vector<std::string>>{
           {"-n", ns.name_, "link", "set", "lo", "up"},
           {"-n", ns.name_, "link", "set", "lo", "multicast", "on"},
           {"-n", ns.name_, "route", "add", "224.0.0.0/4", "dev", "lo"}}) {
    if (Status done = run_ip(step); !done) return done.error();
  }
  return ns;
}

NetNamespace::~NetNamespace() {
  if (name_.empty()) return;
  (void)shell(ip_command({"netns", "del", name_}));
}

std::vector<std::string> NetNamespace::exec_args(const fs::path& program, const std::vector<std::string>& args) const {
  std::vector<std::string> out{"netns", "exec", name_, program.string()};
  out.insert(out.end(), args.begin(), args.end());
  return out;
}

std::vector<int> bound_udp_ports(int pid) {
  // The inodes of the process's sockets...
  std::set<std::string> inodes;
  std::error_code error;
  for (const fs::directory_entry& fd : fs::directory_iterator("/proc/" + std::to_string(pid) + "/fd", error)) {
    const std::string target = fs::read_symlink(fd.path(), error).string();
    if (target.rfind("socket:[", 0) == 0) inodes.insert(target.substr(8, target.size() - 9));
  }
  // ... and their local ports in the process's namespace's UDP table.
  std::set<int> ports;
  std::ifstream table("/proc/" + std::to_string(pid) + "/net/udp");
  std::string line;
  std::getline(table, line);  // header
  while (std::getline(table, line)) {
    std::istringstream fields(line);
    std::string slot, local, remote, state, queues, timer, retransmits, uid, timeout, inode;
    fields >> slot >> local >> remote >> state >> queues >> timer >> retransmits >> uid >> timeout >> inode;
    if (!inodes.contains(inode)) continue;
    const std::size_t colon = local.find(':');
    if (colon != std::string::npos) ports.insert(std::stoi(local.substr(colon + 1), nullptr, 16));
  }
  return {ports.begin(), ports.end()};
}

}  // namespace ssl::testing
