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
    open_shot_.reset();     // wide, or stopped for a foul
    open_restart_.reset();  // or the restart: not kept (unless on_goal came first)
    restart_move_.reset();
    possession_.reset();
    last_toucher_id_.reset();
    last_toucher_team_.reset();
  }
  if (in_play && restart && (!in_play_ || restart != restart_)) open_restart_ = OpenRestart{.restart = *restart};
  restart_ = restart;
  if (in_play && !in_play_) ball_tracks_.clear();  // the first sample in play is not compared
  in_play_ = in_play;
  if (blue_on_positive_half) blue_on_positive_half_ = blue_on_positive_half;
}

void PlayAccount::on_frame(const geom::Vec2& ball, std::span<const Robot> robots, time::Timestamp t,
                           std::optional<Camera> camera) {
  if (last_frame_ && t <= *last_frame_) return;
  const double dt = last_frame_ ? time::to_seconds(t - *last_frame_) : 0;
  if (in_play_ && possession_ && dt > 0) team_of(*possession_).possession += dt;
  // The ball's velocity from the same camera's last sample, by capture times: cameras see the ball a few cm
  // apart and their packets arrive in bursts, so a sample against another camera's is no speed at all.
  const std::uint32_t track_key = camera ? camera->id : kNoCamera;
  const time::Timestamp sampled = camera ? camera->capture : t;
  BallTrack& track = ball_tracks_[track_key];
  const double track_dt = track.at ? time::to_seconds(sampled - *track.at) : 0;
  const geom::Vec2 velocity = track_dt > 0 ? geom::Vec2((ball - track.ball) / track_dt) : geom::Vec2::Zero();
  const double speed = velocity.norm();
  const bool compare_speed = in_play_ && track_dt > 0 && track.compared;

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
        compare_speed && speed >= kKickMinSpeed && speed < kMaxBallSpeed && speed - track.speed >= kKickSpeedGain;
    // Another camera seeing the same kick a moment later (their views overlap) is no second kick.
    const bool seen_already = last_kick_ && nearest && last_kick_->team == nearest->team &&
                              last_kick_->kicker == nearest->id && time::to_seconds(t - last_kick_->at) < kSameKick;
    if (kicked && nearest && nearest_distance <= kKickReach && nearest->intent != Intent::kNoKick && !seen_already) {
      last_kick_ = LastKick{nearest->team, nearest->id, t};
      on_kick(*nearest, ball, velocity);
    } else if (nearest && nearest_distance <= kTouchDistance) {
      // A touch settles an open pass (not the kicker still at the ball it just kicked).
      const bool kicker_still = open_pass_ && nearest->team == open_pass_->team && nearest->id == open_pass_->kicker &&
                                last_toucher_id_ == nearest->id && last_toucher_team_ == nearest->team;
      if (!(last_toucher_id_ == nearest->id && last_toucher_team_ == nearest->team)) settle_restart(*nearest);
      settle_shot(*nearest);
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
  last_frame_ = t;
  if (!track.at || sampled > *track.at) {
    track.compared = in_play_ && track_dt > 0;
    track.at = sampled;
    track.ball = ball;
    track.speed = speed;
  }
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

void PlayAccount::set_keepers(std::uint32_t blue, std::uint32_t yellow) {
  blue_keeper_ = blue;
  yellow_keeper_ = yellow;
}

void PlayAccount::settle_shot(const Robot& robot) {
  if (!open_shot_ || (robot.team == open_shot_->team && robot.id == open_shot_->kicker)) return;
  if (robot.team != open_shot_->team) {
    const std::optional<std::uint32_t> keeper = robot.team == TeamColor::kBlue ? blue_keeper_ : yellow_keeper_;
    TeamPlay& play = team_of(open_shot_->team);
    ++(keeper == robot.id ? play.shots_saved : play.shots_blocked);
  }
  open_shot_.reset();
}

void PlayAccount::on_goal(TeamColor team) {
  if (open_shot_ && open_shot_->team == team) ++team_of(team).shots_scored;
  open_shot_.reset();
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
  settle_shot(kicker);
  open_shot_.reset();  // the kicker's own shot kicked again
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
    play.shot_distance += (geom::Vec2(attacked_goal_x(kicker.team), 0) - ball).norm();
    open_shot_ = OpenKick{kicker.team, kicker.id};
    return;
  }
  // A clearance, or a shooter's kick that does not go at the goal (a deflection): no pass.
  if (kicker.intent == Intent::kClear || kicker.intent == Intent::kShot) return;
  ++play.passes_tried;
  open_pass_ = OpenKick{kicker.team, kicker.id};
}

double PlayAccount::attacked_goal_x(TeamColor team) const {
  // The goal this team attacks: the other team's, on the half the other team defends.
  const bool attacks_positive = *blue_on_positive_half_ == (team == TeamColor::kYellow);
  return (attacks_positive ? 1.0 : -1.0) * *field_length_ / 2;
}

bool PlayAccount::is_shot(TeamColor team, const geom::Vec2& ball, const geom::Vec2& velocity, bool& on_target) const {
  on_target = false;
  if (!field_length_ || !blue_on_positive_half_) return false;
  const double goal_x = attacked_goal_x(team);
  const double towards = (goal_x - ball.x()) * velocity.x();
  if (towards <= 0 || std::abs(velocity.x()) < 1e-6) return false;
  const double y = ball.y() + velocity.y() * (goal_x - ball.x()) / velocity.x();
  on_target = std::abs(y) <= goal_width_ / 2 - kBallRadius;
  return std::abs(y) <= goal_width_ / 2 + kShotWidthMargin;
}

}  // namespace ssl::sslctl
