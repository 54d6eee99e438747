// RefereeProfile: which rules the built-in referee enforces and how a match is timed, loaded once from a
// YAML file (deploy/config/referee_profiles/<name>.yaml) and validated by the typed config library, so
// that every error names its key. The profile holds rules and game settings only; field dimensions
// belong to the division and are given to the referee separately (FieldGeometry in builtin_referee.h).
//
// Built-in profiles:
//   * arcade     - goal detection only; after a goal the ball is placed on the centre mark, then
//                  FORCE_START by itself after game.stop_duration; every pending kickoff and its
//                  NORMAL_START also continue by themselves (game.auto_continue), so an AI-vs-AI match
//                  runs without an operator.
//   * simulation - what `./ssl up` runs: goals (the ball placed on the centre mark, the conceding team's
//                  kickoff), out of bounds with placement, keep-out and no progress, all continuing by
//                  themselves.
//   * strict_ai  - every rule; after a goal the ball is placed on the centre mark and the referee stays
//                  in STOP with the kickoff in next_command; the operator issues it. Free kicks after a
//                  successful placement or a foul still follow by themselves. Draws go to extra time.
//
// Units: metres and seconds throughout (durations are plain doubles in seconds, as in every config file).
//
//   ssl::Result<RefereeProfile> profile = load_referee_profile("strict_ai");   // or "path/to/mine.yaml"
//   if (!profile) fail(profile.error().message);  // e.g. "...mine.yaml:7: key 'rules.keep_out.radius': ..."
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "libs/domain/division.h"
#include "libs/domain/rules.h"
#include "libs/common/result.h"
#include "libs/common/team.h"

