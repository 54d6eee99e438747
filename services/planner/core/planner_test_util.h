// Test helpers for the planner core: scripted worlds (TEAM frame), referee states (VISION frame and
// colours, as the referee sends them) and a trivial kinematic robot/ball model for closed-loop tests.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "libs/common/team.h"
#include "libs/geometry/angle.h"
#include "services/planner/core/motion.h"
#include "services/planner/core/planner.h"
#include "libs/domain/team_field.h"
#include "libs/domain/team_frame.h"
#include "libs/domain/world.h"

namespace ssl::planner::testing {

using wm::RefereeCommand;

/// Our colour and the side the referee says blue defends.
struct Side {
  TeamColor us = TeamColor::kBlue;
  bool blue_on_positive_half = false;

  wm::TeamFrame frame() const { return wm::TeamFrame::make(us, blue_on_positive_half); }
  std::string name() const {
    return std::string(to_string(us)) + (blue_on_positive_half ? "_BluePositive" : "_BlueNegative");
  }
};

inline void PrintTo(const Side& side, std::ostream* os) { *os << side.name(); }

/// Test name suffix of a parameterised test over sides.
inline std::string side_name(const ::testing::TestParamInfo<Side>& param) { return param.param.name(); }

inline std::vector<Side> all_sides() {
  return {{TeamColor::kBlue, false},
          {TeamColor::kBlue, true},
          {TeamColor::kYellow, false},
          {TeamColor::kYellow, true}};
}

enum class Restart { kKickoff, kPenalty, kFreeKick, kPlacement, kTimeout };

/// The referee command of `restart` for `team`.
inline RefereeCommand command_for(Restart restart, TeamColor team) {
  const bool blue = team == TeamColor::kBlue;
  switch (restart) {
    case Restart::kKickoff:
      return blue ? RefereeCommand::kPrepareKickoffBlue : RefereeCommand::kPrepareKickoffYellow;
    case Restart::kPenalty:
      return blue ? RefereeCommand::kPreparePenaltyBlue : RefereeCommand::kPreparePenaltyYellow;
    case Restart::kFreeKick:
      return blue ? RefereeCommand::kDirectFreeBlue : RefereeCommand::kDirectFreeYellow;
    case Restart::kPlacement:
      return blue ? RefereeCommand::kBallPlacementBlue : RefereeCommand::kBallPlacementYellow;
    case Restart::kTimeout: return blue ? RefereeCommand::kTimeoutBlue : RefereeCommand::kTimeoutYellow;
  }
  return RefereeCommand::kHalt;
}

inline constexpr std::uint32_t kOurKeeper = 0;
inline constexpr double kRadius = 0.09;

/// Scripted inputs for one side: the team-frame world plus a referee in the vision frame.
class Script {
 public:
  explicit Script(Side side) : side_(side) {
    world_.team = side.us;
    world_.flipped = side.frame().flipped();
    set_ball({0, 0});
  }

  const Side& side() const { return side_; }
  wm::Field field() const { return wm::Field(wm::FieldSize{}); }
  RefereeCommand ours(Restart r) const { return command_for(r, side_.us); }
  RefereeCommand theirs(Restart r) const { return command_for(r, opponent(side_.us)); }

  void set_ball(const Vec2& team, const Vec2& velocity = Vec2::Zero()) {
    world_.has_ball = true;
    world_.ball.visible = true;
    world_.ball.confidence = 1;
    world_.ball.position = wm::Vec3(team.x(), team.y(), 0.0215);
    world_.ball.velocity = wm::Vec3(velocity.x(), velocity.y(), 0);
  }
  Vec2 ball() const { return world_.ball.position.head<2>(); }

  void add_friend(std::uint32_t id, const Vec2& p, double heading = 0, const Vec2& v = Vec2::Zero()) {
    wm::RobotState r;
    r.id = id;
    r.position = p;
    r.orientation = heading;
    r.velocity = v;
    r.visible = true;
    r.confidence = 1;
    world_.friendly.push_back(r);
  }
  void add_enemy(std::uint32_t id, const Vec2& p) {
    wm::RobotState r;
    r.id = id;
    r.position = p;
    r.visible = true;
    r.confidence = 1;
    world_.enemy.push_back(r);
  }
  std::vector<wm::RobotState>& friends() { return world_.friendly; }
  std::vector<wm::RobotState>& enemies() { return world_.enemy; }
  wm::RobotState* robot(std::uint32_t id) {
    for (auto& r : world_.friendly) {
      if (r.id == id) return &r;
    }
    return nullptr;
  }

  /// 11 v 11 spread over the field; our keeper (id 0) in goal.
  void default_teams() {
    const Vec2 ours[] = {{-5.8, 0},  {-3.5, 1.0}, {-3.5, -1.0}, {-2.0, 2.5}, {-2.0, -2.5}, {-1.0, 0.5},
                         {0.5, 1.5}, {0.7, -1.8}, {2.0, 3.0},   {2.5, -0.5}, {3.0, 1.0}};
    for (std::uint32_t id = 0; id < 11; ++id) add_friend(id, ours[id]);
    for (std::uint32_t id = 0; id < 11; ++id) add_enemy(id, Vec2(-ours[id].x(), -ours[id].y() + 0.3));
  }

