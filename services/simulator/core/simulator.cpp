#include "services/simulator/core/simulator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "services/simulator/core/physics/robot_kinematics.h"

namespace ssl::sim {
namespace {

bool finite(double value) { return std::isfinite(value); }

bool finite(const RobotCommand& command) {
  return command.velocity.allFinite() &&
         std::all_of(command.wheel_velocity.begin(), command.wheel_velocity.end(), [](double v) { return finite(v); }) &&
         finite(command.kick_speed) && finite(command.kick_angle) && finite(command.dribbler_rpm);
}

std::string describe(RobotKey key) { return std::string(to_string(key.team)) + " " + std::to_string(key.id); }

/// Kickoff formation for one team: the team plays on its half (blue at negative x), spread over the half
/// outside the centre circle, robot 0 as keeper in front of its goal.
Vec2 formation_position(const FieldGeometry& field, TeamColor team, std::uint32_t id) {
  const double side = team == TeamColor::kBlue ? -1.0 : 1.0;
  if (id == 0) return {side * (field.field_length / 2 - 0.3), 0.0};
  const std::uint32_t columns = 3;
  const std::uint32_t index = id - 1;
  const double x = side * (0.9 + static_cast<double>(index % columns) * (field.field_length / 2 - 1.8) / (columns - 1));
  const std::uint32_t rows = 6;  // up to 15 field players: 3 columns x 5 rows (+1 spare row)
  const double row = static_cast<double>(index / columns);
  const double y = (row - (rows - 2) / 2.0) * (field.field_width - 1.0) / (rows - 1);
  return {x, y};
}

}  // namespace

namespace {

/// The vision config with the ball models the physics actually follows, so that what the geometry
/// packet publishes (SSL_GeometryModels) is true of this simulator's ball.
VisionConfig with_ball_models(VisionConfig vision, const PhysicsParams& physics) {
  vision.ball_models.acc_slide = -physics.ball_sliding_deceleration;
  vision.ball_models.acc_roll = -physics.ball_rolling_deceleration;
  // A ball kicked without spin rolls once its spin matches its speed: 1 / (1 + I / (m r^2)) of it.
  vision.ball_models.k_switch = 1.0 / (1.0 + physics.ball_inertia_factor);
  return vision;
}

}  // namespace

Simulator::Simulator(const SimulatorOptions& options)
    : options_(options),
      physics_(std::make_unique<PhysicsWorld>(options.field, options.physics)),
      vision_(std::make_unique<VisionModel>(options.field, with_ball_models(options.vision, options.physics),
                                            options.seed)),
      response_random_(options.seed ^ 0x5deece66dULL) {
  if (auto reason = options.response.invalid_reason()) throw std::invalid_argument("robot response: " + *reason);
  for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
    const RobotSpec& spec = team == TeamColor::kBlue ? options_.blue_spec : options_.yellow_spec;
    physics_->set_team_spec(team, spec);
    vision_->set_robot_spec(team, spec);
  }
  place_initial_robots();
}

void Simulator::place_initial_robots() {
  const std::uint32_t count = std::min(options_.robots_per_team, kMaxRobotsPerTeam);
  for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
    const double facing = team == TeamColor::kBlue ? 0.0 : M_PI;
    for (std::uint32_t id = 0; id < count; ++id) {
      physics_->add_robot({team, id}, formation_position(options_.field, team, id), facing);
      vary_limits({team, id});
    }
  }
}

std::vector<SimError> Simulator::apply(const ControlRequest& request) {
  std::vector<SimError> errors;
  if (request.field) rebuild(*request.field);
  for (const auto& [key, spec] : request.robot_specs) {
    if (!(spec.radius > 0 && spec.height > 0 && spec.mass > 0)) {
      errors.push_back({"INVALID_ROBOT_SPEC", "robot spec of " + describe(key) + " needs positive radius, height, mass"});
      continue;
    }
    // Specs apply per team: the physics models one robot type per team, as every league team fields.
    (key.team == TeamColor::kBlue ? options_.blue_spec : options_.yellow_spec) = spec;
    physics_->set_team_spec(key.team, spec);
    vision_->set_robot_spec(key.team, spec);
  }
  if (request.realism) vision_->set_realism(*request.realism);
  for (const auto& teleport : request.robots) {
    if (auto error = apply_robot(teleport)) errors.push_back(*error);
  }
  if (request.ball) {
    if (auto error = apply_ball(*request.ball)) errors.push_back(*error);
  }
  if (request.simulation_speed) {
    if (finite(*request.simulation_speed) && *request.simulation_speed > 0) {
      simulation_speed_ = *request.simulation_speed;
    } else {
      errors.push_back({"INVALID_SIMULATION_SPEED", "simulation_speed must be a positive number"});
    }
  }
  return errors;
}

