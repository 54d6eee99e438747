// The built-in referee: the state machine (apply, enter_stage), the input cleaning and the rules. See the
// header for the contract. Layout: helpers, construction and inputs, the state machine, the rules.
#include "services/referee_gateway/builtin/builtin_referee.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "libs/domain/keep_out.h"
#include "libs/geometry/distance.h"
#include "services/referee_gateway/builtin/commands.h"

namespace ssl::referee {
namespace {

using builtin::ball_placement;
using builtin::direct_free;
using builtin::kickoff;
using builtin::penalty;
using builtin::to_team;
using geom::Vec2;
using time::duration_from_seconds;
using time::Timestamp;

/// The robot with the smallest `distance_of(position)` no greater than `reach`; nullptr when none is.
template <typename DistanceOf>
const ObservedRobot* nearest_within(const std::vector<ObservedRobot>& robots, double reach, DistanceOf distance_of) {
  const ObservedRobot* nearest = nullptr;
  for (const ObservedRobot& robot : robots) {
    const double distance = distance_of(robot.position);
    if (distance <= reach) {
      reach = distance;
      nearest = &robot;
    }
  }
  return nearest;
}

bool is_direct_free(Command command) {
  return command == Command::kDirectFreeYellow || command == Command::kDirectFreeBlue;
}

/// The stage the match goes to when `stage` ends; `drawn`: the score is level.
std::optional<Stage> stage_after(Stage stage, bool extra_time, bool drawn) {
  switch (stage) {
    case Stage::kNormalFirstHalfPre: return Stage::kNormalFirstHalf;
    case Stage::kNormalFirstHalf: return Stage::kNormalHalfTime;
    case Stage::kNormalHalfTime: return Stage::kNormalSecondHalfPre;
    case Stage::kNormalSecondHalfPre: return Stage::kNormalSecondHalf;
    case Stage::kNormalSecondHalf: return extra_time && drawn ? Stage::kExtraTimeBreak : Stage::kPostGame;
    case Stage::kExtraTimeBreak: return Stage::kExtraFirstHalfPre;
    case Stage::kExtraFirstHalfPre: return Stage::kExtraFirstHalf;
    case Stage::kExtraFirstHalf: return Stage::kExtraHalfTime;
    case Stage::kExtraHalfTime: return Stage::kExtraSecondHalfPre;
    case Stage::kExtraSecondHalfPre: return Stage::kExtraSecondHalf;
    case Stage::kExtraSecondHalf: return drawn ? Stage::kPenaltyShootoutBreak : Stage::kPostGame;
    case Stage::kPenaltyShootoutBreak: return Stage::kPenaltyShootout;
    case Stage::kPenaltyShootout: return Stage::kPostGame;
    case Stage::kPostGame: return std::nullopt;
  }
  return std::nullopt;
}

/// Halves: their clock runs while the game runs. Breaks: their clock runs always.
bool is_half(Stage stage) {
  return stage == Stage::kNormalFirstHalf || stage == Stage::kNormalSecondHalf ||
         stage == Stage::kExtraFirstHalf || stage == Stage::kExtraSecondHalf;
}
bool is_break(Stage stage) {
  return stage == Stage::kNormalHalfTime || stage == Stage::kExtraTimeBreak || stage == Stage::kExtraHalfTime ||
         stage == Stage::kPenaltyShootoutBreak;
}
/// The half a *_PRE stage opens when play starts.
std::optional<Stage> half_opened_by(Stage stage) {
  switch (stage) {
    case Stage::kNormalFirstHalfPre: return Stage::kNormalFirstHalf;
    case Stage::kNormalSecondHalfPre: return Stage::kNormalSecondHalf;
    case Stage::kExtraFirstHalfPre: return Stage::kExtraFirstHalf;
    case Stage::kExtraSecondHalfPre: return Stage::kExtraSecondHalf;
    default: return std::nullopt;
  }
}
std::size_t index_of(TeamColor team) { return team == TeamColor::kYellow ? 0 : 1; }

bool is_finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

double sign_of(double value) { return value < 0 ? -1.0 : 1.0; }

/// How deep `p` lies inside `area` (>= 0 inside: distance to the nearest edge; negative outside).
double depth_in(const geom::Rectangle& area, const Vec2& p) { return -geom::signed_distance(p, area); }
bool entirely_inside(const geom::Rectangle& area, const Vec2& robot, double robot_radius) {
  return depth_in(area, robot) >= robot_radius;
}
bool partly_inside(const geom::Rectangle& area, const Vec2& robot, double robot_radius) {
  return depth_in(area, robot) > -robot_radius;
}

}  // namespace

// -------------------------------------------------------------------------------------------------------
// Construction and inputs

BuiltinReferee::BuiltinReferee(RefereeProfile profile, FieldGeometry field, MatchSetup match)
    : profile_(std::move(profile)), field_(field), division_(match.division) {
  state_.source = RefereeSource::kBuiltin;
  state_.source_identifier = "builtin:" + profile_.name;
  state_.stage = Stage::kNormalFirstHalfPre;
  state_.command = Command::kHalt;
  state_.blue_team_on_positive_half = match.blue_on_positive_half;
  for (auto [info, setup] :
       {std::pair{&state_.yellow, &match.yellow}, std::pair{&state_.blue, &match.blue}}) {
    info->name = setup->name;
    info->goalkeeper = setup->goalkeeper;
    info->can_place_ball = true;
    info->max_allowed_bots = match.max_allowed_bots;
    info->timeouts = kTimeoutsPerTeam;
    info->timeout_time_left = duration_from_seconds(kTimeoutBudget);
  }
  state_.next_command = kickoff(profile_.game.kickoff_team);
  automatic_next_ = profile_.game.auto_continue;
}

void BuiltinReferee::step(const Observation& observation, Timestamp now) {
  if (last_now_ && now < *last_now_) {
    ++counters_.time_went_backwards;
    return;
  }
  begin(now);
  ++counters_.observations;
  const CleanObservation seen = clean(observation, now);
  update_last_touch(seen);
  track_kick(seen);

  const bool timed_stage = is_half(state_.stage) || is_break(state_.stage);
  if (timed_stage && state_.stage_time_left && *state_.stage_time_left <= time::Duration::zero()) {
    const bool drawn = state_.yellow.score == state_.blue.score;
    if (const std::optional<Stage> following = stage_after(state_.stage, profile_.game.extra_time.enabled, drawn)) {
      enter_stage(*following, now);
    }
    return;
  }

  std::optional<Transition> decision;
  switch (phase_) {
    case Phase::kRunning:
      decision = judge_running(seen, now);
      if (!decision && penalty_kicker_) decision = judge_kick_timeout(seen, now);
      if (!decision && state_.stage != Stage::kPenaltyShootout) decision = judge_running_fouls(seen, now);
      break;
    case Phase::kPlacing:
      judge_placement_interference(seen, now);
      decision = judge_placement(seen, now);
      break;
    case Phase::kStopped:
    case Phase::kPreparing:
      judge_keep_out(seen, now);
      if (phase_ == Phase::kStopped) {
        judge_stop_speed(seen, now);
        judge_defense_area_distance(seen, now);
      }
      decision = automatic_continuation(seen, now);
      break;
    case Phase::kKickPending:
      judge_keep_out(seen, now);
      if (is_direct_free(state_.command)) judge_defense_area_distance(seen, now);
      decision = judge_kick_timeout(seen, now);
      // A penalty's ball in play is judged like any running ball (goal, out), and still times out.
      if (!decision && phase_ == Phase::kRunning) decision = judge_running(seen, now);
      break;
    case Phase::kHalted:
    case Phase::kTimeout:
      break;
  }
  judge_boundary_crossing(seen, now);
  if (decision) apply(*decision, now);
}

Status BuiltinReferee::command(Command command, Timestamp now, std::optional<Vec2> designated_position) {
  const auto refuse = [this](std::string message) -> Status {
    ++counters_.rejected_commands;
    return Error{std::move(message)};
  };
  if (static_cast<int>(command) >= kCommandCount) return refuse("not a referee command");
  if (command == Command::kGoalYellow || command == Command::kGoalBlue ||
      command == Command::kIndirectFreeYellow || command == Command::kIndirectFreeBlue) {
    return refuse(std::string(to_string(command)) + " is deprecated; the built-in referee does not issue it");
  }
  const bool placement = command == Command::kBallPlacementYellow || command == Command::kBallPlacementBlue;
  if (placement && (!designated_position || !is_finite(*designated_position))) {
    return refuse(std::string(to_string(command)) + " needs a finite designated position (m)");
  }
  if (last_now_ && now < *last_now_) {
    ++counters_.time_went_backwards;
    now = *last_now_;
  }
  begin(now);
  apply(standard_transition(command, placement ? designated_position : std::nullopt,
                            "operator: " + std::string(to_string(command))),
        now);
  return Status::success();
}

void BuiltinReferee::resume(const RefereeState& saved, Timestamp now) {
  state_.stage = saved.stage;
  state_.stage_time_left = saved.stage_time_left;
  state_.match_type = saved.match_type;
  state_.yellow = saved.yellow;
  state_.blue = saved.blue;
  if (saved.blue_team_on_positive_half) state_.blue_team_on_positive_half = saved.blue_team_on_positive_half;
  state_.command_counter = saved.command_counter;
  state_.command = saved.command;
  begin(now);
  apply(resumption(saved), now);
  // apply() counts a timeout it starts; this one was counted before the restart.
  state_.yellow.timeouts = saved.yellow.timeouts;
  state_.blue.timeouts = saved.blue.timeouts;
}

BuiltinReferee::Transition BuiltinReferee::resumption(const RefereeState& saved) const {
  Transition transition{.command = Command::kStop,
                        .next_is_automatic = profile_.game.auto_continue,
                        .reason = "resumed after a restart of the referee"};
  if (saved.stage == Stage::kPostGame) {
    transition.command = Command::kHalt;
    transition.next_is_automatic = false;
    return transition;
  }
  switch (saved.command) {
    case Command::kHalt:
    case Command::kTimeoutYellow:
    case Command::kTimeoutBlue:
      transition.command = saved.command;
      transition.next_command = saved.next_command;
      break;
    case Command::kStop:
    case Command::kBallPlacementYellow:
    case Command::kBallPlacementBlue:
      transition.next_command = saved.next_command.value_or(Command::kForceStart);
      break;
    case Command::kPrepareKickoffYellow:
    case Command::kPrepareKickoffBlue:
    case Command::kPreparePenaltyYellow:
    case Command::kPreparePenaltyBlue:
      transition.next_command = saved.command;
      break;
    default:  // the ball in play, or a kick under way
      transition.next_command = Command::kForceStart;
      break;
  }
  return transition;
}

void BuiltinReferee::set_blue_on_positive_half(bool blue_on_positive_half) {
  state_.blue_team_on_positive_half = blue_on_positive_half;
}

Status BuiltinReferee::next_stage(Timestamp now) {
  const std::optional<Stage> following =
      stage_after(state_.stage, profile_.game.extra_time.enabled, state_.yellow.score == state_.blue.score);
  if (!following) return Error{"no stage follows " + std::string(to_string(state_.stage))};
  if (last_now_ && now < *last_now_) {
    ++counters_.time_went_backwards;
    now = *last_now_;
  }
  begin(now);
  enter_stage(*following, now);
  return Status::success();
}

void BuiltinReferee::begin(Timestamp now) {
  if (!last_now_) {
    if (state_.command_counter == 0) state_.command_referee = now;
    command_since_ = now;
  } else {
    const time::Duration elapsed = now - *last_now_;
    const Command command = state_.command;
    const bool clock_runs =
        command == Command::kNormalStart || command == Command::kForceStart || is_direct_free(command);
    if (state_.stage_time_left && ((is_half(state_.stage) && clock_runs) || is_break(state_.stage))) {
      *state_.stage_time_left -= elapsed;
    }
    if (is_half(state_.stage) && clock_runs) run_card_clocks(elapsed);
    if (command == Command::kTimeoutYellow) state_.yellow.timeout_time_left -= elapsed;
    if (command == Command::kTimeoutBlue) state_.blue.timeout_time_left -= elapsed;
  }
  if (phase_ == Phase::kPlacing) {
    state_.current_action_time_remaining =
        duration_from_seconds(profile_.game.placement_timeout + placement_extra_time_) - (now - command_since_);
  } else if (phase_ == Phase::kKickPending) {
    state_.current_action_time_remaining = duration_from_seconds(restart_timeout()) - (now - command_since_);
  }
  last_now_ = now;
  state_.packet_referee = now;
}

BuiltinReferee::CleanObservation BuiltinReferee::clean(const Observation& observation, Timestamp now) {
  CleanObservation seen;
  bool invalid_ball = false;
  if (!observation.ball_position) {
    ++counters_.missing_ball;
  } else if (is_finite(*observation.ball_position)) {
    seen.ball = observation.ball_position;
  } else {
    invalid_ball = true;
  }
  if (observation.ball_velocity && !is_finite(*observation.ball_velocity)) invalid_ball = true;
  if (invalid_ball) ++counters_.invalid_ball;

  std::optional<double> interval;  // s since the previous observation with a ball
  const std::optional<geom::Vec2> previous_ball = last_ball_;
  if (seen.ball) {
    if (last_ball_ && last_ball_time_ && now > *last_ball_time_) {
      interval = time::to_seconds(now - *last_ball_time_);
    }
    if (observation.ball_velocity && is_finite(*observation.ball_velocity)) {
      seen.ball_velocity = observation.ball_velocity;
      seen.ball_speed = observation.ball_velocity->norm();
    } else {
      if (interval && *interval <= kSpeedBaseline) seen.ball_velocity = (*seen.ball - *last_ball_) / *interval;
      if (speed_reference_ && now > speed_reference_->second) {
        // Over at least kSpeedBaseline: between two frames 10 ms apart, 3 mm of detection noise alone would
        // read as 0.4 m/s and a resting ball would never be at rest.
        const double baseline = time::to_seconds(now - speed_reference_->second);
        if (baseline >= kSpeedBaseline || !estimated_ball_speed_) {
          estimated_ball_speed_ = (*seen.ball - speed_reference_->first).norm() / baseline;
        }
        seen.ball_speed = estimated_ball_speed_;
      }
    }
    if (!speed_reference_ || now - speed_reference_->second >= duration_from_seconds(kSpeedBaseline)) {
      speed_reference_ = {*seen.ball, now};
    }
    last_ball_ = seen.ball;
    last_ball_time_ = now;
  }

  std::set<std::pair<TeamColor, std::uint32_t>> present;
  for (const ObservedRobot& robot : observation.robots) {
    if (!is_finite(robot.position)) {
      ++counters_.invalid_robot;
    } else if (robot.id > kMaxRobotId) {
      ++counters_.unknown_robot_id;
    } else if (!present.emplace(robot.team, robot.id).second) {
      ++counters_.duplicate_robot;
    } else {
      seen.robots.push_back(robot);
    }
  }
  estimate_robot_velocities(seen, now);
  seen.touch = toucher(seen, kTouchMargin);
  seen.touch_in_reach = seen.touch.has_value();
  if (!seen.touch && interval && previous_ball) seen.touch = deflected_by(seen, *previous_ball, *interval);
  if (seen.ball) last_ball_velocity_ = seen.ball_velocity;
  return seen;
}

std::optional<BuiltinReferee::Touch> BuiltinReferee::toucher(const CleanObservation& seen, double margin) const {
  if (!seen.ball) return std::nullopt;
  const ObservedRobot* nearest = nearest_within(seen.robots, field_.max_robot_radius + field_.ball_radius + margin,
                                                [&](const Vec2& robot) { return (robot - *seen.ball).norm(); });
  if (nearest == nullptr) return std::nullopt;
  return Touch{nearest->team, nearest->id};
}

std::optional<BuiltinReferee::Touch> BuiltinReferee::deflected_by(const CleanObservation& seen, const geom::Vec2& from,
                                                                  double interval) const {
  if (!seen.ball || !seen.ball_velocity || !last_ball_velocity_) return std::nullopt;
  if ((*seen.ball_velocity - *last_ball_velocity_).norm() <= kDeflectionSpeed) return std::nullopt;
  // It met the robot on its way: within reach of where it was running to from the previous observation.
  const geom::Segment path{from, from + *last_ball_velocity_ * interval};
  const double reach = field_.max_robot_radius + field_.ball_radius + kTouchMargin;
  const ObservedRobot* nearest =
      nearest_within(seen.robots, reach, [&](const Vec2& robot) { return geom::distance(robot, path); });
  if (nearest == nullptr) return std::nullopt;
  return Touch{nearest->team, nearest->id};
}

void BuiltinReferee::update_last_touch(const CleanObservation& seen) {
  if (seen.touch) last_touch_ = seen.touch;
}

geom::Rectangle BuiltinReferee::defense_area_of(TeamColor defending_team) const {
  return defense_area(field_, goal_x_of(defending_team));
}

void BuiltinReferee::track_kick(const CleanObservation& seen) {
  if (phase_ != Phase::kKickPending || !seen.ball) return;
  if (!kick_reference_ball_) {
    kick_reference_ball_ = seen.ball;
  } else if ((*seen.ball - *kick_reference_ball_).norm() >= kInPlayDistance) {
    start_running();
    // Double touch: the kicker of this restart may not touch the ball again before another robot did (a
    // kickoff or free kick; a penalty's attacker may play the ball on).
    if (!penalty_kicker_ && last_touch_ && executing_team_ && last_touch_->team == *executing_team_) {
      kicker_watch_ = KickerWatch{*last_touch_, *seen.ball};
    }
  }
}

// -------------------------------------------------------------------------------------------------------
// The state machine

BuiltinReferee::Transition BuiltinReferee::standard_transition(Command command,
                                                               std::optional<Vec2> designated_position,
                                                               std::string reason) const {
  Transition transition{.command = command, .reason = std::move(reason)};
  switch (command) {
    case Command::kHalt:
    case Command::kStop:
    case Command::kTimeoutYellow:
    case Command::kTimeoutBlue:
      // A pause keeps what was pending, and whether it continues by itself once STOP is back.
      transition.next_command = state_.next_command;
      transition.next_is_automatic = automatic_next_;
      break;
    case Command::kPrepareKickoffYellow:
    case Command::kPrepareKickoffBlue:
    case Command::kPreparePenaltyYellow:
    case Command::kPreparePenaltyBlue:
      transition.next_command = Command::kNormalStart;
      break;
    case Command::kBallPlacementYellow:
    case Command::kBallPlacementBlue:
      transition.designated_position = designated_position;
      transition.next_command = state_.next_command.value_or(direct_free(*team_of(command)));
      transition.placement_attempt = 1;
      break;
    default:
      break;
  }
  return transition;
}

void BuiltinReferee::apply(const Transition& transition, Timestamp now) {
  const Phase previous = phase_;
  const Command previous_command = state_.command;
  const Command command = transition.command;
  state_.command = command;
  ++state_.command_counter;
  state_.command_referee = now;
  state_.next_command = transition.next_command;
  state_.designated_position = transition.designated_position;
  state_.status_message = transition.reason;
  automatic_next_ = transition.next_is_automatic;
  placement_attempt_ = transition.placement_attempt;
  awaiting_hand_placement_ = transition.awaiting_hand_placement;
  command_since_ = now;
  keep_out_since_.clear();
  interference_since_.clear();
  area_distance_since_.clear();
  too_fast_in_stop_.clear();
  placement_extra_time_ = 0;
  kicker_watch_.reset();
  placement_ok_since_.reset();
  kick_reference_ball_ = last_ball_;

  switch (command) {
    case Command::kHalt:
      phase_ = Phase::kHalted;
      break;
    case Command::kStop:
    case Command::kGoalYellow:
    case Command::kGoalBlue:
      phase_ = Phase::kStopped;
      break;
    case Command::kNormalStart:
      phase_ = previous == Phase::kPreparing ? Phase::kKickPending : Phase::kRunning;
      break;
    case Command::kForceStart:
      phase_ = Phase::kRunning;
      break;
    case Command::kPrepareKickoffYellow:
    case Command::kPrepareKickoffBlue:
    case Command::kPreparePenaltyYellow:
    case Command::kPreparePenaltyBlue:
      phase_ = Phase::kPreparing;
      break;
    case Command::kDirectFreeYellow:
    case Command::kDirectFreeBlue:
    case Command::kIndirectFreeYellow:
    case Command::kIndirectFreeBlue:
      phase_ = Phase::kKickPending;
      break;
    case Command::kTimeoutYellow:
    case Command::kTimeoutBlue:
      phase_ = Phase::kTimeout;
      break;
    case Command::kBallPlacementYellow:
    case Command::kBallPlacementBlue:
      phase_ = Phase::kPlacing;
      break;
  }
  // The kicker of a kickoff or penalty keeps its role through NORMAL_START.
  const bool kick_of_preparation = command == Command::kNormalStart && phase_ == Phase::kKickPending;
  const std::optional<Command> prepared = previous == Phase::kPreparing ? std::optional(previous_command) : std::nullopt;
  if (!kick_of_preparation) executing_team_ = team_of(command);
  penalty_kicker_.reset();
  if (kick_of_preparation && prepared && is_penalty(*prepared)) penalty_kicker_ = team_of(*prepared);

  if (command == Command::kTimeoutYellow && state_.yellow.timeouts > 0) --state_.yellow.timeouts;
  if (command == Command::kTimeoutBlue && state_.blue.timeouts > 0) --state_.blue.timeouts;
  state_.current_action_time_remaining.reset();
  if (phase_ == Phase::kPlacing) {
    state_.current_action_time_remaining = duration_from_seconds(profile_.game.placement_timeout);
  } else if (phase_ == Phase::kKickPending) {
    state_.current_action_time_remaining = duration_from_seconds(restart_timeout());
  }

  const bool starts_play = command == Command::kNormalStart || command == Command::kForceStart;
  if (starts_play) {
    if (const std::optional<Stage> half = half_opened_by(state_.stage)) enter_stage(*half, now);
  }
  if (phase_ == Phase::kRunning) start_running();
}

void BuiltinReferee::start_running() {
  phase_ = Phase::kRunning;
  dribble_.reset();
  ball_in_own_area_since_.reset();
  state_.game_events.clear();  // the league's game_events are those since the last running state
  ball_inside_since_running_.reset();
  progress_ball_.reset();
}

void BuiltinReferee::enter_stage(Stage stage, Timestamp now) {
  state_.stage = stage;
  state_.stage_time_left.reset();
  const GameSettings& game = profile_.game;
  const auto kickoff_pending = [&](TeamColor team, const std::string& reason) {
    // The teams change sides before every half after the first.
    set_blue_on_positive_half(!state_.blue_team_on_positive_half.value_or(kBlueOnPositiveHalfAtStart));
    apply({.command = Command::kStop,
           .next_command = kickoff(team),
           .next_is_automatic = game.auto_continue,
           .reason = reason + ": kickoff " + std::string(to_string(team))},
          now);
  };
  const auto halt_for = [&](double seconds, const std::string& reason) {
    state_.stage_time_left = duration_from_seconds(seconds);
    apply({.command = Command::kHalt, .reason = reason}, now);
  };
  switch (stage) {
    case Stage::kNormalFirstHalf:
    case Stage::kNormalSecondHalf:
      state_.stage_time_left = duration_from_seconds(game.half_duration);
      break;
    case Stage::kExtraFirstHalf:
    case Stage::kExtraSecondHalf:
      state_.stage_time_left = duration_from_seconds(game.extra_time.half_duration);
      break;
    case Stage::kNormalHalfTime:
      halt_for(game.half_time, "half time");
      break;
    case Stage::kExtraTimeBreak:
      halt_for(game.extra_time.break_duration, "draw: break before extra time");
      break;
    case Stage::kExtraHalfTime:
      halt_for(game.extra_time.half_time, "extra time: half time");
      break;
    case Stage::kPenaltyShootoutBreak:
      halt_for(game.extra_time.shootout_break, "draw after extra time: break before the shoot-out");
      break;
    case Stage::kNormalSecondHalfPre:
      kickoff_pending(opponent(game.kickoff_team), "second half");
      break;
    case Stage::kExtraFirstHalfPre:
      kickoff_pending(game.kickoff_team, "extra time, first half");
      break;
    case Stage::kExtraSecondHalfPre:
      kickoff_pending(opponent(game.kickoff_team), "extra time, second half");
      break;
    case Stage::kPenaltyShootout:
      apply({.command = Command::kStop,
             .next_command = penalty(game.kickoff_team),
             .next_is_automatic = game.auto_continue,
             .reason = "shoot-out: penalty " + std::string(to_string(game.kickoff_team))},
            now);
      break;
    case Stage::kPostGame:
      apply({.command = Command::kHalt, .reason = "match over"}, now);
      break;
    case Stage::kNormalFirstHalfPre:
      break;
  }
}

std::optional<BuiltinReferee::Transition> BuiltinReferee::automatic_continuation(const CleanObservation& seen,
                                                                                 Timestamp now) {
  const GameSettings& game = profile_.game;
  const time::Duration waited = now - command_since_;
  if (waited < duration_from_seconds(game.stop_duration)) return std::nullopt;
  if (phase_ == Phase::kStopped && state_.next_command) {
    const Command next = *state_.next_command;
    std::optional<Vec2> target = placement_needed_for(next, seen.ball);
    // A free kick the referee continues with by itself, whose ball rolled on during STOP (into a defense
    // area, too near a line): placed at the nearest legal spot first, where the kicking team can play it.
    if (!target && automatic_next_ && is_direct_free(next) && seen.ball) {
      const Vec2 spot = legal_free_kick_spot(*seen.ball);
      if ((spot - *seen.ball).norm() > game.placement_tolerance) target = spot;
    }
    // The ball is placed first, even before a restart the operator will issue; without anyone to place
    // it, nothing is issued until it was placed by hand.
    if (target && !awaiting_hand_placement_) return placement_before(next, *target, automatic_next_);
    if (target || !automatic_next_) return std::nullopt;
    return standard_transition(next, std::nullopt, "automatic: " + std::string(to_string(next)));
  }
  if (phase_ == Phase::kPreparing && game.auto_continue) {
    const bool ready = !is_kickoff(state_.command) || robots_ready_for_kickoff(seen);
    if (ready || waited >= duration_from_seconds(game.prepare_timeout)) {
      return standard_transition(Command::kNormalStart, std::nullopt,
                                 ready ? "automatic: NORMAL_START" : "automatic: NORMAL_START (prepare timeout)");
    }
  }
  return std::nullopt;
}

std::optional<Vec2> BuiltinReferee::placement_needed_for(Command restart, const std::optional<Vec2>& ball) const {
  if (!ball) return std::nullopt;  // nothing to judge; the restart goes ahead
  const auto unless_near = [&](const Vec2& spot) -> std::optional<Vec2> {
    if ((*ball - spot).norm() <= profile_.game.placement_tolerance) return std::nullopt;
    return spot;
  };
  if (is_kickoff(restart)) return unless_near(Vec2::Zero());
  if (is_penalty(restart)) return unless_near(penalty_mark_against(opponent(*team_of(restart))));
  if (restart != Command::kForceStart) return std::nullopt;
  // FORCE_START (after no progress, a goal with force_start_after_goal, a failed placement): as the Game
  // Controller does with the location of the event, a ball beyond the lines (in a goal, in the boundary),
  // too near one, or before a defense area (within 1 m of it) goes to the nearest legal free-kick spot
  // first. Left there, a ball stuck by a defense area, where neither team can play it, stalls again.
  return unless_near(legal_free_kick_spot(*ball));
}

BuiltinReferee::Transition BuiltinReferee::placement_before(Command restart, const Vec2& target,
                                                             bool restart_is_automatic,
                                                             std::optional<TeamColor> placer_choice) const {
  // The kicker places for its own kickoff or penalty; before a FORCE_START the team that did not touch the
  // ball last (the Game Controller draws one by lot; this stays deterministic).
  TeamColor placer = placer_choice.value_or(
      team_of(restart).value_or(last_touch_ ? opponent(last_touch_->team) : profile_.game.kickoff_team));
  if (!team_info(placer).can_place_ball) placer = opponent(placer);
  const std::string reason = "ball to (" + std::to_string(target.x()).substr(0, 5) + ", " +
                             std::to_string(target.y()).substr(0, 5) + ") for " + std::string(to_string(restart));
  if (!profile_.game.ball_placement || !team_info(placer).can_place_ball) {
    return {.command = Command::kStop,
            .next_command = restart,
            .next_is_automatic = restart_is_automatic,
            .awaiting_hand_placement = true,
            .reason = reason + ": to be placed by hand"};
  }
  return {.command = ball_placement(placer),
          .next_command = restart,
          .designated_position = target,
          .next_is_automatic = restart_is_automatic,
          .placement_attempt = 1,
          .reason = reason + ": placed by " + std::string(to_string(placer))};
}

bool BuiltinReferee::robots_ready_for_kickoff(const CleanObservation& seen) const {
  const TeamColor kicking = executing_team_.value_or(profile_.game.kickoff_team);
  int kickers_in_circle = 0;
  for (const ObservedRobot& robot : seen.robots) {
    const bool own_half = robot.position.x() * sign_of(goal_x_of(robot.team)) >= 0;
    const bool in_circle = robot.position.norm() < field_.center_circle_radius + field_.max_robot_radius;
    if (!own_half && !(in_circle && robot.team == kicking)) return false;
    if (in_circle && (robot.team != kicking || ++kickers_in_circle > 1)) return false;
  }
  return true;
}

double BuiltinReferee::restart_timeout() const {
  if (penalty_kicker_) return profile_.game.penalty_timeout;
  if (is_direct_free(state_.command)) return profile_.game.free_kick_timeout.of(division_);
  return profile_.game.kickoff_timeout;
}

std::optional<BuiltinReferee::Transition> BuiltinReferee::after_shootout_penalty(Timestamp now) {
  if (state_.stage != Stage::kPenaltyShootout || !penalty_kicker_) return std::nullopt;
  const TeamColor kicker = *penalty_kicker_;
  ++shootout_taken_[index_of(kicker)];
  const std::uint32_t rounds = profile_.game.extra_time.shootout_penalties;
  bool decided = false;
  for (const TeamColor team : {TeamColor::kYellow, TeamColor::kBlue}) {
    const std::size_t us = index_of(team);
    const std::size_t them = index_of(opponent(team));
    // The other team cannot catch up with the kicks it has left (in the regular rounds, or to equal turns
    // in sudden death).
    const std::uint32_t turns = std::max(rounds, shootout_taken_[us]);
    const std::uint32_t left = shootout_taken_[them] < turns ? turns - shootout_taken_[them] : 0;
    if (shootout_scored_[us] > shootout_scored_[them] + left) decided = true;
  }
  // Sudden death (and the end of the regular rounds): a lead after equal turns.
  if (shootout_taken_[0] == shootout_taken_[1] && shootout_taken_[0] >= rounds &&
      shootout_scored_[0] != shootout_scored_[1]) {
    decided = true;
  }
  if (decided) {
    enter_stage(Stage::kPostGame, now);
    return std::nullopt;
  }
  const TeamColor next = opponent(kicker);
  return Transition{.command = Command::kStop,
                    .next_command = penalty(next),
                    .next_is_automatic = profile_.game.auto_continue,
                    .reason = "shoot-out: penalty " + std::string(to_string(next))};
}

bool BuiltinReferee::match_decided_early() const {
  const std::uint32_t goals = profile_.game.early_end_goals;
  if (goals == 0) return false;
  const std::uint32_t yellow = state_.yellow.score;
  const std::uint32_t blue = state_.blue.score;
  return (yellow >= goals && yellow >= blue + 2) || (blue >= goals && blue >= yellow + 2);
}

// -------------------------------------------------------------------------------------------------------
// Rules

std::optional<BuiltinReferee::Transition> BuiltinReferee::judge_running(const CleanObservation& seen,
                                                                        Timestamp now) {
  if (seen.ball) {
    const Vec2& ball = *seen.ball;
    const bool inside = std::abs(ball.x()) <= 0.5 * field_.field_length + field_.ball_radius &&
                        std::abs(ball.y()) <= 0.5 * field_.field_width + field_.ball_radius;
    if (inside) {
      ball_inside_since_running_ = ball;
    } else if (ball_inside_since_running_) {
      std::optional<Transition> decision = judge_ball_left_field(ball, now);
      ball_inside_since_running_.reset();  // judged once, even when ignored (cooldown, rule disabled)
      if (decision) return decision;
    }
  }
  if (state_.stage == Stage::kPenaltyShootout) return std::nullopt;  // only the penalty's end counts
  if (std::optional<Transition> decision = judge_defense_areas(seen, now)) return decision;
  return judge_progress(seen, now);
}

std::optional<BuiltinReferee::Transition> BuiltinReferee::judge_progress(const CleanObservation& seen,
                                                                         Timestamp now) {
  const NoProgressRule& rule = profile_.rules.no_progress;
  if (!rule.enabled || !seen.ball) return std::nullopt;
  if (!progress_ball_ || (*seen.ball - *progress_ball_).norm() >= kInPlayDistance) {
    progress_ball_ = seen.ball;
    progress_since_ = now;
    return std::nullopt;
  }
  const double timeout = rule.timeout.of(division_);
  if (now - progress_since_ < duration_from_seconds(timeout)) return std::nullopt;
  raise({.type = GameEventType::kNoProgressInGame, .location = *seen.ball, .value = timeout}, now, false);
  return Transition{.command = Command::kStop,
                    .next_command = Command::kForceStart,
                    .next_is_automatic = true,
                    .reason = "no progress: FORCE_START"};
}

std::optional<BuiltinReferee::Transition> BuiltinReferee::judge_kick_timeout(const CleanObservation& seen,
                                                                             Timestamp now) {
  if (now - command_since_ < duration_from_seconds(restart_timeout())) return std::nullopt;
  if (!penalty_kicker_) {
    // A kickoff or free kick not taken in time: its ball is in play all the same (no command changes).
    start_running();
    return std::nullopt;
  }
  const TeamColor kicker = *penalty_kicker_;
  const TeamColor defending = opponent(kicker);
  raise({.type = GameEventType::kPenaltyKickFailed,
         .by_team = to_team(kicker),
         .location = seen.ball,
         .text = "not decided within " + std::to_string(static_cast<int>(profile_.game.penalty_timeout)) + " s"},
        now, /*is_foul=*/false);
  if (std::optional<Transition> shootout = after_shootout_penalty(now)) return shootout;
  if (state_.stage == Stage::kPostGame) return std::nullopt;
  return Transition{.command = Command::kStop,
                    .next_command = direct_free(defending),
                    .next_is_automatic = true,
                    .reason = "penalty failed: free kick " + std::string(to_string(defending))};
}

std::optional<BuiltinReferee::Transition> BuiltinReferee::judge_ball_left_field(const Vec2& ball,
                                                                                Timestamp now) {
  // Where the path from the last in-field position crossed the first line (the ball wholly over it).
  const Vec2 from = *ball_inside_since_running_;
  const Vec2 path = ball - from;
  const double beyond_goal_line = 0.5 * field_.field_length + field_.ball_radius;
  const double beyond_touch_line = 0.5 * field_.field_width + field_.ball_radius;
  double to_goal_line = std::numeric_limits<double>::infinity();
  double to_touch_line = std::numeric_limits<double>::infinity();
  if (std::abs(ball.x()) > beyond_goal_line)
    to_goal_line = (sign_of(ball.x()) * beyond_goal_line - from.x()) / path.x();
  if (std::abs(ball.y()) > beyond_touch_line)
    to_touch_line = (sign_of(ball.y()) * beyond_touch_line - from.y()) / path.y();
  const bool over_goal_line = to_goal_line <= to_touch_line;
  const Vec2 exit = from + std::min(to_goal_line, to_touch_line) * path;

  if (over_goal_line && std::abs(exit.y()) <= 0.5 * field_.goal_width - field_.ball_radius) {
    const GoalDetectionRule& rule = profile_.rules.goal_detection;
    if (!rule.enabled) return std::nullopt;
    if (last_goal_ && now - *last_goal_ < duration_from_seconds(rule.cooldown)) return std::nullopt;
    last_goal_ = now;
    const TeamColor conceding = defender_of_goal_at(exit.x());
    const TeamColor scoring = opponent(conceding);
    ++team_info(scoring).score;
    GameEvent goal{.type = GameEventType::kGoal, .by_team = to_team(scoring), .location = exit};
    if (last_touch_ && last_touch_->team == scoring) goal.by_bot = last_touch_->id;
    raise(std::move(goal), now, /*is_foul=*/false);
    if (state_.stage == Stage::kPenaltyShootout) {
      ++shootout_scored_[index_of(scoring)];
      return after_shootout_penalty(now);
    }
    if (match_decided_early()) {
      enter_stage(Stage::kPostGame, now);
      return std::nullopt;
    }
    return after_goal(conceding);
  }

  if (state_.stage == Stage::kPenaltyShootout) return after_shootout_penalty(now);
  const OutOfBoundsRule& rule = profile_.rules.out_of_bounds;
  if (!rule.enabled) return std::nullopt;
  const double x_sign = sign_of(exit.x());
  const double y_sign = sign_of(exit.y());
  const double half_length = 0.5 * field_.field_length;
  const double half_width = 0.5 * field_.field_width;
  // Unknown last touch: a goal kick for the goal line's defenders, or a throw-in for the team defending
  // the half where the ball went out.
  const TeamColor kicking_team = last_touch_ ? opponent(last_touch_->team) : defender_of_goal_at(exit.x());
  Vec2 placement_point;
  if (over_goal_line) {
    const bool goal_kick = kicking_team == defender_of_goal_at(exit.x());
    const double from_goal_line = goal_kick ? rule.goal_kick_distance : rule.line_distance;
    placement_point = {x_sign * (half_length - from_goal_line), y_sign * (half_width - rule.line_distance)};
  } else {
    const double max_x = half_length - rule.line_distance;
    placement_point = {std::clamp(exit.x(), -max_x, max_x), y_sign * (half_width - rule.line_distance)};
  }
  ball_left_field_ = {now, last_touch_};
  boundary_crossing_raised_ = false;
  GameEvent left{
      .type = over_goal_line ? GameEventType::kBallLeftFieldGoalLine : GameEventType::kBallLeftFieldTouchLine,
      .location = exit};
  if (last_touch_) {
    left.by_team = to_team(last_touch_->team);
    left.by_bot = last_touch_->id;
  }
  raise(std::move(left), now, /*is_foul=*/false);
  return free_kick_after_ball_left(
      kicking_team, placement_point,
      std::string(over_goal_line ? "ball over the goal line" : "ball over the touch line") + ": free kick " +
          std::string(to_string(kicking_team)));
}

BuiltinReferee::Transition BuiltinReferee::after_goal(TeamColor conceding_team) const {
  const std::string reason = "goal for " + std::string(to_string(opponent(conceding_team)));
  if (profile_.game.force_start_after_goal) {
    // The ball goes back to the centre mark, then the game goes on.
    Transition place =
        placement_before(Command::kForceStart, Vec2::Zero(), /*restart_is_automatic=*/true, conceding_team);
    place.reason = reason + "; " + place.reason;
    return place;
  }
  return {.command = Command::kStop,
          .next_command = kickoff(conceding_team),
          .next_is_automatic = profile_.game.auto_continue,
          .reason = reason};
}

BuiltinReferee::Transition BuiltinReferee::free_kick_after_ball_left(TeamColor kicking_team,
                                                                     const Vec2& placement_point,
                                                                     const std::string& reason) const {
  if (profile_.rules.out_of_bounds.ball_placement && team_info(kicking_team).can_place_ball) {
    return {.command = ball_placement(kicking_team),
            .next_command = direct_free(kicking_team),
            .designated_position = placement_point,
            .placement_attempt = 1,
            .reason = reason};
  }
  // Nobody places the ball: the free kick follows by itself only when the profile continues everything.
  return {.command = Command::kStop,
          .next_command = direct_free(kicking_team),
          .next_is_automatic = profile_.game.auto_continue,
          .reason = reason};
}

std::optional<BuiltinReferee::Transition> BuiltinReferee::judge_placement(const CleanObservation& seen,
                                                                          Timestamp now) {
  const TeamColor placer = executing_team_.value_or(TeamColor::kYellow);
  const Vec2 target = state_.designated_position.value_or(Vec2::Zero());
  std::optional<double> remaining;
  if (seen.ball) {
    remaining = (*seen.ball - target).norm();
    const bool placed = *remaining <= profile_.game.placement_tolerance && seen.ball_speed &&
                        *seen.ball_speed <= kBallAtRestSpeed;
    if (!placed) {
      placement_ok_since_.reset();
    } else if (!placement_ok_since_) {
      placement_ok_since_ = now;
    }
    if (placed && now - *placement_ok_since_ >= duration_from_seconds(kPlacementHold)) {
      TeamInfo& info = team_info(placer);
      if (info.ball_placement_failures > 0) --info.ball_placement_failures;
      raise({.type = GameEventType::kPlacementSucceeded,
             .by_team = to_team(placer),
             .location = seen.ball,
             .value = remaining},
            now, /*is_foul=*/false);
      const Command next = state_.next_command.value_or(direct_free(placer));
      return Transition{.command = Command::kStop,
                        .next_command = next,
                        .next_is_automatic = automatic_next_ || is_direct_free(next) || profile_.game.auto_continue,
                        .reason = "ball placed by " + std::string(to_string(placer))};
    }
  }
  if (now - command_since_ < duration_from_seconds(profile_.game.placement_timeout + placement_extra_time_)) {
    return std::nullopt;
  }

  TeamInfo& info = team_info(placer);
  ++info.ball_placement_failures;
  if (info.ball_placement_failures >= kMaxPlacementFailures) {
    info.ball_placement_failures_reached = true;
    info.can_place_ball = false;
  }
  raise({.type = GameEventType::kPlacementFailed,
         .by_team = to_team(placer),
         .location = seen.ball,
         .value = remaining},
        now, /*is_foul=*/false);
  const TeamColor other = opponent(placer);
  const std::string reason = "placement by " + std::string(to_string(placer)) + " failed";
  // A failed placement for a free kick gives the free kick to the other team; before a kickoff, penalty or
  // FORCE_START the restart stays what it was.
  const Command pending = state_.next_command.value_or(direct_free(placer));
  const Command next = is_direct_free(pending) ? direct_free(other) : pending;
  if (placement_attempt_ == 1 && team_info(other).can_place_ball) {
    return Transition{.command = ball_placement(other),
                      .next_command = next,
                      .designated_position = target,
                      .next_is_automatic = automatic_next_,
                      .placement_attempt = 2,
                      .reason = reason + ": " + std::string(to_string(other)) + " places"};
  }
  // Placed by hand: a restart that was automatic goes ahead once the ball is where it must be.
  return Transition{.command = Command::kStop,
                    .next_command = next,
                    .next_is_automatic = automatic_next_,
                    .awaiting_hand_placement = true,
                    .reason = reason + ": the ball must be placed by hand"};
}

std::optional<BuiltinReferee::Transition> BuiltinReferee::judge_defense_areas(const CleanObservation& seen,
                                                                              Timestamp now) {
  const DefenseAreaRule& rule = profile_.rules.defense_area;
  if (!rule.enabled) return std::nullopt;
  const double radius = field_.max_robot_radius;
  const auto area_of = [this](TeamColor defending_team) { return defense_area_of(defending_team); };

  for (const TeamColor team : {TeamColor::kYellow, TeamColor::kBlue}) {
    const geom::Rectangle own_area = area_of(team);
    const std::uint32_t goalkeeper = team_info(team).goalkeeper;
    std::uint32_t inside = 0;
    const ObservedRobot* offender = nullptr;
    // The offender: a non-goalkeeper before the goalkeeper, then the deepest, then the lowest id.
    const auto worse = [&](const ObservedRobot& a, const ObservedRobot& b) {
      const bool a_keeper = a.id == goalkeeper;
      const bool b_keeper = b.id == goalkeeper;
      if (a_keeper != b_keeper) return b_keeper;
      const double a_depth = depth_in(own_area, a.position);
      const double b_depth = depth_in(own_area, b.position);
      if (a_depth != b_depth) return a_depth > b_depth;
      return a.id < b.id;
    };
    for (const ObservedRobot& robot : seen.robots) {
      if (robot.team != team || !entirely_inside(own_area, robot.position, radius)) continue;
      ++inside;
      if (offender == nullptr || worse(robot, *offender)) offender = &robot;
    }
    if (inside > rule.max_defenders) {
      raise({.type = GameEventType::kDefenderInDefenseArea,
             .by_team = to_team(team),
             .by_bot = offender->id,
             .location = offender->position,
             .value = depth_in(own_area, offender->position)},
            now, /*is_foul=*/false);
      // STOP first: the ball goes to the penalty mark (placement_needed_for), then the penalty is prepared.
      const TeamColor kicker = opponent(team);
      return Transition{.command = Command::kStop,
                        .next_command = penalty(kicker),
                        .next_is_automatic = true,
                        .reason = std::to_string(inside) + " " + std::string(to_string(team)) +
                                  " robots in their defense area: penalty " + std::string(to_string(kicker))};
    }
  }

  if (!rule.attacker_infringement) return std::nullopt;
  const double reach = field_.max_robot_radius + field_.ball_radius + kTouchMargin;
  for (const TeamColor team : {TeamColor::kYellow, TeamColor::kBlue}) {
    const TeamColor defending = opponent(team);
    const geom::Rectangle their_area = area_of(defending);
    for (const ObservedRobot& robot : seen.robots) {
      if (robot.team != team) continue;
      const bool touches_ball = seen.ball && (robot.position - *seen.ball).norm() <= reach;
      std::optional<GameEventType> offence;
      if (touches_ball && partly_inside(their_area, robot.position, radius)) {
        offence = GameEventType::kAttackerTouchedBallInDefenseArea;
      } else if (entirely_inside(their_area, robot.position, radius)) {
        offence = GameEventType::kAttackerTooCloseToDefenseArea;
      }
      if (!offence) continue;
      raise({.type = *offence,
             .by_team = to_team(team),
             .by_bot = robot.id,
             .location = robot.position,
             .value = depth_in(their_area, robot.position) + radius},
            now, /*is_foul=*/true);
      return Transition{.command = Command::kStop,
                        .next_command = direct_free(defending),
                        .next_is_automatic = true,
                        .reason = std::string(to_string(team)) + " attacker in the defense area: free kick " +
                                  std::string(to_string(defending))};
    }
  }
  return std::nullopt;
}

void BuiltinReferee::judge_keep_out(const CleanObservation& seen, Timestamp now) {
  const KeepOutRule& rule = profile_.rules.keep_out;
  if (!rule.enabled || !seen.ball) return;
  // In STOP both teams keep out; during a restart the team executing it may approach.
  const bool both_teams = phase_ == Phase::kStopped || !executing_team_;
  const TeamColor executing = executing_team_.value_or(TeamColor::kYellow);
  const time::Duration persistence = duration_from_seconds(rule.violation_persistence);
  for (const ObservedRobot& robot : seen.robots) {
    if (!both_teams && robot.team == executing) continue;
    const geom::Circle zone = ball_keep_out(*seen.ball, field_.max_robot_radius, rule.radius);
    const auto key = std::pair{robot.team, robot.id};
    if (geom::signed_distance(robot.position, zone) >= 0) {
      keep_out_since_.erase(key);
      continue;
    }
    auto& [since, reported] = keep_out_since_.try_emplace(key, now, false).first->second;
    if (reported || now - since < persistence) continue;
    reported = true;
    raise({.type = GameEventType::kDefenderTooCloseToKickPoint,
           .by_team = to_team(robot.team),
           .by_bot = robot.id,
           .location = robot.position,
           .value = std::max(geom::distance(robot.position, *seen.ball) - field_.max_robot_radius, 0.0)},
          now, /*is_foul=*/true);
  }
}

void BuiltinReferee::raise(GameEvent event, Timestamp now, bool is_foul) {
  event.id = "builtin-" + std::to_string(++event_sequence_);
  event.created_referee = now;
  const Team foul_by = is_foul ? event.by_team : Team::kUnknown;
  state_.game_events.push_back(std::move(event));
  if (foul_by == Team::kUnknown) return;
  const TeamColor team = foul_by == Team::kYellow ? TeamColor::kYellow : TeamColor::kBlue;
  ++team_info(team).foul_counter;
  book(team, now);
}

TeamInfo& BuiltinReferee::team_info(TeamColor team) {
  return team == TeamColor::kYellow ? state_.yellow : state_.blue;
}

const TeamInfo& BuiltinReferee::team_info(TeamColor team) const {
  return team == TeamColor::kYellow ? state_.yellow : state_.blue;
}

double BuiltinReferee::goal_x_of(TeamColor defending_team) const {
  const bool blue_positive = state_.blue_team_on_positive_half.value_or(kBlueOnPositiveHalfAtStart);
  const bool positive = (defending_team == TeamColor::kBlue) == blue_positive;
  return (positive ? 0.5 : -0.5) * field_.field_length;
}

Vec2 BuiltinReferee::penalty_mark_against(TeamColor defending_team) const {
  const double goal_x = goal_x_of(defending_team);
  return {goal_x - sign_of(goal_x) * field_.goal_center_to_penalty_mark, 0};
}

TeamColor BuiltinReferee::defender_of_goal_at(double x) const {
  return goal_x_of(TeamColor::kBlue) * sign_of(x) > 0 ? TeamColor::kBlue : TeamColor::kYellow;
}

}  // namespace ssl::referee
