// The built-in referee's fouls (see builtin_referee.h, "fouls" and "cards"): robot speeds, the rules judged
// while running (crash, kick too fast, double touch, dribbling, keeper holding the ball, too many robots),
// in STOP and before a restart's ball is in play (too fast in STOP, too close to the opponent's defense
// area, placement interference), the boundary crossing after a ball left the field, and the cards.
#include <algorithm>
#include <cmath>

#include "libs/domain/keep_out.h"
#include "libs/geometry/distance.h"
#include "services/referee_gateway/builtin/builtin_referee.h"
#include "services/referee_gateway/builtin/commands.h"

namespace ssl::referee {
namespace {

using builtin::ball_placement;
using builtin::direct_free;
using builtin::to_team;
using geom::Vec2;
using time::duration_from_seconds;
using time::Timestamp;

}  // namespace

// -------------------------------------------------------------------------------------------------------
// Robot speeds and bookkeeping

void BuiltinReferee::estimate_robot_velocities(CleanObservation& seen, Timestamp now) {
  for (ObservedRobot& robot : seen.robots) {
    const auto key = std::pair{robot.team, robot.id};
    auto reference = robot_speed_reference_.find(key);
    if (robot.velocity && std::isfinite(robot.velocity->x()) && std::isfinite(robot.velocity->y())) {
      robot_velocity_[key] = *robot.velocity;
    } else if (reference != robot_speed_reference_.end() && now > reference->second.second) {
      // Over at least kSpeedBaseline, as for the ball: a few millimetres of noise must not read as speed.
      const double baseline = time::to_seconds(now - reference->second.second);
      if (baseline >= kSpeedBaseline || !robot_velocity_.contains(key)) {
        robot_velocity_[key] = (robot.position - reference->second.first) / baseline;
      }
    } else {
      robot_velocity_[key] = Vec2::Zero();
    }
    robot.velocity = robot_velocity_[key];
    if (reference == robot_speed_reference_.end() ||
        now - reference->second.second >= duration_from_seconds(kSpeedBaseline)) {
      robot_speed_reference_[key] = {robot.position, now};
    }
  }
}

bool BuiltinReferee::may_raise_again(const std::string& key, Timestamp now) {
  auto it = last_raised_.find(key);
  if (it != last_raised_.end() && now - it->second < duration_from_seconds(kFoulRepeat)) return false;
  last_raised_[key] = now;
  return true;
}

void BuiltinReferee::book(TeamColor team, Timestamp now) {
  const CardRule& rule = profile_.rules.cards;
  TeamInfo& info = team_info(team);
  if (!rule.enabled || rule.fouls_per_card == 0 || info.foul_counter % rule.fouls_per_card != 0) return;
  raise({.type = GameEventType::kMultipleFouls, .by_team = to_team(team)}, now, /*is_foul=*/false);
  if (info.yellow_card_times_left.size() >= 2) {
    ++info.red_cards;  // a third concurrent yellow card: the robot stays off for the rest of the match
  } else {
    ++info.yellow_cards;
    info.yellow_card_times_left.push_back(duration_from_seconds(rule.yellow_card_duration));
    std::sort(info.yellow_card_times_left.begin(), info.yellow_card_times_left.end());
  }
  if (info.max_allowed_bots > 0) --info.max_allowed_bots;
}

void BuiltinReferee::run_card_clocks(time::Duration elapsed) {
  for (TeamInfo* info : {&state_.yellow, &state_.blue}) {
    auto& times = info->yellow_card_times_left;
    for (time::Duration& left : times) left -= elapsed;
    const auto expired = std::remove_if(times.begin(), times.end(),
                                        [](const time::Duration& left) { return left <= time::Duration::zero(); });
    info->max_allowed_bots += static_cast<std::uint32_t>(times.end() - expired);
    times.erase(expired, times.end());
  }
}

Vec2 BuiltinReferee::legal_free_kick_spot(const Vec2& p) const {
  const double half_length = 0.5 * field_.field_length;
  const double half_width = 0.5 * field_.field_width;
  const double inset = profile_.rules.out_of_bounds.line_distance;
  Vec2 spot(std::clamp(p.x(), -(half_length - inset), half_length - inset),
            std::clamp(p.y(), -(half_width - inset), half_width - inset));
  const double clear_x = half_length - field_.penalty_area_depth - kRestartDefenseAreaDistance;
  const double clear_y = 0.5 * field_.penalty_area_width + kRestartDefenseAreaDistance;
  if (std::abs(spot.x()) > clear_x && std::abs(spot.y()) < clear_y) {
    // In front of a goal: out of the area's reach along x or along y, whichever is nearer.
    const Vec2 along_x((spot.x() < 0 ? -1 : 1) * clear_x, spot.y());
    const Vec2 along_y(spot.x(), (spot.y() < 0 ? -1 : 1) * clear_y);
    spot = (along_x - spot).norm() <= (along_y - spot).norm() ? along_x : along_y;
  }
  return spot;
}

BuiltinReferee::Transition BuiltinReferee::free_kick_after_foul(TeamColor offender, const std::optional<Vec2>& ball,
                                                                const std::string& reason) const {
  const TeamColor kicking = opponent(offender);
  const std::string text = reason + ": free kick " + std::string(to_string(kicking));
  if (ball) {
    const Vec2 spot = legal_free_kick_spot(*ball);
    if ((spot - *ball).norm() > profile_.game.placement_tolerance && profile_.game.ball_placement &&
        team_info(kicking).can_place_ball) {
      return {.command = ball_placement(kicking),
              .next_command = direct_free(kicking),
              .designated_position = spot,
              .placement_attempt = 1,
              .reason = text};
    }
  }
  return {.command = Command::kStop, .next_command = direct_free(kicking), .next_is_automatic = true, .reason = text};
}

// -------------------------------------------------------------------------------------------------------
// While running

std::optional<BuiltinReferee::Transition> BuiltinReferee::judge_running_fouls(const CleanObservation& seen,
                                                                              Timestamp now) {
  judge_crashes(seen, now);
  judge_ball_speed(seen, now);
  if (auto decision = judge_double_touch(seen, now)) return decision;
  if (auto decision = judge_dribbling(seen, now)) return decision;
  if (auto decision = judge_keeper_held_ball(seen, now)) return decision;
  return judge_robot_count(seen, now);
}

void BuiltinReferee::judge_crashes(const CleanObservation& seen, Timestamp now) {
  const CrashRule& rule = profile_.rules.crash;
  if (!rule.enabled) return;
  const double contact = 2 * field_.max_robot_radius + kCrashContactMargin;
  for (const ObservedRobot& yellow : seen.robots) {
    if (yellow.team != TeamColor::kYellow) continue;
    for (const ObservedRobot& blue : seen.robots) {
      if (blue.team != TeamColor::kBlue) continue;
      const Vec2 between = blue.position - yellow.position;
      const double distance = between.norm();
      if (distance > contact || distance < 1e-9) continue;
      const Vec2 n = between / distance;  // yellow -> blue
      const double yellow_speed = yellow.velocity->dot(n);  // towards the other robot
      const double blue_speed = -blue.velocity->dot(n);
      const double crash_speed = yellow_speed + blue_speed;
      if (crash_speed <= rule.speed) continue;
      const std::string key = "crash:" + std::to_string(yellow.id) + ":" + std::to_string(blue.id);
      if (!may_raise_again(key, now)) continue;
      const Vec2 location = 0.5 * (yellow.position + blue.position);
      const double difference = std::abs(yellow_speed - blue_speed);
      if (difference < rule.drawn_speed_difference) {
        raise({.type = GameEventType::kBotCrashDrawn,
               .by_bot = yellow.id,
               .other_bot = blue.id,
               .location = location,
               .value = crash_speed},
              now, /*is_foul=*/false);
        for (const TeamColor team : {TeamColor::kYellow, TeamColor::kBlue}) {  // both foul
          ++team_info(team).foul_counter;
          book(team, now);
        }
        continue;
      }
      const bool yellow_faster = yellow_speed > blue_speed;
      const ObservedRobot& violator = yellow_faster ? yellow : blue;
      const ObservedRobot& victim = yellow_faster ? blue : yellow;
      raise({.type = GameEventType::kBotCrashUnique,
             .by_team = to_team(violator.team),
             .by_bot = violator.id,
             .other_bot = victim.id,
             .location = location,
             .value = crash_speed},
            now, /*is_foul=*/true);
    }
  }
}

void BuiltinReferee::judge_ball_speed(const CleanObservation& seen, Timestamp now) {
  const BallSpeedRule& rule = profile_.rules.ball_speed;
  if (!rule.enabled || !seen.ball_speed) return;
  if (*seen.ball_speed <= rule.max_speed) {
    ball_too_fast_ = false;
    return;
  }
  if (ball_too_fast_ || !last_touch_) return;
  ball_too_fast_ = true;  // one foul per kick
  raise({.type = GameEventType::kBotKickedBallTooFast,
         .by_team = to_team(last_touch_->team),
         .by_bot = last_touch_->id,
         .location = seen.ball,
         .value = *seen.ball_speed},
        now, /*is_foul=*/true);
}

std::optional<BuiltinReferee::Transition> BuiltinReferee::judge_double_touch(const CleanObservation& seen,
                                                                             Timestamp now) {
  const DoubleTouchRule& rule = profile_.rules.double_touch;
  if (!rule.enabled || !kicker_watch_ || !seen.ball) return std::nullopt;
  const std::optional<Touch>& touching = seen.touch;
  if (touching && (touching->team != kicker_watch_->kicker.team || touching->id != kicker_watch_->kicker.id)) {
    kicker_watch_.reset();  // another robot touched it: the kicker may play again
    return std::nullopt;
  }
  // The kicker plays its ball again only by reaching it. A deflection read off the velocity is no touch of the
  // kicker: just after a kick it stands behind the ball, and two noisy velocity estimates (from vision, 10 ms
  // apart) drew the ball's path back through it; a lockstep match under realistic vision called a double touch
  // on a kicker 0.23 m behind its free kick running away at 2.5 m/s.
  const bool kicker_touches = touching.has_value() && seen.touch_in_reach;
  if (!kicker_touches) {
    kicker_watch_->released = true;
    return std::nullopt;
  }
  const bool travelled = (*seen.ball - kicker_watch_->kick_point).norm() > rule.distance;
  if (!kicker_watch_->released && !travelled) return std::nullopt;
  const Touch kicker = kicker_watch_->kicker;
  kicker_watch_.reset();
  raise({.type = GameEventType::kAttackerDoubleTouchedBall,
         .by_team = to_team(kicker.team),
         .by_bot = kicker.id,
         .location = seen.ball},
        now, /*is_foul=*/true);
  return free_kick_after_foul(kicker.team, seen.ball, std::string(to_string(kicker.team)) + " double touch");
}

std::optional<BuiltinReferee::Transition> BuiltinReferee::judge_dribbling(const CleanObservation& seen,
                                                                          Timestamp now) {
  const DribblingRule& rule = profile_.rules.dribbling;
  if (!rule.enabled || !seen.ball) return std::nullopt;
  const std::optional<Touch> holder = toucher(seen, kDribblingReachMargin);
  if (!holder) {
    dribble_.reset();
    return std::nullopt;
  }
  if (!dribble_ || dribble_->robot.team != holder->team || dribble_->robot.id != holder->id) {
    dribble_ = Dribble{*holder, *seen.ball};
    return std::nullopt;
  }
  if ((*seen.ball - dribble_->start).norm() <= rule.max_distance) return std::nullopt;
  const Dribble dribble = *dribble_;
  dribble_.reset();
  raise({.type = GameEventType::kBotDribbledBallTooFar,
         .by_team = to_team(dribble.robot.team),
         .by_bot = dribble.robot.id,
         .location = dribble.start,
         .secondary_location = seen.ball},
        now, /*is_foul=*/true);
  return free_kick_after_foul(dribble.robot.team, dribble.start,
                              std::string(to_string(dribble.robot.team)) + " dribbled too far");
}

std::optional<BuiltinReferee::Transition> BuiltinReferee::judge_keeper_held_ball(const CleanObservation& seen,
                                                                                 Timestamp now) {
  const KeeperHeldBallRule& rule = profile_.rules.keeper_held_ball;
  if (!rule.enabled || !seen.ball) return std::nullopt;
  std::optional<TeamColor> defending;
  for (const TeamColor team : {TeamColor::kYellow, TeamColor::kBlue}) {
    if (defense_area_of(team).contains(*seen.ball)) defending = team;
  }
  if (!defending) {
    ball_in_own_area_since_.reset();
    return std::nullopt;
  }
  if (!ball_in_own_area_since_ || ball_in_own_area_since_->first != *defending) {
    ball_in_own_area_since_ = {*defending, now};
  }
  const double held = time::to_seconds(now - ball_in_own_area_since_->second);
  if (held <= rule.time.of(division_)) return std::nullopt;
  ball_in_own_area_since_.reset();
  raise({.type = GameEventType::kKeeperHeldBall, .by_team = to_team(*defending), .location = seen.ball, .value = held},
        now, /*is_foul=*/true);
  return free_kick_after_foul(*defending, seen.ball, std::string(to_string(*defending)) + " held the ball");
}

std::optional<BuiltinReferee::Transition> BuiltinReferee::judge_robot_count(const CleanObservation& seen,
                                                                            Timestamp now) {
  const RobotCountRule& rule = profile_.rules.robot_count;
  if (!rule.enabled) return std::nullopt;
  for (const TeamColor team : {TeamColor::kYellow, TeamColor::kBlue}) {
    const auto on_field = static_cast<std::uint32_t>(std::count_if(seen.robots.begin(), seen.robots.end(), [&](const ObservedRobot& r) {
      return r.team == team && counts_towards_robot_limit(field_, r.position);
    }));
    const std::uint32_t allowed = team_info(team).max_allowed_bots;
    std::optional<Timestamp>& since = too_many_since_[team == TeamColor::kYellow ? 0 : 1];
    if (on_field <= allowed) {
      since.reset();
      continue;
    }
    if (!since) since = now;
    if (now - *since <= duration_from_seconds(rule.grace)) continue;
    since = now;  // raised again only after another grace
    raise({.type = GameEventType::kTooManyRobots,
           .by_team = to_team(team),
           .secondary_location = seen.ball,
           .text = std::to_string(on_field) + " on field, " + std::to_string(allowed) + " allowed"},
          now, /*is_foul=*/true);
    return free_kick_after_foul(team, seen.ball ? seen.ball : last_ball_,
                                std::string(to_string(team)) + " has too many robots");
  }
  return std::nullopt;
}

// -------------------------------------------------------------------------------------------------------
// Out of play

void BuiltinReferee::judge_boundary_crossing(const CleanObservation& seen, Timestamp now) {
  const BoundaryCrossingRule& rule = profile_.rules.boundary_crossing;
  if (!rule.enabled || !ball_left_field_ || boundary_crossing_raised_ || !seen.ball) return;
  if (now - ball_left_field_->first > duration_from_seconds(kBoundaryCrossingWindow)) return;
  const bool beyond_walls =
      std::abs(seen.ball->x()) > field_.wall_half_length() || std::abs(seen.ball->y()) > field_.wall_half_width();
  if (!beyond_walls) return;
  boundary_crossing_raised_ = true;
  const std::optional<Touch>& kicker = ball_left_field_->second;
  GameEvent event{.type = GameEventType::kBoundaryCrossing, .location = seen.ball};
  if (kicker) event.by_team = to_team(kicker->team);
  raise(std::move(event), now, /*is_foul=*/kicker.has_value());
}

void BuiltinReferee::judge_stop_speed(const CleanObservation& seen, Timestamp now) {
  const StopSpeedRule& rule = profile_.rules.stop_speed;
  if (!rule.enabled || now - command_since_ < duration_from_seconds(rule.grace)) return;
  for (const ObservedRobot& robot : seen.robots) {
    const double speed = robot.velocity->norm();
    if (speed <= rule.max_speed || !too_fast_in_stop_.emplace(robot.team, robot.id).second) continue;
    raise({.type = GameEventType::kBotTooFastInStop,
           .by_team = to_team(robot.team),
           .by_bot = robot.id,
           .location = robot.position,
           .value = speed},
          now, /*is_foul=*/true);
  }
}

void BuiltinReferee::judge_defense_area_distance(const CleanObservation& seen, Timestamp now) {
  const AttackerDefenseAreaDistanceRule& rule = profile_.rules.attacker_defense_area_distance;
  if (!rule.enabled) return;
  const time::Duration persistence = duration_from_seconds(rule.violation_persistence);
  for (const ObservedRobot& robot : seen.robots) {
    const double distance = geom::distance(robot.position, defense_area_of(opponent(robot.team))) -
                            field_.max_robot_radius;
    const auto key = std::pair{robot.team, robot.id};
    if (distance >= rule.distance) {
      area_distance_since_.erase(key);
      continue;
    }
    auto& [since, reported] = area_distance_since_.try_emplace(key, now, false).first->second;
    if (reported || now - since < persistence) continue;
    reported = true;
    raise({.type = GameEventType::kAttackerTooCloseToDefenseArea,
           .by_team = to_team(robot.team),
           .by_bot = robot.id,
           .location = robot.position,
           .secondary_location = seen.ball,
           .value = std::max(distance, 0.0)},
          now, /*is_foul=*/true);
  }
}

void BuiltinReferee::judge_placement_interference(const CleanObservation& seen, Timestamp now) {
  const PlacementInterferenceRule& rule = profile_.rules.placement_interference;
  if (!rule.enabled || !seen.ball || !state_.designated_position || !executing_team_) return;
  const time::Duration persistence = duration_from_seconds(rule.violation_persistence);
  for (const ObservedRobot& robot : seen.robots) {
    if (robot.team == *executing_team_) continue;
    const geom::Stadium zone =
        placement_keep_out(*seen.ball, *state_.designated_position, field_.max_robot_radius, rule.radius);
    const auto key = std::pair{robot.team, robot.id};
    if (geom::signed_distance(robot.position, zone) >= 0) {
      interference_since_.erase(key);
      continue;
    }
    auto& [since, reported] = interference_since_.try_emplace(key, now, false).first->second;
    if (reported || now - since < persistence) continue;
    reported = true;
    placement_extra_time_ += rule.extra_time;
    raise({.type = GameEventType::kBotInterferedPlacement,
           .by_team = to_team(robot.team),
           .by_bot = robot.id,
           .location = robot.position},
          now, /*is_foul=*/true);
  }
}

}  // namespace ssl::referee