namespace ssl::referee {

struct GoalDetectionRule {
  bool enabled = false;
  double cooldown = 0;  // s after a counted goal during which further goals are ignored
};

struct OutOfBoundsRule {
  bool enabled = false;
  bool ball_placement = false;  // true: the free-kick team places the ball; false: STOP, operator places it
  double line_distance = rules::kRestartLineDistance;  // m inside the touch line (throw-in, corner, goal kick) and goal line (corner)
  double goal_kick_distance = rules::kGoalKickDistance;  // m inside the goal line for a goal kick
};

struct DefenseAreaRule {
  bool enabled = false;
  std::uint32_t max_defenders = 0;     // robots of a team (goalkeeper included) allowed in their own area
  bool attacker_infringement = false;  // an attacker in the opponent's area is a foul (free kick defenders)
};

/// Defender too close to the kick point: in STOP every robot, during the other team's kickoff, penalty
/// preparation or free kick (before the ball is in play) the defenders keep `radius` from the ball.
struct KeepOutRule {
  bool enabled = false;
  double radius = rules::kStopBallDistance;  // m from the ball to the robot's nearest side
  double violation_persistence = rules::kViolationPersistence;  // s too close before it is a foul
};

/// Interfering with a placement: the other team's robots keep `radius` from the stadium ball -> target.
struct PlacementInterferenceRule {
  bool enabled = false;
  double radius = rules::kPlacementKeepOutDistance;                // m
  double violation_persistence = rules::kViolationPersistence;     // s
  double extra_time = rules::kPlacementInterferenceExtraTime;      // s added to the placing team's time per foul
};

/// Non-stopping: two robots of different teams touching with a relative speed along the line between
/// their centres above `speed`: the faster one fouls (BOT_CRASH_UNIQUE), or both when their speeds differ
/// by less than `drawn_speed_difference` (BOT_CRASH_DRAWN).
struct CrashRule {
  bool enabled = false;
  double speed = rules::kCrashSpeed;                             // m/s
  double drawn_speed_difference = rules::kCrashDrawnDifference;  // m/s
};

/// In STOP every robot stays at or below `max_speed` once `grace` passed since the command.
struct StopSpeedRule {
  bool enabled = false;
  double max_speed = rules::kStopMaxSpeed;  // m/s
  double grace = rules::kStopGrace;         // s
};

/// Stopping: the kicker of a kickoff or free kick touches the ball again before another robot did (or
/// stays in contact while it travels more than `distance`): free kick for the other team.
struct DoubleTouchRule {
  bool enabled = false;
  double distance = rules::kDoubleTouchDistance;  // m
};

/// Non-stopping: a robot accelerates the ball beyond `max_speed`.
struct BallSpeedRule {
  bool enabled = false;
  double max_speed = rules::kMaxBallSpeed;  // m/s
};

/// Stopping: the ball kicked over the field boundary (beyond the walls, FieldGeometry's boundary widths):
/// free kick for the other team.
struct BoundaryCrossingRule {
  bool enabled = false;
};

/// Stopping: a robot dribbles the ball more than `max_distance` from where its contact started.
struct DribblingRule {
  bool enabled = false;
  double max_distance = rules::kMaxDribblingDistance;  // m
};

/// During STOP and free kicks (before the ball is in play) robots keep `distance` from the opponent's
/// defense area; inside it for `violation_persistence`: a foul.
struct AttackerDefenseAreaDistanceRule {
  bool enabled = false;
  double distance = rules::kAttackerDefenseAreaDistance;        // m
  double violation_persistence = rules::kViolationPersistence;  // s
};

/// Stopping: the ball lies in a team's own defense area longer than `time` while running.
struct KeeperHeldBallRule {
  bool enabled = false;
  DivisionSeconds time;  // s (5 A / 10 B per rules)
};

/// Stopping: more robots of a team on the field than it may have (max_allowed_bots, lowered by yellow
/// cards) for longer than `grace` (the time to take a robot off).
struct RobotCountRule {
  bool enabled = false;
  double grace = rules::kRobotRemovalGrace;  // s
};

/// Cards: every `fouls_per_card`-th foul of a team raises MULTIPLE_FOULS and a yellow card, which lowers
/// the team's max_allowed_bots by one for `yellow_card_duration` of playing time; a yellow card while two
/// are active is a red card (the robot stays off for the rest of the match).
struct CardRule {
  bool enabled = false;
  std::uint32_t fouls_per_card = rules::kFoulsPerCard;
  double yellow_card_duration = rules::kYellowCardDuration;  // s of playing time
};

/// A game that does not go on: the ball not moved 0.05 m while running for `timeout` (rules: 5 s in
/// division A, 10 s in B) -> STOP, then FORCE_START after stop_duration (the ball placed first when no
/// robot could reach it), as the Game Controller does.
struct NoProgressRule {
  bool enabled = false;
  DivisionSeconds timeout;  // s
};

struct RefereeRules {
  GoalDetectionRule goal_detection;
  OutOfBoundsRule out_of_bounds;
  DefenseAreaRule defense_area;
  KeepOutRule keep_out;
  NoProgressRule no_progress;
  PlacementInterferenceRule placement_interference;
  CrashRule crash;
  StopSpeedRule stop_speed;
  DoubleTouchRule double_touch;
  BallSpeedRule ball_speed;
  BoundaryCrossingRule boundary_crossing;
  DribblingRule dribbling;
  AttackerDefenseAreaDistanceRule attacker_defense_area_distance;
  KeeperHeldBallRule keeper_held_ball;
  RobotCountRule robot_count;
  CardRule cards;
};

/// Extra time and the shoot-out (rules: elimination matches that are drawn after the second half).
struct ExtraTimeSettings {
  bool enabled = false;        // false: the match ends after the second half whatever the score
  double break_duration = 0;   // s before the first extra half (rules 300)
  double half_duration = 0;    // s of playing time per extra half (rules 150)
  double half_time = 0;        // s between the extra halves (rules 120)
  double shootout_break = 0;   // s before the shoot-out (rules 120)
  std::uint32_t shootout_penalties = 0;  // per team before sudden death (rules 5)
};

struct GameSettings {
  double half_duration = rules::kHalfDuration;  // s of playing time per half
  double half_time = rules::kHalfTime;          // s of half-time break
  TeamColor kickoff_team = TeamColor::kYellow;  // kicks off the first half; the other team the second
  bool force_start_after_goal = false;          // after a goal: STOP, then FORCE_START after stop_duration
  bool auto_continue = false;                   // pending kickoffs / penalties continue without the operator
  double stop_duration = 0;                     // s in STOP (or preparing) before an automatic continuation
  double prepare_timeout = 0;   // s: a preparation gets NORMAL_START at the latest now (auto_continue; rules 10)
  double kickoff_timeout = rules::kKickoffTimeout;  // s after NORMAL_START a kickoff ball is in play unkicked
  DivisionSeconds free_kick_timeout;  // s after a free kick its ball is in play without a kick (rules 5 / 10)
  double penalty_timeout = rules::kPenaltyTimeout;  // s a penalty may last after NORMAL_START
  bool ball_placement = false;  // a team places the ball for a kickoff, penalty or FORCE_START whose ball is
                                // not where the restart needs it (false: STOP until placed by hand)
  double placement_timeout = rules::kPlacementTimeout;      // s a team has to place the ball
  double placement_tolerance = rules::kPlacementTolerance;  // m between ball and target when placed
  std::uint32_t early_end_goals = 0;  // a team with this many goals and a lead of 2 ends the match (rules 10;
                                      // 0: never)
  ExtraTimeSettings extra_time;
};

struct RefereeProfile {
  std::string name;
  RefereeRules rules;
  GameSettings game;
};

/// Loads a profile. `name_or_path` is either the name of a built-in profile ("arcade", "strict_ai": any
/// deploy/config/referee_profiles/<name>.yaml, found with find_deploy_file) or the path of a YAML file
/// (anything containing '/' or ending in .yaml / .yml). Errors name the file and key, or list the
/// built-in names for an unknown one.
Result<RefereeProfile> load_referee_profile(std::string_view name_or_path);

/// Loads a profile from YAML text; `source` names it in errors.
Result<RefereeProfile> load_referee_profile_from_string(std::string_view yaml, std::string_view source);

/// The profile as YAML, in schema order with units and docs as comments (loads back to an equal profile).
std::string referee_profile_yaml(const RefereeProfile& profile);

}  // namespace ssl::referee