std::optional<SimError> Simulator::apply_ball(const BallTeleport& teleport) {
  if (teleport.by_force) return SimError{"UNSUPPORTED_BY_FORCE", "teleport by force is not supported; use a plain teleport"};
  for (const auto& value : {teleport.x, teleport.y, teleport.z, teleport.vx, teleport.vy, teleport.vz}) {
    if (value && !finite(*value)) return SimError{"INVALID_VALUE", "ball teleport has a non-finite value"};
  }
  const BallState current = physics_->snapshot().ball;
  const Vec3 position(teleport.x.value_or(current.position.x()), teleport.y.value_or(current.position.y()),
                      teleport.z.value_or(options_.physics.ball_radius));
  const Vec3 velocity(teleport.vx.value_or(0), teleport.vy.value_or(0), teleport.vz.value_or(0));
  physics_->teleport_ball(position, velocity, teleport.roll ? BallSpin::kRolling : BallSpin::kNone);
  if (teleport.teleport_safely) push_robots_away_from_ball();
  return std::nullopt;
}

void Simulator::push_robots_away_from_ball() {
  const WorldSnapshot world = physics_->snapshot();
  const Vec2 ball = world.ball.position.head<2>();
  for (const RobotState& robot : world.robots) {
    const RobotSpec& spec = robot.key.team == TeamColor::kBlue ? options_.blue_spec : options_.yellow_spec;
    const double clearance = spec.radius + options_.physics.ball_radius + 0.05;
    const Vec2 offset = robot.position - ball;
    if (offset.norm() >= clearance) continue;
    const Vec2 away = offset.norm() > 1e-9 ? offset.normalized() : Vec2(robot.key.team == TeamColor::kBlue ? -1 : 1, 0);
    physics_->teleport_robot(robot.key, ball + away * clearance, robot.orientation, Vec2::Zero(), 0);
  }
}

std::optional<SimError> Simulator::apply_robot(const RobotTeleport& teleport) {
  const RobotKey key = teleport.key;
  if (key.id >= kMaxRobotsPerTeam) {
    return SimError{"INVALID_ROBOT_ID", "robot id " + std::to_string(key.id) + " is outside 0..15"};
  }
  if (teleport.by_force) return SimError{"UNSUPPORTED_BY_FORCE", "teleport by force is not supported for " + describe(key)};
  for (const auto& value : {teleport.x, teleport.y, teleport.orientation, teleport.vx, teleport.vy, teleport.angular}) {
    if (value && !finite(*value)) return SimError{"INVALID_VALUE", "teleport of " + describe(key) + " has a non-finite value"};
  }
  if (teleport.present && !*teleport.present) {
    physics_->remove_robot(key);
    return std::nullopt;
  }
  auto find = [&]() -> std::optional<RobotState> {
    for (const RobotState& robot : physics_->snapshot().robots) {
      if (robot.key == key) return robot;
    }
    return std::nullopt;
  };
  std::optional<RobotState> current = find();
  if (!current) {
    if (!teleport.present) {
      return SimError{"UNKNOWN_ROBOT", describe(key) + " is not on the field; set present=true to add it"};
    }
    if (!teleport.x || !teleport.y) {
      return SimError{"MISSING_POSITION", "adding " + describe(key) + " needs x and y"};
    }
    physics_->add_robot(key, {*teleport.x, *teleport.y}, teleport.orientation.value_or(0));
    vary_limits(key);
    current = find();
  }
  const Vec2 position(teleport.x.value_or(current->position.x()), teleport.y.value_or(current->position.y()));
  physics_->teleport_robot(key, position, teleport.orientation.value_or(current->orientation),
                           Vec2(teleport.vx.value_or(0), teleport.vy.value_or(0)), teleport.angular.value_or(0));
  return std::nullopt;
}

