#include "services/simulator/simulator_config.h"

#include "libs/config/config.h"

namespace ssl::sim {
namespace {

using config::field;
using config::Fields;
using config::nested;

Fields<NetworkConfig> network_fields() {
  return {
      field("bind_address", &NetworkConfig::bind_address).doc("local address the protocol ports listen on"),
      field("interface", &NetworkConfig::interface_address).doc("multicast interface address of the vision output"),
      field("vision_group", &NetworkConfig::vision_group).doc("SSL-Vision multicast group"),
      field("vision_port", &NetworkConfig::vision_port).range(1, 65535),
      field("control_port", &NetworkConfig::control_port).range(1, 65535).doc("simulation control (SimulatorCommand)"),
      field("blue_port", &NetworkConfig::blue_port).range(1, 65535).doc("blue RobotControl"),
      field("yellow_port", &NetworkConfig::yellow_port).range(1, 65535).doc("yellow RobotControl"),
      field("grsim_port", &NetworkConfig::grsim_port).range(1, 65535).doc("grSim legacy grSim_Packet"),
  };
}

Fields<CameraConfig> camera_fields() {
  return {
      field("count", &CameraConfig::count).range(1, 8).doc("1, 2, 4, 6 or 8 cameras tiling the field"),
      field("frame_rate", &CameraConfig::frame_rate).unit("Hz").range(1, 1000),
      field("overlap", &CameraConfig::overlap).unit("m").range(0, 3).doc("each camera sees this far beyond its tile"),
      field("height", &CameraConfig::height).unit("m").range(0.5, 20),
      field("geometry_every_frames", &CameraConfig::geometry_every_frames).range(0, 100000)
          .doc("a geometry packet after this many frames (0: only at start)"),
  };
}

Fields<RobotLimits> limit_fields() {
  return {
      field("acc_speedup_absolute_max", &RobotLimits::acc_speedup_absolute_max).unit("m/s^2").range(0.1, 50),
      field("acc_speedup_angular_max", &RobotLimits::acc_speedup_angular_max).unit("rad/s^2").range(0.1, 500),
      field("acc_brake_absolute_max", &RobotLimits::acc_brake_absolute_max).unit("m/s^2").range(0.1, 50),
      field("acc_brake_angular_max", &RobotLimits::acc_brake_angular_max).unit("rad/s^2").range(0.1, 500),
      field("vel_absolute_max", &RobotLimits::vel_absolute_max).unit("m/s").range(0.1, 10),
      field("vel_angular_max", &RobotLimits::vel_angular_max).unit("rad/s").range(0.1, 100),
  };
}

Fields<RobotSpec> robot_fields() {
  return {
      field("radius", &RobotSpec::radius).unit("m").range(0.05, 0.2),
      field("height", &RobotSpec::height).unit("m").range(0.05, 0.3),
      field("mass", &RobotSpec::mass).unit("kg").range(0.1, 10),
      field("center_to_dribbler", &RobotSpec::center_to_dribbler).unit("m").range(0.03, 0.2),
      field("dribbler_width", &RobotSpec::dribbler_width).unit("m").range(0.01, 0.2),
      field("max_linear_kick_speed", &RobotSpec::max_linear_kick_speed).unit("m/s").range(0, 15),
      field("max_chip_kick_speed", &RobotSpec::max_chip_kick_speed).unit("m/s").range(0, 15),
      nested("limits", &RobotSpec::limits, limit_fields()),
  };
}

Fields<SimulatorConfig> simulator_fields() {
  Fields<SimulatorConfig> fields{
      field("division", &SimulatorConfig::division).values({{"a", Division::kA}, {"b", Division::kB}}),
      field("robots_per_team", &SimulatorConfig::robots_per_team).range(0, 16),
      field("seed", &SimulatorConfig::seed).doc("every random draw (vision noise) derives from it"),
      field("mode", &SimulatorConfig::mode)
          .values({{"realtime", Mode::kRealtime}, {"fast", Mode::kFast}, {"lockstep", Mode::kLockstep}}),
      field("realism", &SimulatorConfig::realism)
          .values({{"none", RealismProfile::kNone},
                   {"realistic", RealismProfile::kRealistic},
                   {"competition", RealismProfile::kCompetition}}),
      field("robot_response", &SimulatorConfig::robot_response)
          .values({{"ideal", ResponseProfile::kIdeal},
                   {"realistic", ResponseProfile::kRealistic},
                   {"harsh", ResponseProfile::kHarsh}})
          .doc("how robots answer commands: delay, loss, velocity lag, per-robot limits (robot_response.h)"),
      field("loop_rate", &SimulatorConfig::loop_rate).unit("Hz").range(10, 5000)
          .doc("iterations per second of the real-time loop"),
      field("fast_step", &SimulatorConfig::fast_step).unit("s").range(0.0001, 0.1)
          .doc("simulated time per iteration in fast mode"),
      field("command_timeout", &SimulatorConfig::command_timeout).unit("s").range(0.0, 10.0)
          .doc("a robot without a new command for this long stops, as real firmware does (0: never)"),
      nested("network", &SimulatorConfig::network, network_fields()),
      nested("cameras", &SimulatorConfig::cameras, camera_fields()),
      nested("blue", &SimulatorConfig::blue, robot_fields()),
      nested("yellow", &SimulatorConfig::yellow, robot_fields()),
  };
  fields.check([](const SimulatorConfig& c) -> Status {
    // The camera grid supports these counts only (VisionConfig::validate would throw later otherwise).
    const int count = c.cameras.count;
    if (count != 1 && count != 2 && count != 4 && count != 6 && count != 8) {
      return Error{"key 'cameras.count': " + std::to_string(count) + " is not one of 1, 2, 4, 6, 8"};
    }
    return Status::success();
  });
  return fields;
}

RealismConfig realism_of(RealismProfile profile) {
  switch (profile) {
    case RealismProfile::kNone: return RealismConfig::none();
    case RealismProfile::kRealistic: return RealismConfig::realistic();
    case RealismProfile::kCompetition: return RealismConfig::competition();
  }
  return RealismConfig::none();
}

RobotResponse response_of(ResponseProfile profile) {
  switch (profile) {
    case ResponseProfile::kIdeal: return RobotResponse::ideal();
    case ResponseProfile::kRealistic: return RobotResponse::realistic();
    case ResponseProfile::kHarsh: return RobotResponse::harsh();
  }
  return RobotResponse::ideal();
}

}  // namespace

Result<SimulatorConfig> load_simulator_config(std::span<const std::string> files, const std::vector<std::string>& overrides) {
  return config::load_files(files, simulator_fields(), overrides);
}

Result<SimulatorConfig> load_simulator_config(const std::string& path, const std::vector<std::string>& overrides) {
  return load_simulator_config(std::span<const std::string>(&path, 1), overrides);
}

std::string simulator_config_yaml(const SimulatorConfig& config) { return config::to_yaml(config, simulator_fields()); }

SimulatorOptions simulator_options(const SimulatorConfig& config) {
  SimulatorOptions options;
  options.field = FieldGeometry::of(config.division);
  options.vision.camera_count = config.cameras.count;
  options.vision.frame_rate = config.cameras.frame_rate;
  options.vision.camera_overlap = config.cameras.overlap;
  options.vision.camera_height = config.cameras.height;
  options.vision.geometry_every_frames = static_cast<std::uint32_t>(config.cameras.geometry_every_frames);
  options.vision.realism = realism_of(config.realism);
  options.response = response_of(config.robot_response);
  options.blue_spec = config.blue;
  options.yellow_spec = config.yellow;
  options.vision.max_robot_radius = std::max(config.blue.radius, config.yellow.radius);
  options.robots_per_team = static_cast<std::uint32_t>(config.robots_per_team);
  options.seed = config.seed;
  if (config.command_timeout > 0) {
    options.command_timeout =
        std::chrono::duration_cast<time::Duration>(std::chrono::duration<double>(config.command_timeout));
  }
  return options;
}

ServerOptions server_options(const SimulatorConfig& config) {
  ServerOptions options;
  options.bind_address = config.network.bind_address;
  options.interface_address = config.network.interface_address;
  options.vision_group = config.network.vision_group;
  options.vision_port = config.network.vision_port;
  options.control_port = config.network.control_port;
  options.blue_port = config.network.blue_port;
  options.yellow_port = config.network.yellow_port;
  options.grsim_port = config.network.grsim_port;
  options.lockstep = config.mode == Mode::kLockstep;
  return options;
}

}  // namespace ssl::sim
