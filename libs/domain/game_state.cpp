#include "libs/domain/game_state.h"

#include <algorithm>

namespace ssl::wm {

void GameState::set_restart(Restart restart, TeamColor team, bool ready) {
  restart_ = restart;
  ours_ = team == us_;
  pending_ = true;
  ready_ = ready;
  playing_ = false;
  ball_at_ready_ = ready ? ball_at_rest() : std::nullopt;
  moved_since_.reset();
}

std::optional<Vec2> GameState::ball_at_rest() const {
  const std::size_t n = std::min(recent_count_, kReadySamples);
  if (n == 0) return last_ball_;
  std::array<double, kReadySamples> x{};
  std::array<double, kReadySamples> y{};
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = recent_balls_[i].x();
    y[i] = recent_balls_[i].y();
  }
  const auto median = [n](std::array<double, kReadySamples>& v) {
    const auto middle = v.begin() + static_cast<std::ptrdiff_t>(n / 2);
    std::nth_element(v.begin(), middle, v.begin() + static_cast<std::ptrdiff_t>(n));
    return *middle;
  };
  return Vec2(median(x), median(y));
}

void GameState::update(const RefereeInfo& referee, const TeamFrame& frame, const std::optional<Vec2>& ball) {
  if (ball) last_ball_ = *ball;
  our_goalkeeper_ = us_ == TeamColor::kBlue ? referee.blue_goalkeeper : referee.yellow_goalkeeper;
  their_goalkeeper_ = us_ == TeamColor::kBlue ? referee.yellow_goalkeeper : referee.blue_goalkeeper;
  we_can_place_ball_ = us_ == TeamColor::kBlue ? referee.blue_can_place_ball : referee.yellow_can_place_ball;
  our_max_allowed_bots_ = us_ == TeamColor::kBlue ? referee.blue_max_allowed_bots : referee.yellow_max_allowed_bots;
  placement_team_.reset();
  if (referee.designated_position) placement_team_ = frame.point(*referee.designated_position);
  const bool is_new = !command_counter_ || *command_counter_ != referee.command_counter ||
                      command_ != referee.command;
  command_counter_ = referee.command_counter;
  if (!is_new) {
    if (!is_ball_placement()) placement_team_.reset();
    return;
  }
  command_ = referee.command;
  penalty_in_play_ = false;
  using C = RefereeCommand;
  constexpr TeamColor kB = TeamColor::kBlue;
  constexpr TeamColor kY = TeamColor::kYellow;
  switch (command_) {
    case C::kHalt:
    case C::kStop:
    case C::kGoalYellow:
    case C::kGoalBlue:
      restart_ = Restart::kNone;
      pending_ = ready_ = playing_ = false;
      break;
    case C::kNormalStart:
      if (pending_ && (restart_ == Restart::kKickoff || restart_ == Restart::kPenalty)) {
        ready_ = true;
        ball_at_ready_ = ball_at_rest();
        moved_since_.reset();
      } else {
        restart_ = Restart::kNone;
        pending_ = ready_ = false;
        playing_ = true;
      }
      break;
    case C::kForceStart:
      restart_ = Restart::kNone;
      pending_ = ready_ = false;
      playing_ = true;
      break;
    case C::kPrepareKickoffYellow: set_restart(Restart::kKickoff, kY, false); break;
    case C::kPrepareKickoffBlue: set_restart(Restart::kKickoff, kB, false); break;
    case C::kPreparePenaltyYellow: set_restart(Restart::kPenalty, kY, false); break;
    case C::kPreparePenaltyBlue: set_restart(Restart::kPenalty, kB, false); break;
    // Indirect free kicks no longer exist in the rules; treated as free kicks.
    case C::kDirectFreeYellow:
    case C::kIndirectFreeYellow: set_restart(Restart::kDirectFree, kY, true); break;
    case C::kDirectFreeBlue:
    case C::kIndirectFreeBlue: set_restart(Restart::kDirectFree, kB, true); break;
    case C::kTimeoutYellow: set_restart(Restart::kTimeout, kY, false); break;
    case C::kTimeoutBlue: set_restart(Restart::kTimeout, kB, false); break;
    case C::kBallPlacementYellow: set_restart(Restart::kBallPlacement, kY, false); break;
    case C::kBallPlacementBlue: set_restart(Restart::kBallPlacement, kB, false); break;
  }
  if (!is_ball_placement()) placement_team_.reset();
  recent_count_ = 0;  // the next restart's ball is where it rests after this command
}

void GameState::update_ball(const Vec2& ball, time::Timestamp now) {
  last_ball_ = ball;
  recent_balls_[recent_count_++ % kReadySamples] = ball;
  if (!ready_) return;
  if (!ball_at_ready_) {
    ball_at_ready_ = ball;
    return;
  }
  if ((ball - *ball_at_ready_).norm() <= kBallMovedDistance) {
    moved_since_.reset();
    return;
  }
  if (!moved_since_) moved_since_ = now;
  if (time::to_seconds(now - *moved_since_) >= kBallMovedHold) {
    penalty_in_play_ = restart_ == Restart::kPenalty;
    restart_ = Restart::kNone;
    pending_ = ready_ = false;
    playing_ = true;
  }
}

}  // namespace ssl::wm
