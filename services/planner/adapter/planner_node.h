// PlannerNode: the DDS adapter of the planner. It owns the readers of world.state (our team's partition),
// referee.state and vision.geometry and the writers of robot.commands and planner.debug (our partition),
// all created by QoS profile name; converts samples once (convert.h), ticks the pure core and publishes.
// One thread: run() waits on world.state and polls the other readers (no user code on Fast DDS threads,
// so the core needs no lock).
//
// Ticking (tick_mode): `on_world_state` (default) ticks on every new world.state sample as soon as it is
// taken, i.e. at the vision rate: run() wakes on the sample and ticks at once (samples that arrived during
// the previous tick are folded into one tick, the newest wins); `fixed_rate` ticks at tick_rate Hz with the
// newest world.state. With no world.state for
// stale_world_timeout nothing is ticked or published (robot_link's watchdog stops the robots) and health
// says WARN "no world state". Until the first referee.state the core sees HALT.
//
// Each tick writes one robot.commands sample (every robot's command, stamped with the VisionStamp of the
// world state it was computed from, the planner's own sequence_number and publish_unix_ns) and one
// planner.debug sample. Inputs with NaN/inf or impossible values are rejected and counted, never passed
// on. Health ("planner/<team>") once per second: tick rate, tick time p50/p99, counters.
//
// Run-time parameters (planner_runtime_parameters: limits and margins) arrive on system.params for
// "planner/<team>" and apply from the next tick; the node answers on system.param_state and saves them to
// `saved_parameters` when asked.
//
//   auto node = PlannerNode::create(participant, config, clock, setup.saved_parameters);
//   node->run(shutdown);
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "libs/common/result.h"
#include "libs/common/shutdown.h"
#include "libs/dds/health.h"
#include "libs/dds/participant.h"
#include "libs/service/parameters.h"
#include "libs/time/clock.h"
#include "services/planner/core/planner.h"
#include "services/planner/planner_config.h"

namespace ssl::planner {

struct PlannerNodeCounters {
  std::uint64_t ticks = 0;
  std::uint64_t world_states = 0;         // accepted world.state samples
  std::uint64_t world_rejected = 0;       // NaN/inf, wrong team, bad ids
  std::uint64_t referee_rejected = 0;     // unknown command, NaN/inf position
  std::uint64_t geometry_rejected = 0;    // missing or non-finite dimensions
  std::uint64_t non_finite_commands = 0;  // core outputs replaced by a stop
  std::uint64_t write_failures = 0;       // robot.commands or planner.debug writes refused by DDS

  std::uint64_t inputs_rejected() const { return world_rejected + referee_rejected + geometry_rejected; }
};

class PlannerNode {
 public:
  static Result<PlannerNode> create(dds::Participant& participant, const PlannerServiceConfig& config,
                                    time::Clock& wall_clock, const std::string& saved_parameters = "");

  /// Ticks and publishes until `shutdown` is requested.
  void run(ShutdownSignal& shutdown);

  /// One iteration: takes every pending sample, ticks when due, reports health when due; true if it ticked.
  bool poll();

  const PlannerNodeCounters& counters() const { return counters_; }
  const Planner& planner() const { return planner_; }
  const PlannerServiceConfig& config() const { return config_; }

 private:

  PlannerNode(const PlannerServiceConfig& config, time::Clock& wall_clock,
              dds::Reader<idl::world::WorldState> world, dds::Reader<idl::referee::RefereeState> referee,
              dds::Reader<idl::vision::Geometry> geometry, dds::Writer<idl::robot::RobotCommands> commands,
              dds::Writer<idl::planner::PlannerDebug> debug, dds::HealthReporter health);
  void take_inputs(time::Timestamp now);
  bool tick_due(time::Timestamp now) const;
  void tick(time::Timestamp now);
  bool world_fresh(time::Timestamp now) const;
  std::chrono::nanoseconds wait_budget() const;
  void report_health(time::Timestamp now);
  void reject(std::uint64_t& counter, const std::string& why);
  void apply_parameters();

  PlannerServiceConfig config_;
  std::unique_ptr<service::LiveConfig<PlannerServiceConfig>> parameters_;
  time::Clock* clock_;
  Planner planner_;
  dds::Reader<idl::world::WorldState> world_reader_;
  dds::Reader<idl::referee::RefereeState> referee_reader_;
  dds::Reader<idl::vision::Geometry> geometry_reader_;
  dds::Writer<idl::robot::RobotCommands> commands_writer_;
  dds::Writer<idl::planner::PlannerDebug> debug_writer_;
  dds::HealthReporter health_;

  PlannerInputs inputs_;
  bool have_world_ = false;
  bool have_referee_ = false;
  bool new_world_ = false;                  // a world.state arrived since the last tick (on_world_state)
  idl::common::VisionStamp world_stamp_;    // of inputs_.world, passed through to the outputs
  time::Timestamp world_received_;          // wall clock when the newest world.state was taken
  time::Timestamp next_tick_;               // fixed_rate
  time::Timestamp next_health_;
  time::Timestamp last_health_;  // the previous report, or the start: its rates are since then
  std::uint64_t sequence_ = 0;
  PlannerNodeCounters counters_;
  std::uint64_t ticks_in_period_ = 0;
  std::vector<double> tick_times_;          // s, this health period
  bool rejection_logged_ = false;           // one log line per health period; the counters have the rest
};

}  // namespace ssl::planner
