#include "services/planner/testing/planned_match.h"

#include <algorithm>
#include <stdexcept>

#include "libs/domain/idl_convert.h"
#include "services/referee_gateway/adapter/builtin_service.h"
#include "services/referee_gateway/adapter/convert.h"

namespace ssl::planner::testing {
namespace {

PlannerConfig planner_config(TeamColor team, const PlannedMatchOptions& options) {
  PlannerConfig config;
  config.team = team;
  config.motion = options.motion;
  config.strategy = team == TeamColor::kBlue ? options.blue_strategy : options.yellow_strategy;
  config.free_kick = team == TeamColor::kBlue ? options.blue_free_kick : options.yellow_free_kick;
  config.kickoff = team == TeamColor::kBlue ? options.blue_kickoff : options.yellow_kickoff;
  config.penalty = team == TeamColor::kBlue ? options.blue_penalty : options.yellow_penalty;
  // Under ideal conditions commands act at once: nothing to measure, the planners expect no latency (as the
  // harness always had it); otherwise they plan with the delay their world models measure.
  config.actuation_latency = options.actuation_latency.value_or(
      options.conditions == Conditions::kIdeal ? 0.0 : PlannerConfig().actuation_latency);
  config.measured_latency = options.conditions != Conditions::kIdeal;
  config.default_field = options.field;
  return config;
}

wm::WorldModelConfig model_config(TeamColor team, Conditions conditions) {
  wm::WorldModelConfig config;
  config.team = team;
  config.command_delay.estimate = conditions != Conditions::kIdeal;
  return config;
}

sim::RealismConfig vision_under(Conditions conditions) {
  return conditions == Conditions::kHarsh ? sim::RealismConfig::competition() : sim::RealismConfig::realistic();
}

/// The simulator's robot response of the same name as the conditions.
sim::RobotResponse response_under(Conditions conditions) { return *sim::RobotResponse::profile(to_string(conditions)); }

/// A camera frame as vision.detection carries it to the built-in referee (received when it was sent).
idl::vision::DetectionFrame detection_sample(const sim::DetectionFrame& frame) {
  idl::vision::DetectionFrame out;
  out.camera_id(frame.camera_id);
  out.frame_number(frame.frame_number);
  out.capture_unix_ns(frame.capture_time.nanoseconds());
  out.sent_unix_ns(frame.sent_time.nanoseconds());
  out.receive_unix_ns(frame.sent_time.nanoseconds());
  for (const sim::BallDetection& ball : frame.balls) {
    idl::vision::BallDetection b;
    b.x(ball.x);
    b.y(ball.y);
    b.confidence(static_cast<float>(ball.confidence));
    out.balls().push_back(b);
  }
  auto robots = [](const std::vector<sim::RobotDetection>& detections, std::vector<idl::vision::RobotDetection>& into) {
    for (const sim::RobotDetection& robot : detections) {
      idl::vision::RobotDetection r;
      r.robot_id(robot.robot_id);
      r.x(robot.x);
      r.y(robot.y);
      r.orientation(robot.orientation);
      r.has_orientation(true);
      r.confidence(static_cast<float>(robot.confidence));
      into.push_back(r);
    }
  };
  robots(frame.robots_yellow, out.robots_yellow());
  robots(frame.robots_blue, out.robots_blue());
  return out;
}

std::optional<referee::BuiltinReferee> make_referee(const PlannedMatchOptions& options) {
  if (!options.referee) return std::nullopt;
  const Division division =
      options.field.field_length > sim::FieldGeometry::division_b().field_length ? Division::kA : Division::kB;
  return referee::BuiltinReferee(*options.referee, options.field,
                                 {.yellow = {"yellow", 0},
                                  .blue = {"blue", 0},
                                  .division = division,
                                  .max_allowed_bots = max_robots_per_team(division),
                                  .blue_on_positive_half = options.blue_on_positive_half});
}

}  // namespace

std::optional<Conditions> conditions_named(std::string_view name) {
  if (name == "ideal") return Conditions::kIdeal;
  if (name == "realistic") return Conditions::kRealistic;
  if (name == "harsh") return Conditions::kHarsh;
  return std::nullopt;
}

const char* to_string(Conditions conditions) {
  switch (conditions) {
    case Conditions::kIdeal: return "ideal";
    case Conditions::kRealistic: return "realistic";
    case Conditions::kHarsh: return "harsh";
  }
  return "?";
}

PlannedMatch::PlannedMatch(const PlannedMatchOptions& options)
    : harness_({.robots_per_team = options.robots,
                .realism = vision_under(options.conditions),
                .response = response_under(options.conditions),
                .seed = options.seed,
                .field = options.field},
               model_config(TeamColor::kBlue, options.conditions)),
      yellow_model_(model_config(TeamColor::kYellow, options.conditions)),
      robots_(options.robots),
      builtin_(make_referee(options)),
      referee_sees_vision_(options.conditions != Conditions::kIdeal),
      start_(harness_.now()),
      next_tick_(harness_.now()) {
  yellow_model_.on_geometry(wm::testing::from_sim(harness_.sim().geometry()));
  teams_.push_back({TeamColor::kBlue, Planner(planner_config(TeamColor::kBlue, options)), {}});
  teams_.push_back({TeamColor::kYellow, Planner(planner_config(TeamColor::kYellow, options)), {}});
  scripted_.blue_team_on_positive_half = options.blue_on_positive_half;
}

const wm::WorldModel& PlannedMatch::model(TeamColor team) const {
  return team == TeamColor::kBlue ? harness_.model() : yellow_model_;
}

const PlannerOutput& PlannedMatch::output(TeamColor team) const {
  return team == teams_[0].color ? teams_[0].out : teams_[1].out;
}

Planner& PlannedMatch::planner(TeamColor team) {
  return team == teams_[0].color ? teams_[0].planner : teams_[1].planner;
}

wm::WorldModel& PlannedMatch::model_of(TeamColor team) {
  return team == TeamColor::kBlue ? harness_.model() : yellow_model_;
}

void PlannedMatch::start_match() {
  if (builtin_) (void)builtin_->command(referee::Command::kStop, harness_.now());
}

wm::RefereeInfo PlannedMatch::referee_info() const {
  if (!builtin_) return scripted_;
  // Through the wire types and the services' one conversion, as referee.state reaches them.
  Result<wm::RefereeInfo> info = referee_info_from_idl(referee::to_idl(builtin_->state()));
  if (!info) throw std::logic_error("the built-in referee's state does not convert: " + info.error().message);
  return *info;
}

void PlannedMatch::step_referee(wm::testing::SimHarness& harness, const sim::WorldSnapshot& truth,
                                time::Timestamp now) {
  if (referee_sees_vision_) {
    // As referee_gateway's built-in referee: the newest frame of each camera received within its 100 ms.
    builtin_->step(referee_vision_.observe(now, referee::kVisionMaxAge), now);
  } else {
    referee::Observation seen{.ball_position = truth.ball.position.head<2>(),
                              .ball_velocity = truth.ball.velocity.head<2>()};
    for (const sim::RobotState& robot : truth.robots) {
      seen.robots.push_back({.team = robot.key.team, .id = robot.key.id, .position = robot.position});
    }
    builtin_->step(seen, now);
  }
  // The simulator places the ball, as builtin.teleport_placement has it do for `./ssl up`.
  const referee::RefereeState& state = builtin_->state();
  const bool placing = state.command == referee::Command::kBallPlacementYellow ||
                       state.command == referee::Command::kBallPlacementBlue;
  if (!placing || !state.designated_position || teleported_for_ == state.command_counter) return;
  teleported_for_ = state.command_counter;
  sim::ControlRequest request;
  request.ball = sim::BallTeleport{.x = state.designated_position->x(),
                                   .y = state.designated_position->y(),
                                   .z = 0.0,
                                   .vx = 0.0,
                                   .vy = 0.0,
                                   .vz = 0.0,
                                   .teleport_safely = true};
  if (harness.sim().apply(request).empty()) ++placements_teleported_;
}

Result<referee::RefereeProfile> unattended_strict_ai(double half_duration) {
  Result<referee::RefereeProfile> profile = referee::load_referee_profile("strict_ai");
  if (!profile) return profile;
  profile->game.half_duration = half_duration;
  profile->game.half_time = 10;
  profile->game.auto_continue = true;
  profile->game.early_end_goals = 0;
  profile->game.extra_time.enabled = false;
  return profile;
}

bool PlannedMatch::run_until_final_whistle(
    time::Duration limit, const std::function<void(const sim::DetectionFrame&, const sim::WorldSnapshot&)>& after_frame) {
  const time::Timestamp end = harness_.now() + limit;
  constexpr auto kChunk = std::chrono::seconds(1);
  while (builtin_ && builtin_->state().stage != referee::Stage::kPostGame && harness_.now() < end) {
    run(kChunk, after_frame);
  }
  return builtin_ && builtin_->state().stage == referee::Stage::kPostGame;
}

void PlannedMatch::tick(wm::testing::SimHarness& harness) {
  const time::Timestamp now = harness.now();
  if (now < next_tick_) return;
  next_tick_ = now + kPlannerPeriod;
  // The true world at the tick: what the referee observes, and which robots are on the field (a placement
  // teleport moves the ball and robots off its spot, never robots on or off the field).
  const sim::WorldSnapshot truth = harness.sim().snapshot();
  if (builtin_) {
    step_referee(harness, truth, now);
  } else {
    const double t = time::to_seconds(now - start_);
    while (next_command_ < script_.size() && script_[next_command_].at <= t + 1e-9) {
      const ScriptedCommand& issued = script_[next_command_++];
      scripted_.command = issued.command;
      scripted_.next_command = issued.next;
      scripted_.designated_position = issued.designated;
      ++scripted_.command_counter;
    }
  }
  const wm::RefereeInfo referee = referee_info();
  for (Team& team : teams_) {
    wm::WorldModel& model = model_of(team.color);
    model.on_referee(referee, now);
    for (const sim::RobotFeedback& f : harness.sim().feedback(team.color)) {
      model.on_feedback({.id = f.id, .ball_in_dribbler = f.dribbler_ball_contact}, now);
    }
    const PlannerInputs inputs{.world = model.state(now), .referee = referee, .field = model.field().size()};
    team.planner.step(inputs, now, team.out);
    // Robots the planner does not command (not visible) stop, as robot_link does with stale commands.
    std::vector<sim::RobotCommandFor> commands;
    for (std::uint32_t id = 0; id < robots_; ++id) {
      commands.push_back({.id = id, .command = {}});
      commands.back().command.move = sim::RobotCommand::Move::kLocalVelocity;
    }
    for (const RobotCommand& c : team.out.commands) {
      if (c.id >= robots_) continue;
      sim::RobotCommand& s = commands[c.id].command;
      s.velocity = sim::Vec3(c.forward, c.left, c.angular);
      if (c.kick != KickType::kNone) s.kick_speed = c.kick_speed;
      if (c.kick == KickType::kChip) s.kick_angle = c.chip_angle;
      s.dribbler_rpm = c.dribbler_rpm;
    }
    // Robots taken off the field get no command.
    std::erase_if(commands, [&](const sim::RobotCommandFor& c) {
      return std::none_of(truth.robots.begin(), truth.robots.end(),
                          [&](const sim::RobotState& r) { return r.key.team == team.color && r.key.id == c.id; });
    });
    // The harness tells its (blue) model; yellow's model is told here.
    harness.command(team.color, commands, team.color == TeamColor::kBlue);
    if (team.color == TeamColor::kYellow) {
      std::vector<wm::RobotCommand> sent;
      for (const auto& c : commands) {
        sent.push_back({c.id, c.command.velocity.x(), c.command.velocity.y(), c.command.velocity.z()});
      }
      yellow_model_.on_commands(sent, now);
    }
  }
}

void PlannedMatch::run(time::Duration duration,
                       const std::function<void(const sim::DetectionFrame&, const sim::WorldSnapshot&)>& after_frame) {
  geom::Vec2 last_ball = harness_.sim().snapshot().ball.position.head<2>();
  harness_.run(
      duration, [this](wm::testing::SimHarness& harness) { tick(harness); },
      [&](const sim::DetectionFrame& frame) {
        yellow_model_.on_detection(wm::testing::from_sim(frame), harness_.now());
        if (referee_sees_vision_ && builtin_) referee_vision_.add(detection_sample(frame));
        const sim::WorldSnapshot& truth = harness_.truth(frame.capture_time);
        ball_travel_ += (truth.ball.position.head<2>() - last_ball).norm();
        last_ball = truth.ball.position.head<2>();
        if (after_frame) after_frame(frame, truth);
      });
}

}  // namespace ssl::planner::testing
