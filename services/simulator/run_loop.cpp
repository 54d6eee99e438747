#include "services/simulator/run_loop.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace ssl::sim {
namespace {

using SteadyClock = std::chrono::steady_clock;
using std::chrono::duration;
using std::chrono::duration_cast;

/// Maps simulated time onto Unix time for vision packets: at start, simulated time reads the wall clock.
time::Duration unix_offset_now(const Simulator& sim) {
  const auto wall = duration_cast<time::Duration>(std::chrono::system_clock::now().time_since_epoch());
  return wall - sim.time().since_epoch();
}

class Reporter {
 public:
  Reporter(const Simulator& sim, const SimulatorServer& server, dds::HealthReporter* health,
           const std::function<void(const std::string&)>& log_status)
      : sim_(sim), server_(server), health_(health), log_status_(log_status) {}

  void iteration() { ++iterations_; }

  void maybe_report() {
    const auto now = SteadyClock::now();
    if (now - last_ < (health_ != nullptr ? health_->period() : dds::HealthReporter::kPeriod)) return;
    const double wall = duration<double>(now - last_).count();
    const double simulated = (sim_.time() - last_sim_).count() * 1e-9;
    const ServerCounters counters = server_.counters();
    const double rate = static_cast<double>(iterations_) / wall;
    char line[256];
    std::snprintf(line, sizeof line, "%.0f steps/s, %.1fx real time, %lu vision packets, %lu malformed",
                  rate, simulated / wall, static_cast<unsigned long>(counters.vision_packets_sent),
                  static_cast<unsigned long>(counters.malformed_packets));
    if (log_status_) log_status_(line);
    if (health_ != nullptr) {
      (void)health_->publish({.level = counters.send_failures > 0 ? dds::HealthLevel::kWarn : dds::HealthLevel::kOk,
                              .status = line,
                              .rate_hz = rate,
                              .errors = counters.send_failures,
                              .dropped = counters.malformed_packets,
                              .counters = {{"control_requests", counters.control_requests},
                                           {"robot_control_packets", counters.robot_control_packets},
                                           {"grsim_packets", counters.grsim_packets},
                                           {"sync_steps", counters.sync_steps},
                                           {"errors_answered", counters.errors_answered},
                                           {"vision_packets_sent", counters.vision_packets_sent},
                                           {"geometry_packets_sent", counters.geometry_packets_sent},
                                           {"command_timeouts", sim_.command_timeouts()}}});
    }
    last_ = now;
    last_sim_ = sim_.time();
    iterations_ = 0;
  }

 private:
  const Simulator& sim_;
  const SimulatorServer& server_;
  dds::HealthReporter* health_;
  const std::function<void(const std::string&)>& log_status_;
  SteadyClock::time_point last_ = SteadyClock::now();
  time::Timestamp last_sim_ = sim_.time();
  std::uint64_t iterations_ = 0;
};

}  // namespace

void run_loop(Simulator& sim, SimulatorServer& server, const LoopOptions& options, ShutdownSignal& shutdown,
              dds::HealthReporter* health, const std::function<void(const std::string&)>& log_status) {
  const time::Duration unix_offset = unix_offset_now(sim);
  Reporter reporter(sim, server, health, log_status);
  switch (options.mode) {
    case Mode::kRealtime: {
      const auto period = duration_cast<SteadyClock::duration>(duration<double>(1.0 / options.loop_rate));
      // A stall (debugger, overloaded machine) is not caught up in one giant step.
      const auto max_step = std::chrono::milliseconds(50);
      auto last = SteadyClock::now();
      auto next = last + period;
      while (!shutdown.requested()) {
        server.handle_pending(sim, unix_offset);
        const auto now = SteadyClock::now();
        const auto elapsed = std::min<SteadyClock::duration>(now - last, max_step);
        last = now;
        const auto dt = duration_cast<time::Duration>(elapsed * sim.simulation_speed());
        server.publish(sim.step(dt), sim, unix_offset);
        reporter.iteration();
        reporter.maybe_report();
        next = std::max(next + period, SteadyClock::now());
        shutdown.wait_for(next - SteadyClock::now());
      }
      break;
    }
    case Mode::kFast: {
      const auto step = duration_cast<time::Duration>(duration<double>(options.fast_step));
      while (!shutdown.requested()) {
        server.handle_pending(sim, unix_offset);
        server.publish(sim.step(step), sim, unix_offset);
        reporter.iteration();
        reporter.maybe_report();
      }
      break;
    }
    case Mode::kLockstep: {
      while (!shutdown.requested()) {
        if (server.wait_for_input(std::chrono::milliseconds(100))) {
          server.handle_pending(sim, unix_offset);
          reporter.iteration();
        }
        reporter.maybe_report();
      }
      break;
    }
  }
}

}  // namespace ssl::sim
