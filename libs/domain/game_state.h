// GameState: what the referee's command means for OUR team, with the helpers strategy code asks
// (halted, stopped, playing, our / their kickoff, free kick, penalty, ball placement, ...). Pure: it is
// fed the referee state and, to notice that a restart was taken, the ball position (any frame, used only
// for distances). The ball placement target is returned in the TEAM frame (converted by TeamFrame).
//
// State machine (as the rules, and UBC's GameState): PREPARE_KICKOFF_X / PREPARE_PENALTY_X set a pending
// restart that becomes "ready" with NORMAL_START; DIRECT_FREE_X is ready at once; a ready restart turns
// into normal play once the ball stayed more than kBallMovedDistance from where it was when the restart
// became ready for kBallMovedHold: a kicked ball moves on, while a jump of the estimate for a frame or two
// (its velocity spiking while robots crowd or pass the ball) is no kick. Playing on such a jump was a
// keep-out foul at their restarts and handed our own restart's pass to the strategy before the kick.
// Where the ball was is the median of the last kReadySamples positions since the command before (the ball
// resting at the restart's spot; without any, the last ball known), for the same reason: a spike at the
// moment of NORMAL_START (predicted 9 cm off for a few frames) made the ball at rest count as moved, our
// kickoff was handed to the strategy and a second robot touched the ball.
// FORCE_START is play at once; STOP, HALT, TIMEOUT, GOAL and BALL_PLACEMENT clear it.
//
//   GameState game(TeamColor::kBlue);
//   game.update(referee, frame, ball_vision);
//   if (game.is_our_kickoff() && game.is_setup()) go_to_kickoff_positions();
#pragma once

#include <array>
#include <cstddef>
#include <optional>

#include "libs/common/team.h"
#include "libs/domain/team_frame.h"
#include "libs/domain/world.h"
#include "libs/time/time.h"

namespace ssl::wm {

enum class Restart { kNone, kKickoff, kPenalty, kDirectFree, kBallPlacement, kTimeout };

class GameState {
 public:
  static constexpr double kBallMovedDistance = 0.05;  // m, rules 5.4: the ball is in play after 0.05 m
  static constexpr double kBallMovedHold = 0.05;      // s it stays beyond that before we play on
  static constexpr std::size_t kReadySamples = 9;     // update_ball() positions the reference is the median of

  explicit GameState(TeamColor us = TeamColor::kBlue) : us_(us) {}

  /// Applies a referee state; `ball` (vision frame) is where the ball is now, if known.
  void update(const RefereeInfo& referee, const TeamFrame& frame, const std::optional<Vec2>& ball);
  /// Tells the state machine where the ball is (vision frame) at `now` (any one clock); a taken restart
  /// becomes play.
  void update_ball(const Vec2& ball, time::Timestamp now);

  RefereeCommand command() const { return command_; }
  Restart restart() const { return restart_; }

  bool is_halted() const { return command_ == RefereeCommand::kHalt; }
  bool is_stopped() const { return command_ == RefereeCommand::kStop || is_goal(); }
  bool is_timeout() const { return restart_ == Restart::kTimeout; }
  bool is_goal() const {
    return command_ == RefereeCommand::kGoalBlue || command_ == RefereeCommand::kGoalYellow;
  }
  /// Normal play: robots may touch the ball freely.
  bool is_playing() const { return playing_; }
  /// A restart was announced but NORMAL_START has not come yet (move to positions).
  bool is_setup() const { return pending_ && !ready_; }
  /// The restart may be taken now (after NORMAL_START, or a free kick).
  bool is_ready() const { return ready_; }

  bool is_kickoff() const { return restart_ == Restart::kKickoff; }
  bool is_penalty() const { return restart_ == Restart::kPenalty; }
  bool is_free_kick() const { return restart_ == Restart::kDirectFree; }
  bool is_ball_placement() const { return restart_ == Restart::kBallPlacement; }

  bool is_our_kickoff() const { return is_kickoff() && ours_; }
  bool is_their_kickoff() const { return is_kickoff() && !ours_; }
  bool is_our_penalty() const { return is_penalty() && ours_; }
  bool is_their_penalty() const { return is_penalty() && !ours_; }
  /// A penalty whose ball is in play and which no new command ended yet (goal, STOP): its attacker may
  /// touch the ball again until the penalty is decided.
  bool is_our_penalty_in_play() const { return penalty_in_play_ && ours_; }
  bool is_their_penalty_in_play() const { return penalty_in_play_ && !ours_; }
  bool is_our_free_kick() const { return is_free_kick() && ours_; }
  bool is_their_free_kick() const { return is_free_kick() && !ours_; }
  bool is_our_ball_placement() const { return is_ball_placement() && ours_; }
  bool is_their_ball_placement() const { return is_ball_placement() && !ours_; }
  bool is_our_timeout() const { return is_timeout() && ours_; }
  bool is_their_timeout() const { return is_timeout() && !ours_; }
  /// Robots must keep 0.5 m from the ball (STOP, their restarts, ball placement).
  bool must_keep_distance_from_ball() const {
    return is_stopped() || (restart_ != Restart::kNone && !ours_) || is_ball_placement();
  }

  /// Ball placement target in the TEAM frame, when placing.
  std::optional<Vec2> ball_placement_position() const { return placement_team_; }
  std::uint32_t our_goalkeeper() const { return our_goalkeeper_; }
  std::uint32_t their_goalkeeper() const { return their_goalkeeper_; }
  /// Whether OUR team may still place the ball, and how many robots it may have on the field.
  bool we_can_place_ball() const { return we_can_place_ball_; }
  std::uint32_t our_max_allowed_bots() const { return our_max_allowed_bots_; }

 private:
  void set_restart(Restart restart, TeamColor team, bool ready);
  /// The median (per axis) of the update_ball() positions since the last command (the last kReadySamples),
  /// else the last ball known.
  std::optional<Vec2> ball_at_rest() const;

  TeamColor us_;
  RefereeCommand command_ = RefereeCommand::kHalt;
  std::optional<std::uint32_t> command_counter_;
  Restart restart_ = Restart::kNone;
  bool ours_ = false;
  bool pending_ = false;
  bool ready_ = false;
  bool playing_ = false;
  bool penalty_in_play_ = false;
  std::optional<Vec2> ball_at_ready_;  // vision frame
  std::optional<time::Timestamp> moved_since_;  // the ball beyond kBallMovedDistance since
  std::optional<Vec2> last_ball_;      // vision frame
  std::array<Vec2, kReadySamples> recent_balls_{};  // ring of update_ball() positions, vision frame
  std::size_t recent_count_ = 0;                    // positions put in it since the last command
  std::optional<Vec2> placement_team_;
  std::uint32_t our_goalkeeper_ = 0;
  std::uint32_t their_goalkeeper_ = 0;
  bool we_can_place_ball_ = true;
  std::uint32_t our_max_allowed_bots_ = 11;
};

}  // namespace ssl::wm
