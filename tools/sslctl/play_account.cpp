#include "tools/sslctl/play_account.h"

#include <cmath>

namespace ssl::sslctl {

void PlayAccount::set_field(double length, double goal_width) {
  field_length_ = length;
  goal_width_ = goal_width;
}

void PlayAccount::on_referee(bool in_play, std::optional<bool> blue_on_positive_half,
                             std::optional<Restart> restart) {
  if (!in_play) {
    if (open_pass_) ++team_of(open_pass_->team).passes_out;  // play stopped before anybody took the pass
    open_pass_.reset();
    open_restart_.reset();  // or the restart: not kept (unless on_goal came first)
    restart_move_.reset();
    possession_.reset();
    last_toucher_id_.reset();
    last_toucher_team_.reset();
  }
  if (in_play && restart && (!in_play_ || restart != restart_)) open_restart_ = OpenRestart{.restart = *restart};
  restart_ = restart;
  if (in_play && !in_play_) compare_speed_ = false;
  in_play_ = in_play;
  if (blue_on_positive_half) blue_on_positive_half_ = blue_on_positive_half;
}

void PlayAccount::on_frame(const geom::Vec2& ball, std::span<const Robot> robots, time::Timestamp t) {
  if (last_frame_ && t <= *last_frame_) return;
  const double dt = last_frame_ ? time::to_seconds(t - *last_frame_) : 0;
  const geom::Vec2 velocity = dt > 0 ? geom::Vec2((ball - last_ball_) / dt) : geom::Vec2::Zero();
  const double speed = velocity.norm();
  if (in_play_ && possession_ && dt > 0) team_of(*possession_).possession += dt;

  const Robot* nearest = nullptr;
  double nearest_distance = 0;
  for (const Robot& robot : robots) {
    const double d = (robot.position - ball).norm();
    if (!nearest || d < nearest_distance) {
      nearest = &robot;
      nearest_distance = d;
    }
  }
  if (in_play_) {
    const bool kicked =
        compare_speed_ && speed >= kKickMinSpeed && speed < kMaxBallSpeed && speed - last_speed_ >= kKickSpeedGain;
    if (kicked && nearest && nearest_distance <= kKickReach && nearest->intent != Intent::kNoKick) {
      on_kick(*nearest, ball, velocity);
    } else if (nearest && nearest_distance <= kTouchDistance) {
      // A touch settles an open pass (not the kicker still at the ball it just kicked).
      const bool kicker_still = open_pass_ && nearest->team == open_pass_->team && nearest->id == open_pass_->kicker &&
                                last_toucher_id_ == nearest->id && last_toucher_team_ == nearest->team;
      if (!(last_toucher_id_ == nearest->id && last_toucher_team_ == nearest->team)) settle_restart(*nearest);
      if (open_pass_ && !kicker_still) {
        if (nearest->team == open_pass_->team && nearest->id != open_pass_->kicker) {
          ++team_of(open_pass_->team).passes_completed;
        } else if (nearest->team != open_pass_->team) {
          ++team_of(open_pass_->team).passes_intercepted;
        }
        open_pass_.reset();
      }
      possession_ = nearest->team;
      last_toucher_id_ = nearest->id;
      last_toucher_team_ = nearest->team;
    } else if (last_toucher_id_ && nearest_distance > kTouchDistance) {
      // The ball left its last toucher: a later touch by the same robot is a new touch.
      last_toucher_id_.reset();
      last_toucher_team_.reset();
    }
  }
  compare_speed_ = in_play_ && dt > 0;
  last_frame_ = t;
  last_ball_ = ball;
  last_speed_ = speed;
}

RestartTally& PlayAccount::tally_of(const Restart& restart) {
  TeamPlay& play = team_of(restart.team);
  switch (restart.kind) {
    case RestartKind::kKickoff: return play.kickoffs;
    case RestartKind::kPenalty: return play.penalties;
    case RestartKind::kFreeKick: break;
  }
  return play.free_kicks;
}

void PlayAccount::on_goal(TeamColor team) {
  if (open_restart_ && open_restart_->taker && open_restart_->restart.team == team) {
    ++tally_of(open_restart_->restart).kept;
  }
  if (restart_move_ && restart_move_->team == team) ++tally_of(*restart_move_).goals;
  open_restart_.reset();
  restart_move_.reset();
}

void PlayAccount::settle_restart(const Robot& robot) {
  if (restart_move_ && restart_move_->team != robot.team) restart_move_.reset();  // an opponent's touch ends it
  if (!open_restart_) return;
  const Restart restart = open_restart_->restart;
  if (!open_restart_->taker) {
    // The first touch: the restart's taker, or the other team got there first (nothing taken).
    if (robot.team == restart.team) {
      open_restart_->taker = robot.id;
      restart_move_ = restart;
      ++tally_of(restart).taken;
    } else {
      open_restart_.reset();
    }
    return;
  }
  if (robot.team == restart.team && robot.id == *open_restart_->taker) return;  // the taker again
  if (robot.team == restart.team) ++tally_of(restart).kept;
  open_restart_.reset();
}

void PlayAccount::on_kick(const Robot& kicker, const geom::Vec2& ball, const geom::Vec2& velocity) {
  if (!(last_toucher_id_ == kicker.id && last_toucher_team_ == kicker.team)) settle_restart(kicker);
  TeamPlay& play = team_of(kicker.team);
  ++play.kicks;
  possession_ = kicker.team;
  last_toucher_id_ = kicker.id;
  last_toucher_team_ = kicker.team;
  // A kick settles the pass before it: a teammate's one-touch kick took it.
  if (open_pass_ && kicker.team == open_pass_->team && kicker.id != open_pass_->kicker) {
    ++team_of(open_pass_->team).passes_completed;
  } else if (open_pass_ && kicker.team != open_pass_->team) {
    ++team_of(open_pass_->team).passes_intercepted;
  }
  open_pass_.reset();
  bool on_target = false;
  const bool aimed = is_shot(kicker.team, ball, velocity, on_target);
  if (aimed && kicker.intent != Intent::kPass && kicker.intent != Intent::kClear) {
    ++play.shots;
    if (on_target) ++play.shots_on_target;
    return;
  }
  // A clearance, or a shooter's kick that does not go at the goal (a deflection): no pass.
  if (kicker.intent == Intent::kClear || kicker.intent == Intent::kShot) return;
  ++play.passes_tried;
  open_pass_ = OpenPass{kicker.team, kicker.id};
}

bool PlayAccount::is_shot(TeamColor team, const geom::Vec2& ball, const geom::Vec2& velocity, bool& on_target) const {
  on_target = false;
  if (!field_length_ || !blue_on_positive_half_) return false;
  // The goal this team attacks: the other team's, on the half the other team defends.
  const bool blue_positive = *blue_on_positive_half_;
  const bool attacks_positive = team == TeamColor::kBlue ? !blue_positive : blue_positive;
  const double goal_x = (attacks_positive ? 1.0 : -1.0) * *field_length_ / 2;
  const double towards = (goal_x - ball.x()) * velocity.x();
  if (towards <= 0 || std::abs(velocity.x()) < 1e-6) return false;
  const double y = ball.y() + velocity.y() * (goal_x - ball.x()) / velocity.x();
  on_target = std::abs(y) <= goal_width_ / 2 - kBallRadius;
  return std::abs(y) <= goal_width_ / 2 + kShotWidthMargin;
}

}  // namespace ssl::sslctl
