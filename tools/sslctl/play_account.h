// PlayAccount: how each team played, from observations of the ball and the robots (any one fixed frame, e.g.
// SSL-Vision's, metres) and the referee state: passes tried and completed, shots and shots on target,
// possession. Pure: the caller feeds samples in time order with their times (a live vision stream, a log
// file or a lockstep match's ground truth). Part of the match report (match_report.h).
//
// Rules of the account (only while the ball is in play: NORMAL_START, FORCE_START, free kicks):
//  * a touch: a robot centre within kTouchDistance of the ball centre; the nearest such robot is the ball's
//    last toucher, and its team is in possession until another team's robot touches the ball. Possession is
//    time in play, by the last toucher's team (before the first touch, nobody's).
//  * a kick: the ball's speed rises by at least kKickSpeedGain between two samples to at least
//    kKickMinSpeed (and below kMaxBallSpeed: faster is the ball put somewhere else), a robot within
//    kKickReach: the nearest one kicked it. The first sample after play starts is not compared. With cameras
//    told, the speed is measured between one camera's samples, and the same robot's kick seen by another
//    camera within kSameKick is not counted again.
//  * a shot: a kick whose line crosses the kicker's opponent's goal line within kShotWidthMargin of the goal
//    mouth, towards it (unless its kicker meant a pass or a clearance); on target when it crosses inside the
//    mouth (posts excluded by the ball's radius). Without the field's size (set_field) no kick is a shot.
//    Its end: scored (its team's goal before anybody else touches the ball), saved (the opponents' keeper,
//    as set_keepers tells, touches it first), blocked (another opponent touches it first), or none of these
//    (a teammate touches it first, or play stops: wide).
//  * a pass: any other kick, unless the observer says the kicker meant something else (Intent::kClear, or
//    Intent::kShot: a shooter's kick that misses the goal's direction is a deflection, not a pass), or that
//    its kicker was not armed (Intent::kNoKick: the ball came off the robot's body, a touch and no kick).
//    It is completed when the next robot to touch the ball is a teammate of the kicker (not the kicker),
//    failed when it is an opponent (intercepted), the kicker itself, or play stops first (out).
//  * a restart (a kickoff, penalty or free kick, told by the caller with the team taking it): taken at the
//    first touch by that team once the ball is in play; kept when the next robot to touch the ball after its
//    taker is a teammate, or when the team scores before anybody else touches it (on_goal). Counted by kind.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>

#include "libs/common/team.h"
#include "libs/geometry/vec2.h"
#include "libs/time/time.h"

namespace ssl::sslctl {

/// The restarts of one kind a team took.
struct RestartTally {
  std::uint32_t taken = 0;
  std::uint32_t kept = 0;   // of those: a teammate touched the ball next, or the team scored
  std::uint32_t goals = 0;  // goals with no opponent touch since the team took the restart
};

enum class RestartKind { kKickoff, kPenalty, kFreeKick };

/// A restart the ball is (or is about to be) in play from, and the team taking it.
struct Restart {
  TeamColor team = TeamColor::kBlue;
  RestartKind kind = RestartKind::kFreeKick;
  bool operator==(const Restart&) const = default;
};

struct TeamPlay {
  std::uint32_t passes_tried = 0;
  std::uint32_t passes_completed = 0;
  std::uint32_t passes_intercepted = 0;  // failed: an opponent touched the ball next
  std::uint32_t passes_out = 0;          // failed: play stopped first (the ball left the field, a foul, ...)
  std::uint32_t shots = 0;
  std::uint32_t shots_on_target = 0;
  std::uint32_t shots_scored = 0;   // of the shots: the team's goal before anybody else touched the ball
  std::uint32_t shots_saved = 0;    // the opponents' keeper touched the ball first
  std::uint32_t shots_blocked = 0;  // another opponent touched the ball first
  double shot_distance = 0;         // m: the sum over the shots of the ball's distance from the goal centre
  /// m: the shots' mean distance from the goal centre (0 without shots).
  double shot_distance_mean() const { return shots > 0 ? shot_distance / shots : 0.0; }
  std::uint32_t kicks = 0;        // every kick in play (passes, shots, clearances)
  RestartTally kickoffs;
  RestartTally penalties;
  RestartTally free_kicks;
  double possession = 0;          // s in play with this team's robot the last to touch the ball
};

class PlayAccount {
 public:
  static constexpr double kTouchDistance = 0.13;   // m: robot radius 0.09 + ball radius 0.0215 + 0.02
  static constexpr double kKickReach = 0.25;       // m: robot centre to ball when a kick is recognised
  static constexpr double kKickSpeedGain = 1.0;    // m/s between two samples
  static constexpr double kKickMinSpeed = 1.5;     // m/s
  static constexpr double kSameKick = 0.1;         // s: the kicker's kick seen again this soon is the same
  static constexpr double kMaxBallSpeed = 12.0;    // m/s: faster between two samples is a teleport, not a kick
  static constexpr double kShotWidthMargin = 0.3;  // m beside the goal mouth a shot may cross
  static constexpr double kBallRadius = 0.0215;    // m

