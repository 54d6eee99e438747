// The rulebook's distances, speeds and times that do not depend on the field (those are FieldGeometry's,
// field.h) and are the same in both divisions (per-division ones: division.h). ONE place for each: the
// planner's config defaults, the built-in referee's profile defaults and its fixed thresholds, and the
// keep-out shapes (keep_out.h) all read them here. Metres, metres per second, seconds; distances to a
// robot are from its nearest side unless the name says centre.
//
//   double radius = rules::kStopBallDistance + field.max_robot_radius;  // robot centre from the ball
#pragma once

#include <cstdint>

namespace ssl::rules {

// ---- referee commands (rules: referee commands) ----
/// STOP, and the other team's kickoff / free kick: robots keep this far from the ball.
inline constexpr double kStopBallDistance = 0.5;
/// STOP: every robot at most this fast, after kStopGrace.
inline constexpr double kStopMaxSpeed = 1.5;
inline constexpr double kStopGrace = 2.0;
/// STOP and free kicks before the ball is in play: attackers keep this far from the opponent defense area.
inline constexpr double kAttackerDefenseAreaDistance = 0.2;
/// A kickoff, free kick or penalty ball is in play once it moved this far.
inline constexpr double kInPlayDistance = 0.05;
/// Kickoff: the ball is in play this long after NORMAL_START even if nobody kicked it.
inline constexpr double kKickoffTimeout = 10.0;
/// Penalty: it fails when not decided this long after NORMAL_START.
inline constexpr double kPenaltyTimeout = 10.0;
/// Penalty preparation: every robot but the kicker and the keeper this far behind the ball.
inline constexpr double kPenaltyDistanceBehindBall = 1.0;

// ---- ball placement (rules: ball placement) ----
/// The other team keeps this far from the segment ball -> designated position (a stadium).
inline constexpr double kPlacementKeepOutDistance = 0.5;
/// Placed: the ball at rest within this distance of the designated position.
inline constexpr double kPlacementTolerance = 0.15;
inline constexpr double kPlacementTimeout = 30.0;
/// Each interference foul gives the placing team this much more time.
inline constexpr double kPlacementInterferenceExtraTime = 10.0;
/// A free kick's position: this far inside the field lines, and kRestartDefenseAreaDistance from either
/// defense area; a goal kick's is kGoalKickDistance inside the goal line.
inline constexpr double kRestartLineDistance = 0.2;
inline constexpr double kRestartDefenseAreaDistance = 1.0;
inline constexpr double kGoalKickDistance = 1.0;

// ---- fouls (rules: offenses) ----
/// A non-stopping foul is raised again only after this long (or once its condition cleared).
inline constexpr double kFoulRepeat = 2.0;
/// A robot too close (to the ball, a placement, a defense area) fouls after staying so this long.
inline constexpr double kViolationPersistence = 2.0;
/// Crash: relative speed along the centre line above kCrashSpeed; both foul below kCrashDrawnDifference.
inline constexpr double kCrashSpeed = 1.5;
inline constexpr double kCrashDrawnDifference = 0.3;
/// Double touch: the kicker touched the ball again after it moved this far.
inline constexpr double kDoubleTouchDistance = 0.05;
inline constexpr double kMaxBallSpeed = 6.5;
inline constexpr double kMaxDribblingDistance = 1.0;
/// Too many robots: this long to take one off.
inline constexpr double kRobotRemovalGrace = 10.0;
/// Substitution: the centre substitution area is the boundary within this distance of the halfway line.
inline constexpr double kSubstitutionAreaHalfLength = 1.0;
/// Every kFoulsPerCard-th foul of a team is a yellow card: one robot fewer for kYellowCardDuration of
/// playing time.
inline constexpr std::uint32_t kFoulsPerCard = 3;
inline constexpr double kYellowCardDuration = 120.0;

// ---- match (rules: game structure) ----
inline constexpr double kHalfDuration = 300.0;  // playing time
inline constexpr double kHalfTime = 300.0;
/// A team with this many goals and a lead of at least 2 ends the match early.
inline constexpr std::uint32_t kEarlyEndGoals = 10;

}  // namespace ssl::rules
