#include "services/planner/planner_config.h"

#include "libs/config/config.h"

namespace ssl::planner {
namespace {

using config::field;
using config::Fields;
using config::nested;

Fields<MotionLimits> limit_fields() {
  return {
      field("max_speed", &MotionLimits::max_speed).unit("m/s").range(0.1, 10).doc("normal play"),
      field("max_acceleration", &MotionLimits::max_acceleration).unit("m/s^2").range(0.1, 50),
      field("max_angular_speed", &MotionLimits::max_angular_speed).unit("rad/s").range(0.1, 100),
      field("max_angular_acceleration", &MotionLimits::max_angular_acceleration).unit("rad/s^2").range(0.1, 1000),
      config::optional_field("max_turning_acceleration", &MotionLimits::max_turning_acceleration, 0.0)
          .unit("m/s^2")
          .range(0, 1000)
          .doc("0: no limit; else a turn of the body while moving at v is kept under this / v (robots whose "
               "wheels hold the velocity in their own frame, as grSim's)"),
  };
}

Fields<PlannerConfig> core_fields() {
  return Fields<PlannerConfig>{
      nested("limits", &PlannerConfig::limits, limit_fields()),
      field("motion", &PlannerConfig::motion)
          .values({{"simple", MotionControl::kSimple}, {"trajectory", MotionControl::kTrajectory}})
          .doc("skill layer: simple (proportional, local detours) or trajectory (time-optimal, path search)"),
      config::optional_field("strategy", &PlannerConfig::strategy, Strategy::kBase)
          .values({{"base", Strategy::kBase}, {"ball_chaser", Strategy::kBallChaser}, {"wander", Strategy::kWander}})
          .doc("normal play: base (seeds/001), ball_chaser (every field player runs for the ball, the nearest "
               "shoots: the baseline to beat) or wander (every robot tours waypoints: the referee demos)"),
      config::optional_field("free_kick", &PlannerConfig::free_kick, FreeKickPlay::kShot)
          .values({{"shot", FreeKickPlay::kShot}, {"redirect", FreeKickPlay::kRedirect}, {"pass", FreeKickPlay::kPass}})
          .doc("the base strategy's own free kicks: shot (at the widest open part of their goal), redirect "
               "(a pass that a teammate shoots on at the first touch, where one rates better than the shot) or "
               "pass (redirect, else a pass to a teammate where the shot is poor and the pass rates better)"),
      config::optional_field("kickoff", &PlannerConfig::kickoff, KickoffPlay::kPass)
          .values({{"pass", KickoffPlay::kPass}, {"shot", KickoffPlay::kShot}})
          .doc("the base strategy's own kickoffs: pass (to a teammate waiting in our half, where one rates, "
               "else the shot) or shot (at their goal)"),
      config::optional_field("penalty", &PlannerConfig::penalty, PenaltyPlay::kAdvance)
          .values({{"advance", PenaltyPlay::kAdvance}, {"shot", PenaltyPlay::kShot}})
          .doc("the base strategy's own penalties: advance (the ball played on towards their goal, the kicker "
               "running with it, shot from close in) or shot (from the mark)"),
      field("actuation_latency", &PlannerConfig::actuation_latency).unit("s").range(0, 0.2)
          .doc("from a tick until its command acts on the robot; trajectories plan from where the robot will be"),
      config::optional_field("measured_latency", &PlannerConfig::measured_latency, true)
          .doc("plan with world.state's command_delay (world_model measures it) instead of actuation_latency "
               "once it is known"),
      field("robot_radius", &PlannerConfig::robot_radius).unit("m").range(0.05, 0.2),
      field("stop_speed", &PlannerConfig::stop_speed).unit("m/s").range(0.1, rules::kStopMaxSpeed)
          .doc("the rules' limit during STOP or below"),
      field("stop_speed_margin", &PlannerConfig::stop_speed_margin).unit("m/s").range(0, 1)
          .doc("how far below stop_speed we aim"),
      field("ball_keep_away", &PlannerConfig::ball_keep_away).unit("m").range(rules::kStopBallDistance, 2)
          .doc("the rules' distance (or more) to the ball during STOP and their restarts"),
      field("keep_away_margin", &PlannerConfig::keep_away_margin).unit("m").range(0, 1),
      field("defense_area_keep_away", &PlannerConfig::defense_area_keep_away).unit("m").range(rules::kAttackerDefenseAreaDistance, 1)
          .doc("the rules' distance (or more) to the opponent defense area during STOP"),
      field("placement_tolerance", &PlannerConfig::placement_tolerance).unit("m").range(0.01, rules::kPlacementTolerance)
          .doc("ball placement success radius: the rules' or tighter"),
      field("penalty_line_behind", &PlannerConfig::penalty_line_behind).unit("m").range(0.4, 3)
          .doc("rules: other robots at least this far behind the ball at a penalty"),
  }
      .check([](const PlannerConfig& c) -> Status {
        if (c.stop_speed_margin >= c.stop_speed) return Error{"stop_speed_margin must be below stop_speed"};
        if (c.stop_speed > c.limits.max_speed) return Error{"stop_speed must not exceed limits.max_speed"};
        return {};
      });
}

Fields<PlannerServiceConfig> service_fields() {
  return Fields<PlannerServiceConfig>{
      field("team", &PlannerServiceConfig::team)
          .values({{"blue", TeamColor::kBlue}, {"yellow", TeamColor::kYellow}})
          .doc("our colour: the partition of world.state, robot.commands and planner.debug"),
      field("tick_mode", &PlannerServiceConfig::tick_mode)
          .values({{"on_world_state", TickMode::kOnWorldState}, {"fixed_rate", TickMode::kFixedRate}})
          .doc("on_world_state: tick on every new world.state as soon as it arrives (once the previous tick is "
               "done); fixed_rate: tick_rate Hz"),
      field("tick_rate", &PlannerServiceConfig::tick_rate).unit("Hz").range(1, 1000).doc("fixed_rate only"),
      field("stale_world_timeout", &PlannerServiceConfig::stale_world_timeout).unit("s").range(0.01, 10)
          .doc("without world.state this long: no ticks, nothing published, health WARN"),
      field("default_division", &PlannerServiceConfig::default_division)
          .values({{"a", Division::kA}, {"b", Division::kB}})
          .doc("the field until vision.geometry arrives"),
      nested("planner", &PlannerServiceConfig::core, core_fields()),
  };
}

}  // namespace

wm::FieldSize division_field(Division division) { return FieldGeometry::of(division); }

namespace {

/// What the core takes from the service's keys.
void fill_derived(PlannerServiceConfig& c) {
  c.core.team = c.team;
  // The first tick's dt (later ticks use the time since the previous one); on_world_state keeps the core's
  // nominal value.
  if (c.tick_mode == TickMode::kFixedRate) c.core.tick_period = 1.0 / c.tick_rate;
  c.core.default_field = division_field(c.default_division);
}

}  // namespace

Result<PlannerServiceConfig> load_planner_config(std::span<const std::string> files, const std::vector<std::string>& overrides) {
  auto loaded = config::load_files(files, service_fields(), overrides);
  if (!loaded) return loaded;
  fill_derived(*loaded);
  return loaded;
}

Result<config::RuntimeParameters<PlannerServiceConfig>> planner_runtime_parameters(const PlannerServiceConfig& config) {
  // What may change between two ticks: the skill layer's limits and the margins the plays keep. The team,
  // the ticking, the skill layer's kind and the rules' distances stay as started.
  return config::RuntimeParameters<PlannerServiceConfig>::create(
      config, service_fields(),
      {"planner.limits.max_speed", "planner.limits.max_acceleration", "planner.limits.max_angular_speed",
       "planner.limits.max_angular_acceleration", "planner.actuation_latency", "planner.stop_speed_margin",
       "planner.keep_away_margin"},
      fill_derived);
}

Result<PlannerServiceConfig> load_planner_config(const std::string& path, const std::vector<std::string>& overrides) {
  return load_planner_config(std::span<const std::string>(&path, 1), overrides);
}

std::string planner_config_yaml(const PlannerServiceConfig& config) {
  return config::to_yaml(config, service_fields());
}

std::string planner_config_help() { return config::describe(service_fields()); }

}  // namespace ssl::planner