  /// Sets the referee command (a new counter when it changes); `designated_team` is converted to vision.
  void command(RefereeCommand command, std::optional<RefereeCommand> next = std::nullopt,
               std::optional<Vec2> designated_team = std::nullopt) {
    if (command != referee_.command || counter_ == 0) ++counter_;
    referee_.command = command;
    referee_.command_counter = counter_;
    referee_.blue_team_on_positive_half = side_.blue_on_positive_half;
    referee_.next_command = next;
    referee_.designated_position.reset();
    if (designated_team) referee_.designated_position = side_.frame().to_vision_point(*designated_team);
    referee_.blue_goalkeeper = side_.us == TeamColor::kBlue ? kOurKeeper : 4;
    referee_.yellow_goalkeeper = side_.us == TeamColor::kYellow ? kOurKeeper : 4;
  }
  /// How many of our robots the referee allows on the field (cards).
  void max_allowed_bots(std::uint32_t n) {
    (side_.us == TeamColor::kBlue ? referee_.blue_max_allowed_bots : referee_.yellow_max_allowed_bots) = n;
  }
  void can_place(bool can) {
    (side_.us == TeamColor::kBlue ? referee_.blue_can_place_ball : referee_.yellow_can_place_ball) = can;
  }

  PlannerInputs inputs() const { return {.world = world_, .referee = referee_, .field = std::nullopt}; }

 private:
  Side side_;
  wm::WorldState world_;
  wm::RefereeInfo referee_;
  std::uint32_t counter_ = 0;
};

inline PlannerConfig config_for(const Side& side) {
  PlannerConfig config;
  config.team = side.us;
  return config;
}

/// A visible robot of ours at `position` (team frame), for the skill-layer tests.
inline wm::RobotState robot_at(const Vec2& position, double heading = 0, std::uint32_t id = 1) {
  wm::RobotState robot;
  robot.id = id;
  robot.position = position;
  robot.orientation = heading;
  robot.visible = true;
  return robot;
}

/// An active intent to `target` (team frame), everything else as MotionIntent's defaults.
inline MotionIntent go_to(const Vec2& target) {
  MotionIntent intent;
  intent.active = true;
  intent.target = target;
  return intent;
}

inline time::Timestamp at_tick(int tick) { return time::Timestamp::from_milliseconds(1'000'000 + tick * 10); }

inline Vec2 team_velocity(const RobotCommand& c, double heading) { return to_team(c, heading); }
inline double speed(const RobotCommand& c) { return std::hypot(c.forward, c.left); }

/// Distance from `p` to their defense area (team frame), 0 inside.
inline double distance_to_their_defense_area(const wm::Field& field, const Vec2& p) {
  const double x0 = field.half_length() - field.size().penalty_area_depth;
  const double h = field.size().penalty_area_width / 2;
  const double dx = std::max(x0 - p.x(), 0.0);
  const double dy = std::max(std::abs(p.y()) - h, 0.0);
  return std::hypot(dx, dy);
}

inline double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

/// Kinematic robots and a ball that sticks to a dribbling robot, for closed-loop tests.
class KinematicSim {
 public:
  explicit KinematicSim(Script& script) : script_(script) {}

  void apply(const PlannerOutput& out, double dt) {
    const double dd = kRadius + 0.0215;
    Vec2 ball = script_.ball();
    Vec2 ball_v = script_.inputs().world.ball.velocity.head<2>();
    bool held = false;
    for (const RobotCommand& c : out.commands) {
      wm::RobotState* r = script_.robot(c.id);
      if (!r) continue;
      const Vec2 v = to_team(c, r->orientation);
      r->position += v * dt;
      r->velocity = v;
      r->orientation = geom::Angle::from_radians(r->orientation + c.angular * dt).radians();
      r->angular_velocity = c.angular;
      const Vec2 heading = geom::Angle::from_radians(r->orientation).to_unit_vector();
      const Vec2 rel = ball - r->position;
      const bool in_front = rel.norm() < dd + 0.025 && rel.normalized().dot(heading) > 0.8;
      if (c.kick != KickType::kNone && in_front) {
        ball_v = heading * c.kick_speed;
        kicked_ = true;
      } else if (c.dribbler_rpm > 0 && in_front) {
        ball = r->position + heading * dd;
        ball_v = v;
        held = true;
      } else if (rel.norm() < dd) {
        touched_ = true;  // a push: the ball is moved out of the robot
        ball = r->position + geom::normalized_or_zero(rel) * dd;
      }
    }
    if (!held) {
      ball += ball_v * dt;
      const double s = ball_v.norm();
      ball_v = s > 0.004 ? Vec2(ball_v * ((s - 0.4 * dt) / s)) : Vec2::Zero();
    }
    script_.set_ball(ball, ball_v);
  }

  bool kicked() const { return kicked_; }
  bool touched() const { return touched_; }

 private:
  Script& script_;
  bool kicked_ = false;
  bool touched_ = false;
};

}  // namespace ssl::planner::testing
