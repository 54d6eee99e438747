// ShutdownSignal: turns SIGINT and SIGTERM into an orderly stop request that a main loop can wait on.
//
// Construct it first in main(), before any other thread exists (DDS participants start threads): it blocks
// both signals in the calling thread, so every thread started afterwards inherits the mask and the
// signals are delivered only to the watcher thread this object owns. Destruction restores nothing; the
// process is ending.
//
//   ssl::ShutdownSignal shutdown;
//   auto participant = ...;
//   while (!shutdown.wait_for(std::chrono::milliseconds(100))) { ... }
//   // the participant's destructor deletes every DDS entity: peers hear it leave at once.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace ssl {

class ShutdownSignal {
 public:
  ShutdownSignal();
  ~ShutdownSignal();
  ShutdownSignal(const ShutdownSignal&) = delete;
  ShutdownSignal& operator=(const ShutdownSignal&) = delete;

  /// True once SIGINT or SIGTERM arrived, or request() was called.
  bool requested() const noexcept { return requested_.load(); }

  /// Waits up to `timeout` for a stop request; returns requested().
  bool wait_for(std::chrono::nanoseconds timeout);

  /// Blocks until a stop request.
  void wait();

  /// Requests a stop from inside the program (e.g. a fatal error in a worker).
  void request();

  /// Number of the signal that requested the stop, 0 if none or request() was used.
  int signal_number() const noexcept { return signal_number_.load(); }

 private:
  void watch();

  std::atomic<bool> requested_{false};
  std::atomic<bool> closing_{false};
  std::atomic<int> signal_number_{0};
  std::mutex mutex_;
  std::condition_variable changed_;
  std::thread watcher_;
};

}  // namespace ssl
