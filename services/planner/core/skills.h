// The action nodes of seeds/001: what ONE robot does, as a function of the tick's Situation (the global game
// state) and a typed params struct, returning its MotionIntent. Stateless: anything a skill must remember
// between ticks comes in its params (where a dribble started) or is read from the world (where the ball
// rolls, which way the possessor faces). Plays and the strategy pick the skill and its params; the skill
// layer (motion.h) drives the intent.
//
//   const MotionIntent intent = run_skill(situation, robot, ShootParams{});
//   const MotionIntent intent = pass(situation, robot, {.receiver = {1.0, 2.0}});
//
// All positions are in the TEAM frame (our goal at negative x).
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <variant>

#include "libs/domain/rules.h"
#include "libs/geometry/segment.h"
#include "services/planner/core/motion.h"
#include "services/planner/core/plays.h"

namespace ssl::planner {

enum class Skill {
  kPass,
  kReceive,
  kGoToBall,
  kGoToPoint,
  kTurnWithBall,
  kClear,
  kShoot,
  kStop,
  kOpenSpace,
  kManMark,
  kBlock,
  kDefendGoal,
  kChallenge,
  kRedirect,
};
std::string_view skill_name(Skill skill);

/// Kick the ball to `receiver` so that it arrives there at `arrival_speed` (what a receiver controls).
struct PassParams {
  Vec2 receiver = Vec2::Zero();       // m
  double arrival_speed = 1.5;         // m/s at the receiver
  double ball_deceleration = 0.35;    // m/s^2 of the rolling ball (carpet)
  // A kicked ball first slides and keeps this fraction of its speed once it rolls (5/7: a solid sphere).
  double rolling_fraction = 5.0 / 7.0;
};
/// Wait at `point`; once the ball rolls towards us, stand on its line, dribbler on, and give way as it
/// arrives (the cushion).
struct ReceiveParams {
  Vec2 point = Vec2::Zero();          // m, where the pass is expected
  double cushion = 0.3;               // fraction of the ball's speed we move back with it, near the ball
};
/// Take the ball from the side we come from, dribbler on; a ball rolling away is moved with, away from the
/// defense areas.
struct GoToBallParams {
  double final_speed = 1.0;           // m/s cap for the last part
};
/// Without the ball: to `point`, facing the ball. With it: dribble there, never further than the rules'
/// dribbling distance from where the dribble started.
struct GoToPointParams {
  Vec2 point = Vec2::Zero();
  std::optional<double> orientation;  // rad; default: face the ball (without it) / keep the heading (with it)
  bool with_ball = false;
  std::optional<Vec2> dribble_start;  // where we took the ball (with_ball)
  double max_speed = std::numeric_limits<double>::infinity();  // m/s
};
/// Turn on the spot to `orientation`, the ball held by the dribbler, slowly enough to keep it.
struct TurnWithBallParams {
  double orientation = 0;             // rad
  double max_angular_speed = 3.0;     // rad/s
};
/// Kick the ball away from our goal, where the fewest opponents are.
struct ClearParams {
  double speed = rules::kMaxBallSpeed - 1.0;  // m/s
};
/// Shoot at the widest part of their goal left open by the robots, as seen from the ball. Beyond kShotRange
/// the ball is played towards it to stop before their goal line, not out of the field.
/// Beyond `max_distance` from their goal centre it only gets behind the ball and moves with it (a penalty's
/// attacker running with the ball it played on), kicking once the ball is in range.
struct ShootParams {
  std::optional<double> speed;        // m/s; default: the config's kick speed
  double max_distance = std::numeric_limits<double>::infinity();  // m, ball to their goal centre
};
/// Brake to a standstill.
struct StopParams {};
/// Move to the spot near `anchor` with most room from opponents and a free line from the ball, keeping off
/// the ball on the way (a teammate running across a pass deflects it).
struct OpenSpaceParams {
  Vec2 anchor = Vec2::Zero();
  double radius = 1.0;                // m around the anchor that is searched
};
/// Stay goal-side of opponent robot `opponent`, `distance` from it on its line to our goal.
struct ManMarkParams {
  std::uint32_t opponent = 0;
  double distance = 0.3;              // m, centre to centre
};
/// The possessor `opponent`: while it faces our goal (within `facing_limit`), stand in its mouth (in front
/// of its kicker); once it turns further away, block its line of sight to our goal instead.
struct BlockParams {
  std::uint32_t opponent = 0;
  double facing_limit = 1.0;          // rad between its heading and the direction to our goal
  double distance = 0.3;              // m, centre to centre
};
/// The keeper: on the bisector of the goal as seen from the ball, intercepting a shot on its predicted
/// line; `touch_line`: on the goal line (their penalty before it is taken).
struct DefendGoalParams {
  bool touch_line = false;
};
/// Win a contested ball: no going round it; kick it on the first contact the way we come at it, turned
/// towards their goal by at most `max_turn`, at `speed` (a poke past the opponent towards our wingers).
struct ChallengeParams {
  double max_turn = 0.5;   // rad (the ball must still meet the kicker at the front)
  double speed = 3.0;      // m/s
};
/// Meet a pass at `point` with the kicker armed, facing `aim`: the first touch shoots the ball on (a
/// one-touch redirect; the kicker sends it along the heading). The robot turns towards the ball as far as
/// needed for the ball to meet its front within max_angle of the heading.
struct RedirectParams {
  Vec2 point = Vec2::Zero();          // m, where the pass is expected
  Vec2 aim = Vec2::Zero();            // m, where the redirected ball goes
  double speed = rules::kMaxBallSpeed - 0.5;  // m/s
  double max_angle = 0.9;             // rad between the heading and the way back along the pass
};

using SkillCall = std::variant<PassParams, ReceiveParams, GoToBallParams, GoToPointParams, TurnWithBallParams,
                               ClearParams, ShootParams, StopParams, OpenSpaceParams, ManMarkParams, BlockParams,
                               DefendGoalParams, ChallengeParams, RedirectParams>;
Skill skill_of(const SkillCall& call);
/// A skill one robot runs instead of the tree's choice (Planner::override_skill).
struct SkillOverride {
  SkillCall call;
};

MotionIntent pass(const Situation& s, const wm::RobotState& robot, const PassParams& p);
MotionIntent receive(const Situation& s, const wm::RobotState& robot, const ReceiveParams& p);
MotionIntent go_to_ball(const Situation& s, const wm::RobotState& robot, const GoToBallParams& p);
MotionIntent go_to_point(const Situation& s, const wm::RobotState& robot, const GoToPointParams& p);
MotionIntent turn_with_ball(const Situation& s, const wm::RobotState& robot, const TurnWithBallParams& p);
MotionIntent clear_ball(const Situation& s, const wm::RobotState& robot, const ClearParams& p);
MotionIntent shoot(const Situation& s, const wm::RobotState& robot, const ShootParams& p);
MotionIntent stop(const Situation& s, const wm::RobotState& robot, const StopParams& p);
MotionIntent open_space(const Situation& s, const wm::RobotState& robot, const OpenSpaceParams& p);
MotionIntent man_mark(const Situation& s, const wm::RobotState& robot, const ManMarkParams& p);
MotionIntent block(const Situation& s, const wm::RobotState& robot, const BlockParams& p);
MotionIntent defend_goal(const Situation& s, const wm::RobotState& robot, const DefendGoalParams& p);
MotionIntent challenge(const Situation& s, const wm::RobotState& robot, const ChallengeParams& p);
MotionIntent redirect(const Situation& s, const wm::RobotState& robot, const RedirectParams& p);
/// The skill `call` names, with its params.
MotionIntent run_skill(const Situation& s, const wm::RobotState& robot, const SkillCall& call);

// ---- shared by the skills and the plays ----

/// m from a robot's centre to the ball's centre when the ball touches its dribbler.
double dribbler_distance(const Situation& s);
/// rad, the heading that faces `to` from `from`.
double heading_to(const Vec2& from, const Vec2& to);

/// m from their goal centre beyond which a shot has no chance (shot_quality 0): a ball kicked at the goal
/// from further is a long ball, played to stop before their goal line (shoot).
inline constexpr double kShotRange = 7.0;
/// m/s a flat kick needs for the ball to come to rest `distance` m away: it slides, then rolls, as the
/// league's straight-ball model (wm::BallModel's defaults) says.
double kick_speed_to_rest_after(double distance);
/// The fastest kick (m/s, at most `speed`) along the unit direction `u` from the ball that comes to rest
/// `stop_inside` m before the first field line on its way.
double kick_speed_kept_in(const Situation& s, const Vec2& u, double speed, double stop_inside);

/// The widest part of their goal mouth that no robot (but `shooter`) hides, seen from `from`: its angle (rad,
/// 0 when all of it is hidden) and its middle on the goal line (the goal centre when hidden).
struct GoalOpening {
  double width = 0;  // rad
  Vec2 target = Vec2::Zero();
};
GoalOpening goal_opening(const Situation& s, const Vec2& from, std::optional<std::uint32_t> shooter = std::nullopt);
/// Where a shot goes in: the middle of the widest part of their goal mouth that no robot (but `shooter`)
/// hides from the ball; the goal centre when all of it is hidden.
Vec2 shot_target(const Situation& s, std::optional<std::uint32_t> shooter = std::nullopt);
/// Behind the ball on the line along `u` (where a kick sends it), the dribbler at it, facing along `u`
/// within `max_heading_error` (rad): a kick now goes along `u`.
bool behind_ball_facing(const Situation& s, const wm::RobotState& robot, const Vec2& u, double max_heading_error);
/// The ball lies at `robot`'s dribbler (within `reach` m of touching it: 4 cm by default), in front of it
/// (within 0.35 rad).
bool holds_ball(const Situation& s, const wm::RobotState& robot, double reach = 0.04);
/// A shot at our goal: the ball's path from where it is to where it crosses our goal line inside the mouth
/// (plus a margin), for a ball at least 0.5 m/s fast coming our way from any angle; nullopt otherwise.
std::optional<geom::Segment> shot_path(const Situation& s);

}  // namespace ssl::planner
