#include "services/robot_link/robot_link_config.h"

#include "libs/config/config.h"
#include "services/robot_link/backend/serial_port.h"

namespace ssl::robot_link {
namespace {

using config::field;
using config::Fields;
using config::nested;

Fields<SimTargetConfig> sim_fields() {
  return {
      field("host", &SimTargetConfig::host).doc("simulator address (sim and grsim backends)"),
      field("port", &SimTargetConfig::port)
          .range(0, 65535)
          .doc("0: 10301 blue / 10302 yellow (sim), 20011 (grsim)"),
      field("grsim_feedback", &SimTargetConfig::grsim_feedback)
          .doc("grsim: listen for grSim's Robots_Status"),
      field("grsim_status_port", &SimTargetConfig::grsim_status_port)
          .range(0, 65535)
          .doc("0: 30011 blue / 30012 yellow"),
  };
}

Fields<RadioConfig> radio_fields() {
  return {
      field("transport", &RadioConfig::transport)
          .values({{"udp", RadioTransport::kUdp}, {"serial", RadioTransport::kSerial}}),
      field("host", &RadioConfig::host).doc("base station address (udp)"),
      field("port", &RadioConfig::port).range(0, 65535).doc("base station port (udp); 0: 10400"),
      field("local_port", &RadioConfig::local_port)
          .range(0, 65535)
          .doc("status frames arrive here (udp); 0: any, the base station replies to the sender"),
      field("device", &RadioConfig::device).doc("serial device of the base station (serial)"),
      field("baud", &RadioConfig::baud).range(9600, 4000000).doc("serial baud rate"),
  };
}

Fields<RobotLimits> robot_fields() {
  return {
      field("vel_absolute_max", &RobotLimits::vel_absolute_max).unit("m/s").range(0.1, 10),
      field("vel_angular_max", &RobotLimits::vel_angular_max).unit("rad/s").range(0.1, 100),
      field("acc_speedup_absolute_max", &RobotLimits::acc_speedup_absolute_max).unit("m/s^2").range(0.1, 50),
      field("acc_brake_absolute_max", &RobotLimits::acc_brake_absolute_max).unit("m/s^2").range(0.1, 50),
      field("acc_speedup_angular_max", &RobotLimits::acc_speedup_angular_max).unit("rad/s^2").range(0.1, 500),
      field("acc_brake_angular_max", &RobotLimits::acc_brake_angular_max).unit("rad/s^2").range(0.1, 500),
      field("max_linear_kick_speed", &RobotLimits::max_linear_kick_speed).unit("m/s").range(0, 15),
      field("max_chip_kick_speed", &RobotLimits::max_chip_kick_speed).unit("m/s").range(0, 15),
      field("max_chip_angle", &RobotLimits::max_chip_angle).unit("rad").range(0, 1.5),
      field("max_dribbler_rpm", &RobotLimits::max_dribbler_rpm).unit("rpm").range(0, 65535),
  };
}

Fields<RobotLinkConfig> robot_link_fields() {
  return Fields<RobotLinkConfig>{
      field("team", &RobotLinkConfig::team).one_of({"", "blue", "yellow"}).doc("\"\": give --team"),
      field("backend", &RobotLinkConfig::backend)
          .values(
              {{"sim", BackendKind::kSim}, {"grsim", BackendKind::kGrsim}, {"radio", BackendKind::kRadio}}),
      field("send_rate", &RobotLinkConfig::send_rate)
          .unit("Hz")
          .range(1, 1000)
          .doc("the radio's rate: new commands leave at once within it (token bucket, burst 2), and with nothing "
               "new the last ones are resent this often (heartbeat)"),
      field("command_timeout", &RobotLinkConfig::command_timeout)
          .unit("s")
          .range(0.005, 10)
          .doc("watchdog: a robot without a fresh command this long is stopped"),
      field("startup_stop", &RobotLinkConfig::startup_stop)
          .unit("s")
          .range(0, 10)
          .doc("every uncommanded robot id gets stops this long after start"),
      field("feedback_heartbeat", &RobotLinkConfig::feedback_heartbeat)
          .unit("s")
          .range(0.01, 10)
          .doc("unchanged robot.feedback is republished this often"),
      field("interface", &RobotLinkConfig::interface_address)
          .doc("local address of the UDP sockets (the interface facing the simulator / base station)"),
      nested("sim", &RobotLinkConfig::sim, sim_fields()),
      nested("radio", &RobotLinkConfig::radio, radio_fields()),
      nested("robot", &RobotLinkConfig::robot, robot_fields()),
      field("estop_device", &RobotLinkConfig::estop_device).doc("serial e-stop device, \"\": none"),
      field("estop_device_baud", &RobotLinkConfig::estop_device_baud).range(9600, 4000000),
      field("keyboard_estop", &RobotLinkConfig::keyboard_estop)
          .doc("space toggles the e-stop (stdin a terminal)"),
  }
      .check([](const RobotLinkConfig& config) -> Status {
        if (!is_supported_baud(config.radio.baud)) {
          return Error{"radio.baud " + std::to_string(config.radio.baud) + " is not a standard baud rate"};
        }
        if (!is_supported_baud(config.estop_device_baud)) {
          return Error{"estop_device_baud " + std::to_string(config.estop_device_baud) +
                       " is not a standard baud rate"};
        }
        if (config.backend == BackendKind::kRadio && config.radio.transport == RadioTransport::kSerial &&
            config.radio.device.empty()) {
          return Error{"backend radio over serial needs radio.device"};
        }
        if (config.command_timeout * config.send_rate < 2) {
          return Error{"command_timeout must span at least two send periods (1 / send_rate)"};
        }
        return {};
      });
}

time::Duration seconds(double value) { return time::duration_from_seconds(value); }

}  // namespace

Result<RobotLinkConfig> load_robot_link_config(std::span<const std::string> files, const std::vector<std::string>& overrides) {
  return config::load_files(files, robot_link_fields(), overrides);
}

Result<RobotLinkConfig> load_robot_link_config(const std::string& path, const std::vector<std::string>& overrides) {
  return load_robot_link_config(std::span<const std::string>(&path, 1), overrides);
}

Result<config::RuntimeParameters<RobotLinkConfig>> robot_link_runtime_parameters(const RobotLinkConfig& config) {
  // The robots' limits (a slower robot in the lab, a weaker kicker). The watchdog, the send rate and the
  // backend stay as started: the safety layer does not change under a running match.
  return config::RuntimeParameters<RobotLinkConfig>::create(
      config, robot_link_fields(),
      {"robot.vel_absolute_max", "robot.vel_angular_max", "robot.acc_speedup_absolute_max",
       "robot.acc_brake_absolute_max", "robot.acc_speedup_angular_max", "robot.acc_brake_angular_max",
       "robot.max_linear_kick_speed", "robot.max_chip_kick_speed", "robot.max_dribbler_rpm"});
}

std::string robot_link_config_yaml(const RobotLinkConfig& config) {
  return config::to_yaml(config, robot_link_fields());
}

Result<TeamColor> config_team(const RobotLinkConfig& config) {
  if (auto team = parse_team(config.team)) return *team;
  return Error{"no team: give --team blue|yellow (or set 'team' in the config file)"};
}

CoreConfig core_config(const RobotLinkConfig& config) {
  return CoreConfig{.limits = config.robot,
                    .command_timeout = seconds(config.command_timeout),
                    .send_period = seconds(1.0 / config.send_rate),
                    .startup_stop = seconds(config.startup_stop)};
}

BackendOptions backend_options(const RobotLinkConfig& config, TeamColor team) {
  BackendOptions options;
  options.kind = config.backend;
  options.team = team;
  options.bind_address = config.interface_address;
  if (config.backend == BackendKind::kRadio) {
    options.host = config.radio.host;
    options.port = config.radio.port;
  } else {
    options.host = config.sim.host;
    options.port = config.sim.port;
  }
  options.grsim_feedback = config.sim.grsim_feedback;
  options.grsim_status_port = config.sim.grsim_status_port;
  options.radio_transport = config.radio.transport;
  options.radio_local_port = config.radio.local_port;
  options.serial_device = config.radio.device;
  options.serial_baud = config.radio.baud;
  return options;
}

}  // namespace ssl::robot_link
