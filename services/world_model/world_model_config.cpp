#include "services/world_model/world_model_config.h"

#include "libs/config/config.h"

namespace ssl::wm {
namespace {

using config::field;
using config::Fields;
using config::nested;

Fields<RobotFilterParams> robot_fields() {
  return Fields<RobotFilterParams>{
      field("position_stddev", &RobotFilterParams::position_stddev).unit("m").range(1e-4, 0.1),
      field("orientation_stddev", &RobotFilterParams::orientation_stddev).unit("rad").range(1e-4, 1),
      field("acceleration_stddev", &RobotFilterParams::acceleration_stddev).unit("m/s^2").range(0.01, 100)
          .doc("prior spread of the acceleration when the uncommanded model takes over"),
      field("mode_jerk_stddev", &RobotFilterParams::mode_jerk_stddev).unit("m/s^3/sqrt(Hz)")
          .range(0.001, 1000).length(1, RobotFilter::kMaxJerkModes)
          .doc("white jerk densities of the uncommanded (Singer) model, one IMM mode each: enemy robots"),
      field("mode_angular_acceleration_stddev", &RobotFilterParams::mode_angular_acceleration_stddev)
          .unit("rad/s^2").range(0.01, 1000).length(1, RobotFilter::kMaxJerkModes)
          .doc("each of those modes' white angular acceleration"),
      field("mode_acceleration_time_constant", &RobotFilterParams::mode_acceleration_time_constant).unit("s")
          .range(0, 100).length(1, RobotFilter::kMaxJerkModes)
          .doc("each of those modes' acceleration decays with it (0: held)"),
      field("mode_switch_rate", &RobotFilterParams::mode_switch_rate).unit("1/s").range(0.001, 100)
          .doc("expected switches per second between those modes"),
      field("stationary_mode", &RobotFilterParams::stationary_mode)
          .doc("one more IMM mode: the robot stands (velocity zero)"),
      field("stationary_drift_stddev", &RobotFilterParams::stationary_drift_stddev).unit("m/sqrt(s)")
          .range(1e-6, 1).doc("how far a standing robot's position may drift (pushed)"),
      field("acceleration_time_constant", &RobotFilterParams::acceleration_time_constant).unit("s")
          .range(0, 100)
          .doc("a single filter's acceleration decays with it (0: held); also the published prediction's"),
      field("commanded_acceleration_stddev", &RobotFilterParams::commanded_acceleration_stddev)
          .unit("m/s^2").range(0.01, 100).doc("process noise while following our command"),
      field("angular_acceleration_stddev", &RobotFilterParams::angular_acceleration_stddev)
          .unit("rad/s^2").range(0.01, 1000),
      field("commanded_angular_acceleration_stddev", &RobotFilterParams::commanded_angular_acceleration_stddev)
          .unit("rad/s^2").range(0.01, 1000),
      field("max_acceleration", &RobotFilterParams::max_acceleration).unit("m/s^2").range(0.1, 50),
      field("max_angular_acceleration", &RobotFilterParams::max_angular_acceleration).unit("rad/s^2")
          .range(0.1, 1000),
      field("command_timeout", &RobotFilterParams::command_timeout).unit("s").range(0.001, 5),
      field("gate_distance", &RobotFilterParams::gate_distance).unit("m").range(0.01, 10)
          .doc("beyond prediction + max_speed * dt: teleport candidate"),
      field("max_speed", &RobotFilterParams::max_speed).unit("m/s").range(0.1, 20),
      field("maneuver_gate", &RobotFilterParams::maneuver_gate).range(1, 1e6)
          .doc("chi-square (3 dof): beyond it a step is re-predicted with more process noise"),
      field("maneuver_noise_scale", &RobotFilterParams::maneuver_noise_scale).range(1, 1e6),
      field("collision_velocity_stddev", &RobotFilterParams::collision_velocity_stddev).unit("m/s")
          .range(0.01, 10).doc("beyond the maneuver gate the IMM's loosest mode takes a velocity impulse"),
      field("command_delay", &RobotFilterParams::command_delay).unit("s").range(0, 1)
          .doc("sent -> executed by the robot"),
      field("velocity_turns_with_robot", &RobotFilterParams::velocity_turns_with_robot)
          .doc("without a command, also try a velocity that turns with the robot"),
      field("motion_model_time_constant", &RobotFilterParams::motion_model_time_constant).unit("s")
          .range(0.001, 10).doc("memory of the choice between the two uncommanded models"),
      field("contact_acceleration_stddev", &RobotFilterParams::contact_acceleration_stddev).unit("m/s^2")
          .range(0.01, 100),
      field("contact_angular_acceleration_stddev", &RobotFilterParams::contact_angular_acceleration_stddev)
          .unit("rad/s^2").range(0.1, 1000),
  }
      .check([](const RobotFilterParams& robot) -> Status {
        const std::size_t modes = robot.mode_jerk_stddev.size();
        for (const auto& [name, values] : {std::pair{"mode_angular_acceleration_stddev",
                                                     &robot.mode_angular_acceleration_stddev},
                                           std::pair{"mode_acceleration_time_constant",
                                                     &robot.mode_acceleration_time_constant}}) {
          if (values->size() != modes) {
            return Error{std::string(name) + " needs one value per mode_jerk_stddev (" + std::to_string(modes) +
                         "), has " + std::to_string(values->size())};
          }
        }
        return {};
      });
}

Fields<BallFilterParams> ball_fields() {
  return {
      field("position_stddev", &BallFilterParams::position_stddev).unit("m").range(1e-4, 0.1),
      field("near_robot_position_stddev", &BallFilterParams::near_robot_position_stddev).unit("m")
          .range(1e-4, 0.5),
      field("acceleration_stddev", &BallFilterParams::acceleration_stddev).unit("m/s^2").range(0.001, 100),
      field("maneuver_mahalanobis2", &BallFilterParams::maneuver_mahalanobis2).range(1, 1e6)
          .doc("chi-square (2 dof): beyond it a detection is a kick or a collision"),
      field("maneuver_velocity_stddev", &BallFilterParams::maneuver_velocity_stddev).unit("m/s").range(0, 50),
      field("maneuver_min_velocity_stddev", &BallFilterParams::maneuver_min_velocity_stddev).unit("m/s")
          .range(0, 50),
      field("gate_mahalanobis2", &BallFilterParams::gate_mahalanobis2).range(1, 1e6)
          .doc("chi-square gate, 2 dof"),
      field("gate_min_distance", &BallFilterParams::gate_min_distance).unit("m").range(0, 1),
      field("max_ball_speed", &BallFilterParams::max_ball_speed).unit("m/s").range(1, 30),
      field("reinit_detections", &BallFilterParams::reinit_detections).range(1, 8),
      field("kick_speed_increase", &BallFilterParams::kick_speed_increase).unit("m/s").range(0.1, 20),
  };
}

Fields<BallModel> ball_model_fields() {
  return {
      field("acc_slide", &BallModel::acc_slide).unit("m/s^2").range(-50, -0.01),
      field("acc_roll", &BallModel::acc_roll).unit("m/s^2").range(-10, -0.001),
      field("k_switch", &BallModel::k_switch).range(0.01, 1),
  };
}

Fields<CameraAlignmentParams> camera_alignment_fields() {
  return {
      field("estimate_scale", &CameraAlignmentParams::estimate_scale)
          .doc("per-camera scale about its centre (camera height errors)"),
      field("estimate_rotation", &CameraAlignmentParams::estimate_rotation),
      field("min_pairs", &CameraAlignmentParams::min_pairs).range(1, 1000000)
          .doc("pairs of simultaneous detections a camera needs before it is corrected"),
      field("max_speed", &CameraAlignmentParams::max_speed).unit("m/s").range(0.1, 20),
      field("offset_drift", &CameraAlignmentParams::offset_drift).unit("m/sqrt(s)").range(0, 1),
  };
}

Fields<DetectionNoiseParams> detection_noise_fields() {
  return {
      field("estimate", &DetectionNoiseParams::estimate)
          .doc("estimate each camera's robot detection noise from its detections (false: robot.*_stddev)"),
      field("min_samples", &DetectionNoiseParams::min_samples).range(1, 1000000)
          .doc("residuals a camera needs before its estimate is used"),
      field("memory", &DetectionNoiseParams::memory).range(0.5, 0.999999)
          .doc("per residual: weight of the past"),
      field("max_span", &DetectionNoiseParams::max_span).unit("s").range(0.005, 1)
          .doc("three detections of one robot by one camera within this make a residual"),
      field("clip_sigmas", &DetectionNoiseParams::clip_sigmas).range(1, 100)
          .doc("a residual counts at most this many current sigmas (collisions are not noise)"),
      field("min_factor", &DetectionNoiseParams::min_factor).range(0.01, 1)
          .doc("the estimate stays at least this times the configured noise ..."),
      field("max_factor", &DetectionNoiseParams::max_factor).range(1, 100).doc("... and at most this times"),
  };
}

Fields<CommandDelayParams> command_delay_fields() {
  return {
      field("estimate", &CommandDelayParams::estimate)
          .doc("measure our robots' delay from command to motion (false: robot.command_delay, the planner's own)"),
      field("min_delay", &CommandDelayParams::min_delay).unit("s").range(0, 1),
      field("max_delay", &CommandDelayParams::max_delay).unit("s").range(0.01, 1).doc("the candidates' range"),
      field("resolution", &CommandDelayParams::resolution).unit("s").range(0.001, 0.1),
      field("window", &CommandDelayParams::window).unit("s").range(0.1, 10).doc("motion replayed per evaluation"),
      field("evaluation_period", &CommandDelayParams::evaluation_period).unit("s").range(0.01, 10),
      field("memory", &CommandDelayParams::memory).unit("s").range(0.1, 600)
          .doc("how long past evaluations count (exponential)"),
      field("velocity_span", &CommandDelayParams::velocity_span).unit("s").range(0.02, 0.5)
          .doc("detections around an instant for its measured velocity"),
      field("max_acceleration", &CommandDelayParams::max_acceleration).unit("m/s^2").range(0.1, 20),
      field("command_timeout", &CommandDelayParams::command_timeout).unit("s").range(0.01, 10),
      field("min_excitation", &CommandDelayParams::min_excitation).unit("m/s").range(0, 10)
          .doc("a robot's commands must change this much within a window to count"),
      field("min_weight", &CommandDelayParams::min_weight).range(0, 1e6).doc("samples before an estimate is given"),
  };
}

Fields<WorldModelConfig> core_fields() {
  return {
      field("carried_ball_after", &WorldModelConfig::carried_ball_after).unit("s").range(0, 1)
          .doc("without a ball detection this long, a ball last seen at a dribbler counts as hidden by it"),
      field("carried_ball_timeout", &WorldModelConfig::carried_ball_timeout).unit("s").range(0, 10)
          .doc("a ball hidden right after touching a dribbler moves with that robot this long"),
      field("chip_window", &WorldModelConfig::chip_window).unit("s").range(0.1, 10)
          .doc("after a kick, how long a chip flight is looked for and tracked"),
      field("align_cameras", &WorldModelConfig::align_cameras)
          .doc("estimate each camera's calibration error from objects seen by two cameras"),
      nested("camera_alignment", &WorldModelConfig::camera_alignment, camera_alignment_fields()),
      nested("robot", &WorldModelConfig::robot, robot_fields()),
      nested("detection_noise", &WorldModelConfig::detection_noise, detection_noise_fields()),
      nested("command_delay", &WorldModelConfig::command_delay, command_delay_fields()),
      nested("ball", &WorldModelConfig::ball, ball_fields()),
      nested("ball_model", &WorldModelConfig::ball_model, ball_model_fields()),
      field("min_confidence", &WorldModelConfig::min_confidence).range(0, 1),
      field("robot_lost_timeout", &WorldModelConfig::robot_lost_timeout).unit("s").range(0.01, 60),
      field("ball_lost_timeout", &WorldModelConfig::ball_lost_timeout).unit("s").range(0.01, 600),
      field("visible_timeout", &WorldModelConfig::visible_timeout).unit("s").range(0.001, 10),
      field("feedback_timeout", &WorldModelConfig::feedback_timeout).unit("s").range(0.001, 10),
      field("center_to_dribbler", &WorldModelConfig::center_to_dribbler).unit("m").range(0.01, 0.2),
      field("robot_radius", &WorldModelConfig::robot_radius).unit("m").range(0.05, 0.2),
      field("possession_distance", &WorldModelConfig::possession_distance).unit("m").range(0, 0.5),
      field("near_robot_distance", &WorldModelConfig::near_robot_distance).unit("m").range(0, 1),
      field("dribbler_capture_distance", &WorldModelConfig::dribbler_capture_distance).unit("m").range(0, 1),
      field("vision_clock_slowness", &WorldModelConfig::vision_clock_slowness).unit("s/s").range(0, 0.5)
          .doc("how much slower than this host's clock the vision clock may run (grSim stamps simulated time)"),
      field("contact_margin", &WorldModelConfig::contact_margin).unit("m").range(0, 0.5)
          .doc("robots this close to touching (or a wall) do not trust their commands"),
  };
}

Fields<WorldModelServiceConfig> service_fields() {
  return {
      field("team", &WorldModelServiceConfig::team)
          .values({{"blue", TeamColor::kBlue}, {"yellow", TeamColor::kYellow}}),
      field("publish_mode", &WorldModelServiceConfig::publish_mode)
          .values({{"on_frame", PublishMode::kOnFrame}, {"fixed_rate", PublishMode::kFixedRate}})
          .doc("on_frame: after every camera frame; fixed_rate: publish_rate Hz"),
      field("publish_rate", &WorldModelServiceConfig::publish_rate).unit("Hz").range(1, 1000),
      field("stale_vision_timeout", &WorldModelServiceConfig::stale_vision_timeout).unit("s").range(0.01, 10),
      nested("filter", &WorldModelServiceConfig::core, core_fields()),
  };
}

}  // namespace

Result<WorldModelServiceConfig> load_world_model_config(std::span<const std::string> files, const std::vector<std::string>& overrides) {
  auto loaded = config::load_files(files, service_fields(), overrides);
  if (loaded) loaded->core.team = loaded->team;
  return loaded;
}

Result<config::RuntimeParameters<WorldModelServiceConfig>> world_model_runtime_parameters(
    const WorldModelServiceConfig& config) {
  // The thresholds the model reads at every frame; the filters' noise models stay as started.
  return config::RuntimeParameters<WorldModelServiceConfig>::create(
      config, service_fields(),
      {"filter.min_confidence", "filter.possession_distance", "filter.near_robot_distance",
       "filter.dribbler_capture_distance", "filter.robot_lost_timeout", "filter.ball_lost_timeout",
       "filter.visible_timeout"},
      [](WorldModelServiceConfig& c) { c.core.team = c.team; });
}

Result<WorldModelServiceConfig> load_world_model_config(const std::string& path, const std::vector<std::string>& overrides) {
  return load_world_model_config(std::span<const std::string>(&path, 1), overrides);
}

std::string world_model_config_yaml(const WorldModelServiceConfig& config) {
  return config::to_yaml(config, service_fields());
}

}  // namespace ssl::wm