std::vector<SimError> Simulator::set_commands(TeamColor team, const std::vector<RobotCommandFor>& commands) {
  std::vector<SimError> errors;
  for (const auto& [id, command] : commands) {
    const RobotKey key{team, id};
    if (!finite(command)) {
      errors.push_back({"INVALID_VALUE", "command for " + describe(key) + " has a non-finite value; ignored"});
      continue;
    }
    if (!command_valid(command)) {
      errors.push_back({"INVALID_VALUE", "command for " + describe(key) +
                                             " has a negative kick speed or a kick angle outside [0, 90) degrees; ignored"});
      continue;
    }
    if (!physics_->has_robot(key)) {
      errors.push_back({"UNKNOWN_ROBOT", describe(key) + " is not on the field; command ignored"});
      continue;
    }
    if (response_random_.bernoulli(options_.response.command_loss)) {
      ++commands_lost_;
      continue;
    }
    if (options_.response.command_delay > 0) {
      responding_[key].in_flight.emplace_back(time() + time::duration_from_seconds(options_.response.command_delay),
                                              command);
      continue;
    }
    act(key, command);
    last_command_[key] = {.at = time()};
  }
  return errors;
}

void Simulator::set_response(const RobotResponse& response) {
  if (auto reason = response.invalid_reason()) throw std::invalid_argument("robot response: " + *reason);
  options_.response = response;
  for (const RobotState& robot : physics_->snapshot().robots) {
    physics_->set_robot_limit_scale(robot.key, 1, 1);
    vary_limits(robot.key);
  }
}

void Simulator::act(RobotKey key, const RobotCommand& command) {
  if (options_.response.velocity_time_constant <= 0) {
    physics_->set_command(key, command);
    return;
  }
  Responding& robot = responding_[key];
  // A new kind of move (local, global, wheels) starts aiming where the robot goes now.
  if (!robot.set_point || robot.set_point->move != command.move) robot.aimed = current_motion(key, command.move);
  robot.set_point = command;
}

RobotCommand Simulator::current_motion(RobotKey key, RobotCommand::Move move) const {
  RobotCommand now{.move = move};
  for (const RobotState& robot : physics_->snapshot().robots) {
    if (robot.key != key) continue;
    const Vec2 local = geom::rotate(robot.velocity, geom::Angle::from_radians(-robot.orientation));
    switch (move) {
      case RobotCommand::Move::kLocalVelocity: now.velocity = Vec3(local.x(), local.y(), robot.angular_velocity); break;
      case RobotCommand::Move::kGlobalVelocity:
        now.velocity = Vec3(robot.velocity.x(), robot.velocity.y(), robot.angular_velocity);
        break;
      case RobotCommand::Move::kWheelVelocity: {
        const RobotSpec& spec = robot.key.team == TeamColor::kBlue ? options_.blue_spec : options_.yellow_spec;
        now.wheel_velocity = wheel_velocities_from_local(spec, spec.radius * options_.physics.wheel_distance_fraction,
                                                         Vec3(local.x(), local.y(), robot.angular_velocity));
        break;
      }
      case RobotCommand::Move::kNone: break;
    }
  }
  return now;
}

