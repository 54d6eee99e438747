// ChildProcess: starts a program of this build as a separate process for tests that exercise real
// processes (DDS between processes, signals, shared-memory cleanup). stdout and stderr are captured;
// every wait has a timeout, so a misbehaving child fails the test instead of hanging it.
//
//   auto child = ChildProcess::start(bin_dir() / "sslctl", {"topic", "echo", "referee.event", "--count", "1"});
//   auto line = child->read_line(10s);          // nullopt on timeout or end of output
//   auto code = child->wait(10s);               // exit status, nullopt on timeout
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "libs/common/result.h"

namespace ssl::testing {

/// build/bin, found relative to the running test executable (build/tests/<test>).
std::filesystem::path bin_dir();

/// What a shell command line printed (stdout and stderr) and its exit status (-1 when it did not exit).
struct ShellRun {
  int status = -1;
  std::string output;
};
/// Runs `command` with /bin/sh and waits for it.
ShellRun shell(const std::string& command);

/// `cmake --install` of this build under `prefix` (a match PC's tree: prefix/opt/ssl-stack/bin,
/// prefix/etc/ssl-stack, prefix/lib/systemd/system); the error carries cmake's output.
Status install_build(const std::filesystem::path& prefix);

class ChildProcess {
 public:
  static Result<ChildProcess> start(const std::filesystem::path& program, const std::vector<std::string>& args);

  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&&) = delete;
  ChildProcess(const ChildProcess&) = delete;
  ~ChildProcess();  // kills (SIGKILL) and reaps a child that is still running

  /// Next line of stdout without its newline; nullopt when none arrives within `timeout` or stdout closed.
  std::optional<std::string> read_line(std::chrono::milliseconds timeout);

  /// Everything the child wrote to stderr so far (non-blocking), for failure messages.
  std::string drain_stderr();

  /// Sends a signal (SIGTERM, SIGINT, ...).
  void signal(int signal_number);

  /// Waits for exit; the exit code (128 + signal if killed by a signal), nullopt on timeout.
  std::optional<int> wait(std::chrono::milliseconds timeout);

  pid_t pid() const { return pid_; }

 private:
  ChildProcess(pid_t pid, int stdout_fd, int stderr_fd) : pid_(pid), stdout_fd_(stdout_fd), stderr_fd_(stderr_fd) {}

  pid_t pid_ = -1;
  int stdout_fd_ = -1;
  int stderr_fd_ = -1;
  std::string stdout_buffer_;
  std::string stderr_buffer_;
  std::optional<int> exit_code_;
};

}  // namespace ssl::testing
