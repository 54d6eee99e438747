#include "services/planner/testing/planned_match.h"

namespace ssl::planner::testing {
namespace {

PlannerConfig planner_config(TeamColor team, const sim::FieldGeometry& field) {
  PlannerConfig config;
  config.team = team;
  config.default_field = wm::testing::field_size(field);
  return config;
}

wm::WorldModelConfig model_config(TeamColor team) {
  wm::WorldModelConfig config;
  config.team = team;
  return config;
}

}  // namespace

PlannedMatch::PlannedMatch(const PlannedMatchOptions& options)
    : harness_({.robots_per_team = options.robots, .seed = options.seed, .field = options.field},
               model_config(TeamColor::kBlue)),
      yellow_model_(model_config(TeamColor::kYellow)),
      robots_(options.robots),
      start_(harness_.now()),
      next_tick_(harness_.now()) {
  yellow_model_.on_geometry(wm::testing::from_sim(harness_.sim().geometry()));
  teams_.push_back({TeamColor::kBlue, Planner(planner_config(TeamColor::kBlue, options.field)), {}});
  teams_.push_back({TeamColor::kYellow, Planner(planner_config(TeamColor::kYellow, options.field)), {}});
  referee_.info.blue_team_on_positive_half = options.blue_on_positive_half;
}

const wm::WorldModel& PlannedMatch::model(TeamColor team) const {
  return team == TeamColor::kBlue ? harness_.model() : yellow_model_;
}

wm::WorldModel& PlannedMatch::model_of(TeamColor team) {
  return team == TeamColor::kBlue ? harness_.model() : yellow_model_;
}

void PlannedMatch::tick(wm::testing::SimHarness& harness) {
  const time::Timestamp now = harness.now();
  if (now < next_tick_) return;
  next_tick_ = now + kPlannerPeriod;
  const double t = time::to_seconds(now - start_);
  while (next_command_ < script_.size() && script_[next_command_].at <= t + 1e-9) {
    referee_.info.command = script_[next_command_++].command;
    ++referee_.info.command_counter;
  }
  for (Team& team : teams_) {
    wm::WorldModel& model = model_of(team.color);
    model.on_referee(referee_.info, now);
    for (const sim::RobotFeedback& f : harness.sim().feedback(team.color)) {
      model.on_feedback({.id = f.id, .ball_in_dribbler = f.dribbler_ball_contact}, now);
    }
    const PlannerInputs inputs{.world = model.state(now), .referee = referee_, .field = model.field().size()};
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
        const sim::WorldSnapshot& truth = harness_.truth(frame.capture_time);
        ball_travel_ += (truth.ball.position.head<2>() - last_ball).norm();
        last_ball = truth.ball.position.head<2>();
        if (after_frame) after_frame(frame, truth);
      });
}

}  // namespace ssl::planner::testing
