// Planner: the pure core of the planner service. Each tick it takes the world (TEAM frame, from
// world.state), the referee state and `now`, ticks the team's behaviour tree and returns one command per
// robot plus what it decided (for planner.debug). No DDS, sockets, threads or clocks; the same inputs give
// the same outputs.
//
// The tree (seeds/000 section 3): a Root selector whose first child is the RefereeOverride subtree (HALT,
// STOP, TIMEOUT, ball placement, kickoff, penalty, direct free kick, each ours or theirs resolved at tick
// time from the command and our colour); NORMAL_START / FORCE_START fall through to the strategy's tree
// (a prepared kickoff / penalty, and a free kick, stay in their branch until the ball is in play, so that
// our kicker may now kick and everybody else keeps the restart's positions; wm::GameState tracks that).
// Tree actions do not write commands: they write per-robot MOTION INTENTS (where to go, how fast at most,
// what to avoid, kick/dribble) to the blackboard; the skill layer turns intents into velocity commands
// (planner I: a simple controller; planner II replaces it with trajectories behind the same interface),
// and a final rule layer enforces the command's limits whatever the tree said (e.g. HALT -> zero, STOP ->
// at most 1.5 m/s).
//
//   Planner planner({.team = TeamColor::kBlue});
//   PlannerOutput out = planner.step({.world = world, .referee = referee}, now);
//   publish(out.commands); publish_debug(out);
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "libs/common/team.h"
#include "libs/time/time.h"
#include "libs/domain/world.h"
#include "libs/domain/rules.h"

namespace ssl::planner {

using wm::Vec2;

struct MotionIntent;   // motion.h
struct SkillOverride;  // skills.h
class MotionPlanner;   // motion.h

struct PlannerInputs {
  wm::WorldState world;               // TEAM frame (world.state)
  wm::RefereeInfo referee;            // referee.state, VISION frame; its side is not read (world.flipped is)
  std::optional<wm::FieldSize> field; // from vision.geometry when known, else the configured division's
};

enum class KickType { kNone, kFlat, kChip };

/// One robot's command, LOCAL frame (as robot.commands): forward towards the dribbler, left, CCW.
struct RobotCommand {
  std::uint32_t id = 0;
  double forward = 0;      // m/s
  double left = 0;         // m/s
  double angular = 0;      // rad/s
  KickType kick = KickType::kNone;
  double kick_speed = 0;   // m/s
  double chip_angle = 0;   // rad
  double dribbler_rpm = 0;
};

/// Debug: who does what, where to (TEAM frame).
struct RoleInfo {
  std::uint32_t robot_id = 0;
  std::string role;     // e.g. "goalkeeper", "kicker", "defender"
  std::string tactic;   // e.g. "stop_formation", "place_ball"
  std::string skill;    // e.g. "move_to", "dribble_to", "kick"
  Vec2 target = Vec2::Zero();
  std::vector<Vec2> path;                 // the planned trajectory every 0.1 s (planner II), team frame
  std::optional<double> tracking_error;   // m, from where last tick's trajectory put the robot now
};

struct TreeNodeInfo {
  std::string name;     // node path or name
  std::uint16_t depth = 0;
  enum class Status { kIdle, kRunning, kSuccess, kFailure } status = Status::kIdle;
};

struct PlannerOutput {
  std::vector<RobotCommand> commands;  // one per visible friendly robot, by id
  std::string play;                    // the active override branch or strategy play, e.g. "stop", "our_kickoff"
  std::string game_tactic;             // the base strategy's coach: "<mode>/<style>" (e.g. "defending/press_ball");
                                       // empty when the referee override or another strategy played
  std::vector<RoleInfo> roles;
  std::vector<TreeNodeInfo> tree;      // depth-first, as ticked
  std::uint64_t tick = 0;
};

struct MotionLimits {
  double max_speed = 3.0;              // m/s, normal play
  double max_acceleration = 3.0;       // m/s^2
  double max_angular_speed = 6.0;      // rad/s
  double max_angular_acceleration = 30;  // rad/s^2
  // m/s^2, 0 for no limit: a robot whose wheels hold the velocity in its own frame (grSim; real robots
  // without a gyro-stabilised controller) must turn that velocity at v * w when it turns its body at w rad/s
  // while moving at v m/s; with a limit the turn is kept slow enough that v * w stays under it. On grSim
  // robots turning faster lost their way: the velocity reached missed the command by 0.2 m/s where v * w
  // stayed under 1 m/s^2, 0.5 m/s at 2-3 and over 1 m/s above 5 (11 v 11, 4 minutes, both teams), and one
  // ran on into another at 1.7 m/s while commanded to stand. The site says it (deploy/sites/grsim).
  double max_turning_acceleration = 0;

  /// rad/s: the fastest turn for a robot moving at `speed` m/s (max_angular_speed at rest or without a limit).
  double angular_speed_at(double speed) const {
    return max_turning_acceleration > 0 && speed * max_angular_speed > max_turning_acceleration
               ? max_turning_acceleration / speed
               : max_angular_speed;
  }

