#include "services/simulator/adapter/convert.h"

#include <cmath>

#include "libs/league/field_geometry.h"
#include "proto/ssl_simulation_custom_erforce_realism.pb.h"

namespace ssl::sim {
namespace {

constexpr double kMillimetresPerMetre = 1000.0;
constexpr double kDegreesToRadians = M_PI / 180.0;

double to_unix_seconds(time::Timestamp simulated, time::Duration unix_offset) {
  return static_cast<double>((simulated + unix_offset).nanoseconds()) * 1e-9;
}

std::optional<TeamColor> team_from_proto(Team team) {
  if (team == ::BLUE) return TeamColor::kBlue;
  if (team == ::YELLOW) return TeamColor::kYellow;
  return std::nullopt;
}

std::optional<RobotKey> key_from_proto(const RobotId& id, std::vector<SimError>& errors) {
  const auto team = team_from_proto(id.team());
  if (!team) {
    errors.push_back({"UNKNOWN_TEAM", "robot " + std::to_string(id.id()) + " has no team (yellow or blue)"});
    return std::nullopt;
  }
  return RobotKey{*team, id.id()};
}

RobotSpec spec_from_proto(const RobotSpecs& specs, const RobotSpec& base) {
  RobotSpec spec = base;
  if (specs.has_radius()) spec.radius = specs.radius();
  if (specs.has_height()) spec.height = specs.height();
  if (specs.has_mass()) spec.mass = specs.mass();
  if (specs.has_max_linear_kick_speed()) spec.max_linear_kick_speed = specs.max_linear_kick_speed();
  if (specs.has_max_chip_kick_speed()) spec.max_chip_kick_speed = specs.max_chip_kick_speed();
  if (specs.has_center_to_dribbler()) spec.center_to_dribbler = specs.center_to_dribbler();
  if (specs.has_limits()) {
    const auto& limits = specs.limits();
    if (limits.has_acc_speedup_absolute_max()) spec.limits.acc_speedup_absolute_max = limits.acc_speedup_absolute_max();
    if (limits.has_acc_speedup_angular_max()) spec.limits.acc_speedup_angular_max = limits.acc_speedup_angular_max();
    if (limits.has_acc_brake_absolute_max()) spec.limits.acc_brake_absolute_max = limits.acc_brake_absolute_max();
    if (limits.has_acc_brake_angular_max()) spec.limits.acc_brake_angular_max = limits.acc_brake_angular_max();
    if (limits.has_vel_absolute_max()) spec.limits.vel_absolute_max = limits.vel_absolute_max();
    if (limits.has_vel_angular_max()) spec.limits.vel_angular_max = limits.vel_angular_max();
  }
  if (specs.has_wheel_angles()) {
    const auto& wheels = specs.wheel_angles();
    spec.wheel_angles = {wheels.front_right(), wheels.back_right(), wheels.back_left(), wheels.front_left()};
  }
  return spec;
}

/// ER-Force's realism message (the de-facto standard other teams send) as a complete realism config:
/// fields it leaves unset are off, as in the ER-Force simulator.
RealismConfig realism_from_erforce(const RealismConfigErForce& erforce, std::vector<SimError>& errors) {
  RealismConfig realism = RealismConfig::none();
  realism.ball_position_stddev = erforce.stddev_ball_p();
  realism.robot_position_stddev = erforce.stddev_robot_p();
  realism.robot_orientation_stddev = erforce.stddev_robot_phi();
  realism.ball_occlusion = erforce.enable_invisible_ball();
  realism.camera_position_error = erforce.camera_position_error();
  realism.ball_missing_probability = erforce.missing_ball_detections();
  realism.vision_delay = static_cast<double>(erforce.vision_delay()) * 1e-9;
  realism.processing_time_jitter = static_cast<double>(erforce.vision_processing_time()) * 1e-9;
  for (const auto& [has, name] : {std::pair{erforce.has_robot_command_loss(), "robot_command_loss"},
                                  std::pair{erforce.has_robot_response_loss(), "robot_response_loss"},
                                  std::pair{erforce.has_stddev_ball_area(), "stddev_ball_area"},
                                  std::pair{erforce.has_dribbler_ball_detections(), "dribbler_ball_detections"},
                                  std::pair{erforce.has_camera_overlap(), "camera_overlap (set it in the config file)"}}) {
    if (has) errors.push_back({"UNSUPPORTED_REALISM", std::string("realism field ") + name + " is not supported; ignored"});
  }
  return realism;
}

}  // namespace

ControlRequest control_from_proto(const SimulatorCommand& command, std::vector<SimError>& errors) {
  ControlRequest request;
  if (command.has_control()) {
    const SimulatorControl& control = command.control();
    if (control.has_teleport_ball()) {
      const TeleportBall& ball = control.teleport_ball();
      BallTeleport teleport;
      if (ball.has_x()) teleport.x = ball.x();
      if (ball.has_y()) teleport.y = ball.y();
      if (ball.has_z()) teleport.z = ball.z();
      if (ball.has_vx()) teleport.vx = ball.vx();
      if (ball.has_vy()) teleport.vy = ball.vy();
      if (ball.has_vz()) teleport.vz = ball.vz();
      teleport.teleport_safely = ball.teleport_safely();
      teleport.roll = ball.roll();
      teleport.by_force = ball.by_force();
      request.ball = teleport;
    }
    for (const TeleportRobot& robot : control.teleport_robot()) {
      const auto key = key_from_proto(robot.id(), errors);
      if (!key) continue;
      RobotTeleport teleport;
      teleport.key = *key;
      if (robot.has_x()) teleport.x = robot.x();
      if (robot.has_y()) teleport.y = robot.y();
      if (robot.has_orientation()) teleport.orientation = robot.orientation();
      if (robot.has_v_x()) teleport.vx = robot.v_x();
      if (robot.has_v_y()) teleport.vy = robot.v_y();
      if (robot.has_v_angular()) teleport.angular = robot.v_angular();
      if (robot.has_present()) teleport.present = robot.present();
      teleport.by_force = robot.by_force();
      request.robots.push_back(teleport);
    }
    if (control.has_simulation_speed()) request.simulation_speed = control.simulation_speed();
  }
  if (command.has_config()) {
    const SimulatorConfig& config = command.config();
    if (config.has_geometry()) request.field = league::field_from_proto(config.geometry().field());
    for (const RobotSpecs& specs : config.robot_specs()) {
      const auto key = key_from_proto(specs.id(), errors);
      if (key) request.robot_specs.emplace_back(*key, spec_from_proto(specs, RobotSpec{}));
    }
    if (config.has_realism_config()) {
      for (const auto& custom : config.realism_config().custom()) {
        RealismConfigErForce erforce;
        if (custom.UnpackTo(&erforce)) {
          request.realism = realism_from_erforce(erforce, errors);
        } else {
          errors.push_back({"UNSUPPORTED_REALISM", "unknown custom realism config '" + custom.type_url() + "'"});
        }
      }
    }
    if (config.has_vision_port()) {
      errors.push_back({"UNSUPPORTED_VISION_PORT", "the vision port is set with --vision-port at start; ignored"});
    }
  }
  return request;
}

std::vector<RobotCommandFor> commands_from_proto(const RobotControl& control, std::vector<SimError>& errors) {
  std::vector<RobotCommandFor> commands;
  commands.reserve(static_cast<std::size_t>(control.robot_commands_size()));
  for (const ::RobotCommand& wire : control.robot_commands()) {
    RobotCommandFor entry;
    entry.id = wire.id();
    if (wire.id() >= kMaxRobotsPerTeam) {
      errors.push_back({"INVALID_ROBOT_ID", "robot id " + std::to_string(wire.id()) + " is outside 0..15"});
      continue;
    }
    RobotCommand& command = entry.command;
    if (wire.has_move_command()) {
      const RobotMoveCommand& move = wire.move_command();
      switch (move.command_case()) {
        case RobotMoveCommand::kLocalVelocity:
          command.move = RobotCommand::Move::kLocalVelocity;
          command.velocity = {move.local_velocity().forward(), move.local_velocity().left(),
                              move.local_velocity().angular()};
          break;
        case RobotMoveCommand::kGlobalVelocity:
          command.move = RobotCommand::Move::kGlobalVelocity;
          command.velocity = {move.global_velocity().x(), move.global_velocity().y(), move.global_velocity().angular()};
          break;
        case RobotMoveCommand::kWheelVelocity:
          command.move = RobotCommand::Move::kWheelVelocity;
          command.wheel_velocity = {move.wheel_velocity().front_right(), move.wheel_velocity().back_right(),
                                    move.wheel_velocity().back_left(), move.wheel_velocity().front_left()};
          break;
        case RobotMoveCommand::COMMAND_NOT_SET:
          break;
      }
    }
    command.kick_speed = wire.kick_speed();
    command.kick_angle = wire.kick_angle() * kDegreesToRadians;
    command.dribbler_rpm = wire.dribbler_speed();
    commands.push_back(entry);
  }
  return commands;
}

GrsimInput grsim_from_proto(const grSim_Packet& packet, std::vector<SimError>& errors) {
  GrsimInput input;
  if (packet.has_commands()) {
    input.team = packet.commands().isteamyellow() ? TeamColor::kYellow : TeamColor::kBlue;
    for (const grSim_Robot_Command& wire : packet.commands().robot_commands()) {
      if (wire.id() >= kMaxRobotsPerTeam) {
        errors.push_back({"INVALID_ROBOT_ID", "robot id " + std::to_string(wire.id()) + " is outside 0..15"});
        continue;
      }
      RobotCommandFor entry;
      entry.id = wire.id();
      RobotCommand& command = entry.command;
      if (wire.wheelsspeed()) {
        errors.push_back({"UNSUPPORTED_WHEEL_SPEED",
                          "grSim wheel motor speeds are not supported; use the simulation protocol's wheel_velocity"});
      } else {
        command.move = RobotCommand::Move::kLocalVelocity;
        command.velocity = {wire.veltangent(), wire.velnormal(), wire.velangular()};
      }
      // grSim kicks with separate horizontal and vertical speeds; convert to speed and elevation.
      const double horizontal = wire.kickspeedx();
      const double vertical = wire.kickspeedz();
      command.kick_speed = std::hypot(horizontal, vertical);
      command.kick_angle = command.kick_speed > 0 ? std::atan2(vertical, horizontal) : 0.0;
      command.dribbler_rpm = wire.spinner() ? 1000.0 : 0.0;
      input.commands.push_back(entry);
    }
  }
  if (packet.has_replacement()) {
    const grSim_Replacement& replacement = packet.replacement();
    if (replacement.has_ball()) {
      BallTeleport teleport;
      if (replacement.ball().has_x()) teleport.x = replacement.ball().x();
      if (replacement.ball().has_y()) teleport.y = replacement.ball().y();
      if (replacement.ball().has_vx()) teleport.vx = replacement.ball().vx();
      if (replacement.ball().has_vy()) teleport.vy = replacement.ball().vy();
      input.control.ball = teleport;
    }
    for (const grSim_RobotReplacement& robot : replacement.robots()) {
      RobotTeleport teleport;
      teleport.key = {robot.yellowteam() ? TeamColor::kYellow : TeamColor::kBlue, robot.id()};
      teleport.x = robot.x();
      teleport.y = robot.y();
      teleport.orientation = robot.dir() * kDegreesToRadians;
      teleport.present = robot.has_turnon() ? robot.turnon() : true;
      input.control.robots.push_back(teleport);
    }
  }
  return input;
}

Robots_Status grsim_status_to_proto(const std::vector<RobotFeedback>& feedback) {
  Robots_Status status;
  for (const RobotFeedback& robot : feedback) {
    auto* wire = status.add_robots_status();
    wire->set_robot_id(static_cast<std::int32_t>(robot.id));
    wire->set_infrared(robot.dribbler_ball_contact);
    wire->set_flat_kick(false);
    wire->set_chip_kick(false);
  }
  return status;
}

RobotControlResponse response_to_proto(const std::vector<RobotFeedback>& feedback, const std::vector<SimError>& errors) {
  RobotControlResponse response;
  for (const SimError& error : errors) {
    auto* wire = response.add_errors();
    wire->set_code(error.code);
    wire->set_message(error.message);
  }
  for (const RobotFeedback& robot : feedback) {
    auto* wire = response.add_feedback();
    wire->set_id(robot.id);
    wire->set_dribbler_ball_contact(robot.dribbler_ball_contact);
  }
  return response;
}

SimulatorResponse response_to_proto(const std::vector<SimError>& errors) {
  SimulatorResponse response;
  for (const SimError& error : errors) {
    auto* wire = response.add_errors();
    wire->set_code(error.code);
    wire->set_message(error.message);
  }
  return response;
}

SSL_DetectionFrame detection_to_proto(const DetectionFrame& frame, time::Duration unix_offset) {
  SSL_DetectionFrame wire;
  wire.set_frame_number(frame.frame_number);
  wire.set_t_capture(to_unix_seconds(frame.capture_time, unix_offset));
  wire.set_t_sent(to_unix_seconds(frame.sent_time, unix_offset));
  wire.set_camera_id(frame.camera_id);
  for (const BallDetection& ball : frame.balls) {
    auto* out = wire.add_balls();
    out->set_confidence(ball.confidence);
    out->set_area(ball.area);
    out->set_x(static_cast<float>(ball.x * kMillimetresPerMetre));
    out->set_y(static_cast<float>(ball.y * kMillimetresPerMetre));
    if (ball.has_z) out->set_z(static_cast<float>(ball.z * kMillimetresPerMetre));
    out->set_pixel_x(ball.pixel_x);
    out->set_pixel_y(ball.pixel_y);
  }
  auto add_robots = [](const std::vector<RobotDetection>& robots, auto* (SSL_DetectionFrame::*add)(),
                       SSL_DetectionFrame& out_frame) {
    for (const RobotDetection& robot : robots) {
      auto* out = (out_frame.*add)();
      out->set_confidence(robot.confidence);
      out->set_robot_id(robot.robot_id);
      out->set_x(static_cast<float>(robot.x * kMillimetresPerMetre));
      out->set_y(static_cast<float>(robot.y * kMillimetresPerMetre));
      out->set_orientation(static_cast<float>(robot.orientation));
      out->set_pixel_x(robot.pixel_x);
      out->set_pixel_y(robot.pixel_y);
      out->set_height(static_cast<float>(robot.height * kMillimetresPerMetre));
    }
  };
  add_robots(frame.robots_yellow, &SSL_DetectionFrame::add_robots_yellow, wire);
  add_robots(frame.robots_blue, &SSL_DetectionFrame::add_robots_blue, wire);
  return wire;
}

SSL_GeometryData geometry_to_proto(const GeometryData& geometry) {
  auto mm = [](double metres) { return static_cast<std::int32_t>(std::lround(metres * kMillimetresPerMetre)); };
  auto mmf = [](double metres) { return static_cast<float>(metres * kMillimetresPerMetre); };
  SSL_GeometryData wire;
  SSL_GeometryFieldSize* field = wire.mutable_field();
  const FieldGeometry& f = geometry.field;
  field->set_field_length(mm(f.field_length));
  field->set_field_width(mm(f.field_width));
  field->set_goal_width(mm(f.goal_width));
  field->set_goal_depth(mm(f.goal_depth));
  field->set_boundary_width(mm(f.boundary_width));
  field->set_boundary_width_goal_line(mm(f.boundary_width_goal_line));
  field->set_penalty_area_depth(mm(f.penalty_area_depth));
  field->set_penalty_area_width(mm(f.penalty_area_width));
  field->set_center_circle_radius(mm(f.center_circle_radius));
  field->set_line_thickness(mm(f.line_thickness));
  field->set_goal_center_to_penalty_mark(mm(f.goal_center_to_penalty_mark));
  field->set_goal_height(mm(f.goal_height));
  field->set_ball_radius(mmf(geometry.ball_radius));
  field->set_max_robot_radius(mmf(geometry.max_robot_radius));
  field->set_goal_substitution_area_width(mm(f.goal_substitution_area_width));
  for (const FieldLine& line : geometry.lines) {
    auto* out = field->add_field_lines();
    out->set_name(line.name);
    out->mutable_p1()->set_x(mmf(line.p1.x()));
    out->mutable_p1()->set_y(mmf(line.p1.y()));
    out->mutable_p2()->set_x(mmf(line.p2.x()));
    out->mutable_p2()->set_y(mmf(line.p2.y()));
    out->set_thickness(mmf(line.thickness));
    out->set_type(static_cast<SSL_FieldShapeType>(line.type));
  }
  for (const FieldArc& arc : geometry.arcs) {
    auto* out = field->add_field_arcs();
    out->set_name(arc.name);
    out->mutable_center()->set_x(mmf(arc.center.x()));
    out->mutable_center()->set_y(mmf(arc.center.y()));
    out->set_radius(mmf(arc.radius));
    out->set_a1(static_cast<float>(arc.a1));
    out->set_a2(static_cast<float>(arc.a2));
    out->set_thickness(mmf(arc.thickness));
    out->set_type(static_cast<SSL_FieldShapeType>(arc.type));
  }
  for (const CameraCalibration& calibration : geometry.calibrations) {
    auto* out = wire.add_calib();
    out->set_camera_id(calibration.camera_id);
    out->set_focal_length(static_cast<float>(calibration.focal_length));
    out->set_principal_point_x(static_cast<float>(calibration.principal_point_x));
    out->set_principal_point_y(static_cast<float>(calibration.principal_point_y));
    out->set_distortion(static_cast<float>(calibration.distortion));
    out->set_q0(static_cast<float>(calibration.q0));
    out->set_q1(static_cast<float>(calibration.q1));
    out->set_q2(static_cast<float>(calibration.q2));
    out->set_q3(static_cast<float>(calibration.q3));
    out->set_tx(mmf(calibration.tx));
    out->set_ty(mmf(calibration.ty));
    out->set_tz(mmf(calibration.tz));
    out->set_derived_camera_world_tx(mmf(calibration.derived_world.x()));
    out->set_derived_camera_world_ty(mmf(calibration.derived_world.y()));
    out->set_derived_camera_world_tz(mmf(calibration.derived_world.z()));
    out->set_pixel_image_width(calibration.pixel_image_width);
    out->set_pixel_image_height(calibration.pixel_image_height);
  }
  return wire;
}

}  // namespace ssl::sim