void Simulator::deliver_commands(double h) {
  const time::Timestamp now = time();
  const double tau = options_.response.velocity_time_constant;
  const double follow = tau > 0 ? 1.0 - std::exp(-h / tau) : 1.0;
  for (auto it = responding_.begin(); it != responding_.end();) {
    const RobotKey key = it->first;
    Responding& robot = it->second;
    if (!physics_->has_robot(key)) {
      it = responding_.erase(it);
      continue;
    }
    while (!robot.in_flight.empty() && robot.in_flight.front().first <= now) {
      act(key, robot.in_flight.front().second);
      last_command_[key] = {.at = robot.in_flight.front().first};
      robot.in_flight.pop_front();
    }
    if (robot.set_point) {
      const RobotCommand& set_point = *robot.set_point;
      RobotCommand aimed = set_point;
      aimed.velocity = robot.aimed.velocity + follow * (set_point.velocity - robot.aimed.velocity);
      for (std::size_t i = 0; i < aimed.wheel_velocity.size(); ++i) {
        aimed.wheel_velocity[i] =
            robot.aimed.wheel_velocity[i] + follow * (set_point.wheel_velocity[i] - robot.aimed.wheel_velocity[i]);
      }
      robot.aimed = aimed;
      physics_->set_command(key, aimed);
    }
    ++it;
  }
}

void Simulator::vary_limits(RobotKey key) {
  const double spread = options_.response.limit_spread;
  if (spread <= 0) return;
  // Drawn from the seed and the robot alone, so the same robot is the same whenever it is added.
  VisionRandom draw(options_.seed * 0x9e3779b97f4a7c15ULL + static_cast<std::uint64_t>(key.team) * 16 + key.id + 1);
  const double speed = draw.uniform(1 - spread, 1 + spread);
  const double acceleration = draw.uniform(1 - spread, 1 + spread);
  physics_->set_robot_limit_scale(key, speed, acceleration);
}

StepOutput Simulator::step(time::Duration dt) {
  StepOutput output;
  if (dt <= time::Duration::zero()) return output;
  // Advance in physics sub-steps so that each camera captures the world at its own frame time, however
  // long the requested step is (a lockstep client may ask for 100 ms at once).
  const auto sub_step =
      std::chrono::duration_cast<time::Duration>(std::chrono::duration<double>(physics_->params().step));
  for (time::Duration remaining = dt; remaining > time::Duration::zero(); remaining -= sub_step) {
    const time::Duration h = std::min(remaining, sub_step);
    deliver_commands(std::chrono::duration<double>(h).count());
    stop_robots_without_commands();
    physics_->step(h);
    if (physics_->time() + time_offset_ < vision_->next_event_time()) continue;
    VisionOutput vision = vision_->update(snapshot());
    output.frames.insert(output.frames.end(), std::make_move_iterator(vision.frames.begin()),
                         std::make_move_iterator(vision.frames.end()));
    output.geometry_due |= vision.geometry_due;
  }
  return output;
}

void Simulator::stop_robots_without_commands() {
  if (!options_.command_timeout) return;
  const time::Timestamp now = time();
  for (auto& [key, last] : last_command_) {
    if (last.stopped || now - last.at <= *options_.command_timeout) continue;
    last.stopped = true;
    if (!physics_->has_robot(key)) continue;
    act(key, RobotCommand{.move = RobotCommand::Move::kLocalVelocity});
    ++command_timeouts_;
  }
}

std::vector<RobotFeedback> Simulator::feedback(TeamColor team) const {
  std::vector<RobotFeedback> feedback;
  for (const RobotState& robot : physics_->snapshot().robots) {
    if (robot.key.team == team) feedback.push_back({robot.key.id, robot.ball_contact});
  }
  return feedback;
}

time::Timestamp Simulator::time() const { return physics_->time() + time_offset_; }

WorldSnapshot Simulator::snapshot() const {
  WorldSnapshot world = physics_->snapshot();
  world.time += time_offset_;
  return world;
}

void Simulator::rebuild(const FieldGeometry& field) {
  const WorldSnapshot world = snapshot();
  time_offset_ = world.time.since_epoch();  // the new physics world starts at 0; simulated time goes on
  options_.field = field;
  physics_ = std::make_unique<PhysicsWorld>(field, options_.physics);
  physics_->set_team_spec(TeamColor::kBlue, options_.blue_spec);
  physics_->set_team_spec(TeamColor::kYellow, options_.yellow_spec);
  for (const RobotState& robot : world.robots) {
    physics_->add_robot(robot.key, robot.position, robot.orientation);
    vary_limits(robot.key);
  }
  physics_->teleport_ball(world.ball.position, world.ball.velocity);
  vision_->set_field(field);
}

}  // namespace ssl::sim