  friend bool operator==(const MotionLimits&, const MotionLimits&) = default;
};

/// The skill layer: planner I's proportional controller with local detours, or planner II's trajectories
/// along a searched path (trajectory_motion.h).
enum class MotionControl { kSimple, kTrajectory };

/// What the team does in normal play (NORMAL_START, FORCE_START); the referee override above it is the
/// same for all. kBase: seeds/001's base strategy; kBallChaser: every field player runs for the ball and the
/// nearest shoots (the baseline the base strategy must beat); kWander: every robot tours waypoints on the
/// field, ball or not (the referee demos: watch each command take over).
enum class Strategy { kBase, kBallChaser, kWander };

/// The base strategy's own free kicks: kShot, the kicker shoots at the widest open part of their goal;
/// kRedirect, the set play of free_kick_set_play (team_play.h) where one rates better, else the shot; kPass,
/// that set play, else a pass to a teammate where the straight shot is poor and a pass rates better, else the
/// shot. kPass keeps the ball after more free kicks (24-27 % against 10-15 % in 11 v 11 lockstep series) but
/// scored no more goals there (2.00 against 2.47 a match, 30 seeds), so kShot stays the default.
enum class FreeKickPlay { kShot, kRedirect, kPass };

/// The base strategy's own kickoffs: kPass, the set play of kickoff_set_play (team_play.h): a pass to a
/// teammate waiting in our half where one rates, else the shot; kShot, the kicker shoots at their goal.
enum class KickoffPlay { kShot, kPass };

/// The base strategy's own penalties: kAdvance, penalty_attack (plays.h): the ball is played on and shot
/// from close in; kShot, the kicker shoots from the mark.
enum class PenaltyPlay { kShot, kAdvance };

struct PlannerConfig {
  TeamColor team = TeamColor::kBlue;
  MotionLimits limits;
  MotionControl motion = MotionControl::kTrajectory;
  Strategy strategy = Strategy::kBase;
  FreeKickPlay free_kick = FreeKickPlay::kShot;  // the base strategy only
  KickoffPlay kickoff = KickoffPlay::kPass;      // the base strategy only
  PenaltyPlay penalty = PenaltyPlay::kAdvance;   // the base strategy only
  // s from the planner's tick until its command acts on the robot (DDS, robot_link, radio): the trajectory
  // skill layer plans from where the last command will have taken the robot by then. world.state is
  // already predicted to now (world_model compensates the vision delay).
  double actuation_latency = 0.015;
  // Plan with world.state's command_delay instead (world_model measures it from our commands and the
  // motion vision shows) once it is known; actuation_latency until then.
  bool measured_latency = true;
  double tick_period = 1.0 / 100;      // s, the first tick's dt; later ticks use the time since the previous one
  double robot_radius = 0.09;          // m
  double stop_speed = rules::kStopMaxSpeed;  // m/s during STOP (a margin is applied below it)
  double stop_speed_margin = 0.2;      // m/s below stop_speed we aim for
  double ball_keep_away = rules::kStopBallDistance;  // m to the ball during STOP / their restarts
  double keep_away_margin = 0.1;       // m, extra we keep to be safe
  double defense_area_keep_away = rules::kAttackerDefenseAreaDistance;  // m, their defense area in STOP
  double placement_tolerance = rules::kPlacementTolerance;  // m, ball placement success radius
  double penalty_line_behind = rules::kPenaltyDistanceBehindBall;  // m, others behind the penalty ball
  double ball_placement_speed = 1.0;   // m/s, the placer while it carries the ball
  double kick_speed = 5.0;             // m/s, shots at the goal (below rules::kMaxBallSpeed)
  double role_hysteresis = 0.3;        // m, a new role assignment must be this much (and 10 %) cheaper
  wm::FieldSize default_field;         // until vision.geometry arrives (division A)
};

class Planner {
 public:
  explicit Planner(const PlannerConfig& config);
  /// With another skill layer (planner II: trajectories). nullptr: the simple controller.
  Planner(const PlannerConfig& config, std::unique_ptr<MotionPlanner> motion);
  ~Planner();
  Planner(Planner&&) noexcept;
  Planner& operator=(Planner&&) noexcept;

  /// One tick at `now` (host wall clock; only differences matter).
  PlannerOutput step(const PlannerInputs& inputs, time::Timestamp now);
  /// The same, into `out` (its vectors and strings are reused: no allocation once they are big enough).
  void step(const PlannerInputs& inputs, time::Timestamp now, PlannerOutput& out);

  /// A run-time parameter change: from the next tick the planner works with `config` (same team). When the
  /// skill layer's limits, kind, robot radius or actuation latency changed, the layer is made anew (its
  /// trajectories restart from the robots' measured motion); roles, the game state and overrides stay.
  void reconfigure(const PlannerConfig& config);

  /// Lab and test use: from the next tick robot `id` (0..15) runs `skill` instead of what the tree decides
  /// (the rule layer still applies: HALT, STOP speed, no kicks while not allowed); nullopt gives it back.
  void override_skill(std::uint32_t id, const std::optional<SkillOverride>& skill);

  /// The motion intent the last tick gave robot `id`, nullptr if it had none (not visible, or id > 15).
  const MotionIntent* last_intent(std::uint32_t id) const;

  /// The tree as ASCII / DOT (last tick's statuses), for --print-tree and the console.
  std::string tree_ascii() const;
  std::string tree_dot() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ssl::planner
