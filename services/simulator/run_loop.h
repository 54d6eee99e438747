// The simulator's main loop in its three modes, on the caller's thread:
//  - realtime: steps the physics by the wall-clock time elapsed (times the simulation speed) at loop_rate;
//  - fast: steps fixed increments as fast as the CPU allows (vision timestamps follow simulated time);
//  - lockstep: steps only when a client sends a SimulationSyncRequest on the control port.
// Every second it publishes system.health (when a reporter is given) and logs a status line.
#pragma once

#include <functional>

#include "libs/common/shutdown.h"
#include "libs/dds/health.h"
#include "services/simulator/adapter/server.h"
#include "services/simulator/simulator_config.h"

namespace ssl::sim {

struct LoopOptions {
  Mode mode = Mode::kRealtime;
  double loop_rate = 500;    // Hz (realtime)
  double fast_step = 0.002;  // s of simulated time per iteration (fast)
};

/// Runs until `shutdown` is requested. `health` may be null (no DDS). `log_status` receives a one-line
/// summary once per second.
void run_loop(Simulator& sim, SimulatorServer& server, const LoopOptions& options, ShutdownSignal& shutdown,
              dds::HealthReporter* health, const std::function<void(const std::string&)>& log_status);

}  // namespace ssl::sim
