#include "services/planner/adapter/planner_node.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <string>

#include "libs/common/percentile.h"
#include "services/planner/adapter/convert.h"

namespace ssl::planner {
namespace {

using namespace std::chrono_literals;

constexpr auto kMaxWait = 5ms;  // longest wait for world.state, so other inputs and health stay current

}  // namespace

Result<PlannerNode> PlannerNode::create(dds::Participant& participant, const PlannerServiceConfig& config,
                                        time::Clock& wall_clock, const std::string& saved_parameters) {
  namespace topics = dds::topics;
  auto world = participant.make_reader(topics::kWorldState, config.team);
  if (!world) return world.error();
  auto referee = participant.make_reader(topics::kRefereeState);
  if (!referee) return referee.error();
  auto geometry = participant.make_reader(topics::kVisionGeometry);
  if (!geometry) return geometry.error();
  auto commands = participant.make_writer(topics::kRobotCommands, config.team);
  if (!commands) return commands.error();
  auto debug = participant.make_writer(topics::kPlannerDebug, config.team);
  if (!debug) return debug.error();
  const std::string instance = "planner/" + std::string(to_string(config.team));
  auto health = dds::HealthReporter::create(participant, instance);
  if (!health) return health.error();
  // Up (READY) once it hears a world model.
  health->ready_when([reader = *world] { return reader.counters().matched_writers > 0; });
  health->exit_when_stalled();
  auto params = planner_runtime_parameters(config);
  if (!params) return params.error();
  PlannerNode node(config, wall_clock, std::move(*world), std::move(*referee), std::move(*geometry),
                   std::move(*commands), std::move(*debug), std::move(*health));
  auto live = service::LiveConfig<PlannerServiceConfig>::create(participant, instance, std::move(*params), saved_parameters);
  if (!live) return live.error();
  node.parameters_ = std::move(*live);
  return node;
}

void PlannerNode::apply_parameters() {
  std::optional<PlannerServiceConfig> next = parameters_->poll();
  if (!next) return;
  config_ = *next;
  planner_.reconfigure(config_.core);
  spdlog::info("planner/{}: run-time parameters changed", to_string(config_.team));
}

PlannerNode::PlannerNode(const PlannerServiceConfig& config, time::Clock& wall_clock,
                         dds::Reader<idl::world::WorldState> world, dds::Reader<idl::referee::RefereeState> referee,
                         dds::Reader<idl::vision::Geometry> geometry, dds::Writer<idl::robot::RobotCommands> commands,
                         dds::Writer<idl::planner::PlannerDebug> debug, dds::HealthReporter health)
    : config_(config),
      clock_(&wall_clock),
      planner_(config.core),
      world_reader_(std::move(world)),
      referee_reader_(std::move(referee)),
      geometry_reader_(std::move(geometry)),
      commands_writer_(std::move(commands)),
      debug_writer_(std::move(debug)),
      health_(std::move(health)) {
  tick_times_.reserve(4096);
  const time::Timestamp now = clock_->now();
  last_health_ = now;
  next_health_ = now + health_.period();
  next_tick_ = now;
}

void PlannerNode::reject(std::uint64_t& counter, const std::string& why) {
  ++counter;
  if (!rejection_logged_) {
    spdlog::warn("planner/{}: input rejected: {}", to_string(config_.team), why);
    rejection_logged_ = true;
  }
}

void PlannerNode::take_inputs(time::Timestamp now) {
  for (const auto& s : geometry_reader_.take()) {
    auto field = from_idl(s.data);
    if (field) {
      inputs_.field = *field;
    } else {
      reject(counters_.geometry_rejected, field.error().message);
    }
  }
  for (const auto& s : referee_reader_.take()) {
    auto referee = from_idl(s.data);
    if (referee) {
      inputs_.referee = *referee;
      have_referee_ = true;
    } else {
      reject(counters_.referee_rejected, referee.error().message);
    }
  }
  dds::Sample<idl::world::WorldState> sample;
  while (world_reader_.take_next(sample)) {
    auto world = from_idl(sample.data);
    if (!world) {
      reject(counters_.world_rejected, world.error().message);
      continue;
    }
    if (world->team != config_.team) {
      reject(counters_.world_rejected, "world.state in " + std::string(to_string(world->team)) +
                                           "'s frame on " + std::string(to_string(config_.team)) + "'s partition");
      continue;
    }
    inputs_.world = std::move(*world);
    world_stamp_ = sample.data.stamp();
    world_received_ = now;
    have_world_ = true;
    new_world_ = true;
    ++counters_.world_states;
  }
}

bool PlannerNode::world_fresh(time::Timestamp now) const {
  return have_world_ && time::to_seconds(now - world_received_) <= config_.stale_world_timeout;
}

bool PlannerNode::tick_due(time::Timestamp now) const {
  if (!world_fresh(now)) return false;
  if (config_.tick_mode == TickMode::kFixedRate) return now >= next_tick_;
  return new_world_;
}

std::chrono::nanoseconds PlannerNode::wait_budget() const {
  const time::Timestamp now = clock_->now();
  std::chrono::nanoseconds budget = kMaxWait;
  if (config_.tick_mode == TickMode::kFixedRate) budget = std::min(budget, next_tick_ - now);
  return std::max(budget, std::chrono::nanoseconds(0));
}

void PlannerNode::tick(time::Timestamp now) {
  const auto start = std::chrono::steady_clock::now();
  const PlannerOutput out = planner_.step(inputs_, now);
  const double duration = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  tick_times_.push_back(duration);
  ++counters_.ticks;
  ++ticks_in_period_;
  new_world_ = false;

  const std::int64_t publish_ns = clock_->now().nanoseconds();
  if (!commands_writer_.write(
          to_idl(out.commands, config_.team, world_stamp_, ++sequence_, publish_ns, &counters_.non_finite_commands))) {
    ++counters_.write_failures;
  }
  if (!debug_writer_.write(to_idl(out, config_.team, world_stamp_, duration))) ++counters_.write_failures;
}

bool PlannerNode::poll() {
  apply_parameters();
  time::Timestamp now = clock_->now();
  take_inputs(now);
  bool ticked = false;
  if (tick_due(now)) {
    tick(now);
    ticked = true;
  }
  if (config_.tick_mode == TickMode::kFixedRate && now >= next_tick_) {
    // The next slot of the fixed grid; after a stall (or while the world is stale) skip the missed ones.
    next_tick_ = std::max(next_tick_ + time::duration_from_seconds(1.0 / config_.tick_rate), now);
  }
  now = clock_->now();
  if (now >= next_health_) {
    report_health(now);
    next_health_ = now + health_.period();
  }
  return ticked;
}

void PlannerNode::report_health(time::Timestamp now) {
  dds::HealthReport report;
  if (!world_fresh(now)) {
    report.level = dds::HealthLevel::kWarn;
    report.status = "no world state";
  } else if (!have_referee_) {
    report.level = dds::HealthLevel::kWarn;
    report.status = "no referee state (HALT assumed)";
  } else {
    report.level = dds::HealthLevel::kOk;
    report.status = "running";
  }
  report.rate_hz = static_cast<double>(ticks_in_period_) / std::max(1e-3, time::to_seconds(now - last_health_));
  report.latency_p50 = percentile(tick_times_, 0.5);
  report.latency_p99 = percentile(tick_times_, 0.99);
  report.errors = counters_.write_failures + counters_.non_finite_commands;
  report.dropped = counters_.inputs_rejected();
  report.counters = {{"ticks", counters_.ticks},
                     {"world_states", counters_.world_states},
                     {"inputs_rejected", counters_.inputs_rejected()},
                     {"world_rejected", counters_.world_rejected},
                     {"referee_rejected", counters_.referee_rejected},
                     {"geometry_rejected", counters_.geometry_rejected},
                     {"non_finite_commands", counters_.non_finite_commands},
                     {"write_failures", counters_.write_failures}};
  (void)health_.publish(report);
  tick_times_.clear();
  ticks_in_period_ = 0;
  last_health_ = now;
  rejection_logged_ = false;
}

void PlannerNode::run(ShutdownSignal& shutdown) {
  while (!shutdown.requested()) {
    world_reader_.wait_for_data(wait_budget());
    poll();
  }
}

}  // namespace ssl::planner