  /// What the kicking robot meant, when the observer knows it (a lockstep match reads the planner's skill
  /// and whether it armed its kicker).
  enum class Intent { kUnknown, kPass, kShot, kClear, kNoKick };

  struct Robot {
    TeamColor team = TeamColor::kBlue;
    std::uint32_t id = 0;
    geom::Vec2 position = geom::Vec2::Zero();  // m
    Intent intent = Intent::kUnknown;
  };

  /// The field's length and goal width (m): goals lie at x = +-length / 2.
  void set_field(double length, double goal_width);
  /// The referee's state: whether the ball is in play, which half blue defends, and the restart the ball is
  /// (or is about to be) in play from.
  void on_referee(bool in_play, std::optional<bool> blue_on_positive_half,
                  std::optional<Restart> restart = std::nullopt);
  /// A goal for `team` (settles the restart it was taking and the shot it kicked).
  void on_goal(TeamColor team);
  /// Each team's keeper, as the referee names it (whose first touch saves a shot).
  void set_keepers(std::uint32_t blue, std::uint32_t yellow);
  /// The camera a sample comes from and when it captured it (its own clock): the ball's speed is measured
  /// between samples of one camera.
  struct Camera {
    std::uint32_t id = 0;
    time::Timestamp capture;
  };

  /// One observation of the ball and every robot seen at `t` (older samples are ignored); without a camera
  /// the ball's speed is measured between successive samples at their times `t`.
  void on_frame(const geom::Vec2& ball, std::span<const Robot> robots, time::Timestamp t,
                std::optional<Camera> camera = std::nullopt);

  const TeamPlay& team(TeamColor color) const { return color == TeamColor::kBlue ? blue_ : yellow_; }

 private:
  /// A pass or shot kicked and not yet settled: who kicked it.
  struct OpenKick {
    TeamColor team;
    std::uint32_t kicker;
  };
  TeamPlay& team_of(TeamColor color) { return color == TeamColor::kBlue ? blue_ : yellow_; }
  struct OpenRestart {
    Restart restart;
    std::optional<std::uint32_t> taker;  // once taken
  };
  RestartTally& tally_of(const Restart& restart);
  void on_kick(const Robot& kicker, const geom::Vec2& ball, const geom::Vec2& velocity);
  /// A touch (or kick) by a robot other than the last toucher: takes or settles an open restart, and ends
  /// the move of a taken one when the robot is an opponent.
  void settle_restart(const Robot& robot);
  bool is_shot(TeamColor team, const geom::Vec2& ball, const geom::Vec2& velocity, bool& on_target) const;
  /// A touch (or kick) by `robot` other than the shot's kicker ends the open shot: saved, blocked, or neither.
  void settle_shot(const Robot& robot);
  /// x (m) of the goal `team` attacks; needs the field's length and the sides.
  double attacked_goal_x(TeamColor team) const;

  TeamPlay blue_;
  TeamPlay yellow_;
  std::optional<double> field_length_;
  double goal_width_ = 0;
  bool in_play_ = false;
  std::optional<bool> blue_on_positive_half_;
  /// The ball as one camera (or the camera-less stream) last saw it.
  struct BallTrack {
    std::optional<time::Timestamp> at;  // its capture time
    geom::Vec2 ball = geom::Vec2::Zero();
    double speed = 0;       // m/s, against the sample before
    bool compared = false;  // its speed was measured in play (the first sample in play is not)
  };
  static constexpr std::uint32_t kNoCamera = 0xffffffff;
  std::optional<time::Timestamp> last_frame_;
  std::map<std::uint32_t, BallTrack> ball_tracks_;  // by camera id
  struct LastKick {
    TeamColor team;
    std::uint32_t kicker;
    time::Timestamp at;
  };
  std::optional<LastKick> last_kick_;
  std::optional<TeamColor> possession_;
  std::optional<OpenKick> open_pass_;
  std::optional<OpenKick> open_shot_;
  std::optional<std::uint32_t> blue_keeper_;
  std::optional<std::uint32_t> yellow_keeper_;
  std::optional<OpenRestart> open_restart_;
  std::optional<Restart> restart_move_;  // taken, and no opponent touched the ball since
  std::optional<Restart> restart_;       // as last told by on_referee
  std::optional<std::uint32_t> last_toucher_id_;
  std::optional<TeamColor> last_toucher_team_;
};

}  // namespace ssl::sslctl
