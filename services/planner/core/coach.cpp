#include "services/planner/core/coach.h"

#include <algorithm>
#include <array>

namespace ssl::planner {

std::string_view to_string(TeamMode mode) {
  switch (mode) {
    case TeamMode::kAttacking: return "attacking";
    case TeamMode::kDefending: return "defending";
    case TeamMode::kContesting: return "contesting";
  }
  return "?";
}

std::string_view to_string(Style style) {
  switch (style) {
    case Style::kBuildUpAttack: return "build_up_attack";
    case Style::kHighPressureAttack: return "high_pressure_attack";
    case Style::kHoldPossession: return "hold_possession";
    case Style::kClearance: return "clearance";
    case Style::kScrambleDefence: return "scramble_defence";
    case Style::kPressBall: return "press_ball";
    case Style::kContestBall: return "contest_ball";
  }
  return "?";
}

std::string_view to_string(Role role) {
  switch (role) {
    case Role::kGoalie: return "goalkeeper";
    case Role::kAttacker: return "attacker";
    case Role::kReceiver: return "receiver";
    case Role::kWinger: return "winger";
    case Role::kMidfieldSupport: return "midfield_support";
    case Role::kDefender: return "defender";
    case Role::kMarker: return "marker";
    case Role::kPresser: return "presser";
  }
  return "?";
}

TeamMode mode_of(Style style) {
  switch (style) {
    case Style::kBuildUpAttack:
    case Style::kHighPressureAttack:
    case Style::kHoldPossession:
    case Style::kClearance:
      return TeamMode::kAttacking;
    case Style::kScrambleDefence:
    case Style::kPressBall:
      return TeamMode::kDefending;
    case Style::kContestBall:
      break;
  }
  return TeamMode::kContesting;
}

Style style_for(const GameReading& r) {
  switch (r.possession) {
    case wm::Possession::kFriendly:
      if (r.ball_third == Third::kOurs && r.advantage < 0) return Style::kClearance;
      if (r.advantage < 0) return Style::kHoldPossession;
      if (r.ball_third == Third::kTheirs) return Style::kHighPressureAttack;
      return Style::kBuildUpAttack;
    case wm::Possession::kEnemy:
      return r.ball_third == Third::kOurs ? Style::kScrambleDefence : Style::kPressBall;
    case wm::Possession::kNone:
    case wm::Possession::kContested:
      break;
  }
  // A loose ball in our third with them coming (momentum towards our goal) is danger first.
  if (r.ball_third == Third::kOurs && r.momentum < 0) return Style::kScrambleDefence;
  return Style::kContestBall;
}

std::span<const Role> roles_of(Style style) {
  using R = Role;
  static constexpr std::array kBuildUp{R::kAttacker, R::kWinger, R::kMidfieldSupport, R::kDefender,
                                       R::kWinger,   R::kDefender, R::kMidfieldSupport, R::kMarker,
                                       R::kMidfieldSupport, R::kMarker};
  static constexpr std::array kHighPressure{R::kAttacker, R::kWinger, R::kWinger, R::kDefender,
                                            R::kMidfieldSupport, R::kDefender, R::kMidfieldSupport,
                                            R::kMarker, R::kWinger, R::kMarker};
  static constexpr std::array kHold{R::kAttacker, R::kMidfieldSupport, R::kMidfieldSupport, R::kDefender,
                                    R::kWinger,   R::kDefender,        R::kMarker,          R::kMidfieldSupport,
                                    R::kMarker,   R::kWinger};
  static constexpr std::array kClear{R::kAttacker, R::kDefender, R::kMidfieldSupport, R::kDefender,
                                     R::kWinger,   R::kMarker,   R::kMarker,          R::kMidfieldSupport,
                                     R::kMarker,   R::kWinger};
  static constexpr std::array kScramble{R::kPresser, R::kDefender, R::kDefender, R::kMarker, R::kWinger,
                                        R::kMarker,  R::kMarker,   R::kMarker,   R::kMarker, R::kMarker};
  // Pressing high keeps a winger up the field: the counter-attack's pass option once the ball is won.
  static constexpr std::array kPress{R::kPresser, R::kWinger, R::kDefender, R::kMidfieldSupport, R::kWinger,
                                     R::kDefender, R::kMarker,  R::kMarker,  R::kMarker, R::kMarker};
  static constexpr std::array kContest{R::kAttacker, R::kWinger, R::kDefender, R::kMidfieldSupport,
                                       R::kWinger,   R::kDefender, R::kMarker, R::kMarker,
                                       R::kMidfieldSupport, R::kMarker};
  switch (style) {
    case Style::kBuildUpAttack: return kBuildUp;
    case Style::kHighPressureAttack: return kHighPressure;
    case Style::kHoldPossession: return kHold;
    case Style::kClearance: return kClear;
    case Style::kScrambleDefence: return kScramble;
    case Style::kPressBall: return kPress;
    case Style::kContestBall: break;
  }
  return kContest;
}

GameReading Coach::read(const Situation& s) {
  GameReading r;
  r.possession = s.possession;
  const double third = s.field.length() / 6;
  r.ball_third = s.ball.x() < -third ? Third::kOurs : s.ball.x() > third ? Third::kTheirs : Third::kMiddle;
  // Momentum: the ball's velocity towards their goal, smoothed over momentum_time.
  const double dt = last_read_ ? std::clamp(s.now - *last_read_, 0.0, 0.1) : 0.0;
  last_read_ = s.now;
  const double drift = std::clamp(s.ball_velocity.x() / params_.momentum_speed, -1.0, 1.0);
  momentum_ += (drift - momentum_) * std::min(1.0, dt / params_.momentum_time);
  r.momentum = momentum_;
  for (const wm::RobotState& robot : s.robots) {
    if ((robot.position - s.ball).norm() <= params_.advantage_radius) ++r.advantage;
  }
  for (const wm::RobotState& robot : s.enemies) {
    if ((robot.position - s.ball).norm() <= params_.advantage_radius) --r.advantage;
  }
  return r;
}

Style Coach::decide(const GameReading& reading, double now) {
  const Style wanted = style_for(reading);
  if (!style_ || wanted == Style::kScrambleDefence) {
    style_ = wanted;
    candidate_.reset();
    return *style_;
  }
  if (wanted == *style_) {
    candidate_.reset();
    return *style_;
  }
  if (candidate_ != wanted) {
    candidate_ = wanted;
    candidate_since_ = now;
  }
  if (now - candidate_since_ >= params_.switch_delay - 1e-9) {
    style_ = wanted;
    candidate_.reset();
  }
  return *style_;
}

}  // namespace ssl::planner
