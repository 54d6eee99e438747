// BuiltinReferee: an automatic referee in the manner of the SSL Game Controller, for matches without one
// (simulated AI-vs-AI matches, the lab). Pure: no threads, no DDS, no sockets, no protobuf, no clock. The
// caller feeds vision observations with the current time and forwards the operator's commands; the
// referee answers with a RefereeState (source kBuiltin) that the adapter publishes like a Game
// Controller's. Same inputs in the same order give the same state.
//
// Frame and units: the SSL-Vision global frame, metres, m/s. Clock: `now` is the caller's Unix wall
// clock (the simulated one in lockstep runs); it stamps the packet and command times and drives every
// timer. step() ignores a `now` earlier than the previous one; command() and next_stage() use the
// previous time instead (both counted), so time never runs backwards inside.
//
// State machine. Each command puts the referee into a phase; the transition bookkeeping (counter, command
// time, next command, designated position, timers, phase, stage start of a half) lives in one function,
// `apply`, which every operator command, rule decision and stage change goes through:
//   HALT -> halted | STOP -> stopped | BALL_PLACEMENT_* -> placing | PREPARE_* -> preparing |
//   DIRECT_FREE_* and NORMAL_START after a preparation -> kick pending (the ball is in play once it moved
//   0.05 m; that changes no command) | FORCE_START, NORMAL_START otherwise -> running | TIMEOUT_* ->
//   timeout.
// Rule decisions (goal, out of bounds, defense area) are taken only while running; keep-out is checked in
// stopped, placing, preparing and kick pending. Automatic continuations: in STOP the pending next_command
// is issued after the profile's stop_duration when it was marked automatic (a goal's kickoff and the
// FORCE_START after no progress, the FORCE_START after a goal's placement with force_start_after_goal;
// a free kick after a successful placement or a foul). A preparation gets its NORMAL_START with
// auto_continue once stop_duration passed and the robots stand as the restart demands (kickoff: every
// robot in its own half and outside the centre circle but the kicker), at the latest after
// prepare_timeout. Nothing automatic happens during HALT or a timeout; the operator's commands always
// take effect.
//
// Restarts always restart: before a pending kickoff, penalty or FORCE_START is issued (automatically or
// not), the referee checks the ball. A kickoff needs it on the centre mark, a penalty on the penalty mark
// (within placement_tolerance), a FORCE_START inside the field lines. Otherwise, with game.ball_placement,
// it issues BALL_PLACEMENT to that point (the kicking team, for FORCE_START the team that did not touch
// the ball last) with the restart as next_command; a placement that fails twice leaves STOP with the
// restart pending until an operator places the ball. So a ball left in a goal, or beyond the field
// lines, is never force-started.
//
// Rules (each only when the profile enables it; thresholds in m and s):
//  * last touch: the robot nearest to the ball with centres within robot + ball radius + kTouchMargin.
//  * goal: the ball wholly over the goal line (centre beyond it by the ball radius) where its path crossed
//    between the posts (|y| <= goal_width / 2 - ball radius). Score for the team attacking that goal,
//    kGoal, STOP; next: the conceding team's kickoff (automatic with auto_continue; the ball is placed on
//    the centre mark first), or with force_start_after_goal at once BALL_PLACEMENT to the centre mark by
//    the conceding team and then FORCE_START. Goals within `cooldown` of the
//    last one are ignored, and the ball must have been seen in the field since play (re)started, so a
//    ball left lying in the goal never scores twice. A team reaching early_end_goals with a lead of two
//    ends the match (POST_GAME).
//  * out of bounds: the ball wholly over a touch line or over the goal line outside the posts. Free kick
//    for the team that did not touch it last (unknown: the defenders of that half). Placement point:
//    line_distance inside the touch line at the exit x (kept line_distance from the goal lines); over a
//    goal line line_distance inside the touch line and line_distance (corner kick) or goal_kick_distance
//    (goal kick) inside the goal line. With ball_placement: BALL_PLACEMENT for that team; success = ball
//    within placement_tolerance of the target at <= kBallAtRestSpeed for kPlacementHold -> STOP, then the
//    free kick after stop_duration. Timeout (placement_timeout): kPlacementFailed, the other team places
//    for its own free kick; a second timeout -> STOP, the ball is placed by hand.
//  * defense area: more than max_defenders robots of a team entirely inside their own area -> penalty for
//    the other team (PREPARE_PENALTY, next NORMAL_START). An attacker entirely inside the opponent's
//    area, or touching the ball while partly inside -> foul, STOP, then (automatic) the defenders' free
//    kick where the ball is.
//  * no progress: the ball not moved 0.05 m for the division's `timeout` while running ->
//    kNoProgressInGame, STOP, then FORCE_START after stop_duration (automatic).
//  * restart timeouts (game settings, rules 5.3): a kickoff's ball is in play kickoff_timeout after
//    NORMAL_START, a free kick's free_kick_timeout after the command, kicked or not (no command changes;
//    current_action_time_remaining counts down to it). A penalty still undecided penalty_timeout after
//    NORMAL_START failed: kPenaltyKickFailed, STOP, goal kick (free kick) for the defenders.
//  * keep-out (defender too close to the kick point): in STOP every robot, during a kickoff, penalty
//    preparation or free kick (before the ball is in play) the other team's robots, must keep `radius`
//    between their nearest side and the ball. Inside for `violation_persistence` -> one foul per stay
//    (foul_counter +1); the command does not change.
//  * placement interference: during a placement the other team keeps `radius` from the stadium ball ->
//    target; inside for `violation_persistence` -> BOT_INTERFERED_PLACEMENT, a foul, `extra_time` more for
//    the placing team.
//  * fouls (builtin_referee_fouls.cpp; each rule its own profile section, numbers of the rules 13.3-13.6):
//    while running, non-stopping: crash (unique / drawn), kick too fast; stopping (STOP, then the other
//    team's free kick where the ball was, placed first when it is not a legal spot): double touch,
//    dribbling too far, keeper holding the ball, too many robots; after the ball left the field, a ball
//    seen beyond the walls within kBoundaryCrossingWindow is also a boundary crossing (a foul of the last
//    toucher, the free kick stays the other team's). In STOP: too fast. In STOP and free kicks before the
//    ball is in play: too close to the opponent's defense area. A non-stopping foul is raised again for the
//    same robots only after kFoulRepeat. Robot speeds are the observation's or estimated over
//    kSpeedBaseline.
//  * cards: every fouls_per_card-th foul of a team -> MULTIPLE_FOULS and a yellow card (max_allowed_bots
//    one lower for yellow_card_duration of playing time); a third concurrent one is a red card.
// game_events holds the events since the ball was last in play, each with a unique id "builtin-<n>".
//
// Stages, as the Game Controller runs them: NORMAL_FIRST_HALF_PRE -> (NORMAL_START / FORCE_START)
// NORMAL_FIRST_HALF -> (half_duration of playing time) NORMAL_HALF_TIME with HALT -> (half_time)
// NORMAL_SECOND_HALF_PRE with STOP and the other team's kickoff pending -> NORMAL_SECOND_HALF ->
// POST_GAME with HALT. With extra_time enabled and a draw: EXTRA_TIME_BREAK (HALT) -> EXTRA_FIRST_HALF_PRE
// -> EXTRA_FIRST_HALF -> EXTRA_HALF_TIME -> EXTRA_SECOND_HALF_PRE -> EXTRA_SECOND_HALF, and if still
// drawn PENALTY_SHOOTOUT_BREAK -> PENALTY_SHOOTOUT: penalties in turn (the first half's kickoff team
// first), shootout_penalties each, then sudden death, until one team leads after equal turns or can no
// longer be caught; then POST_GAME. The teams change sides (blue_team_on_positive_half flips) on entering
// every *_PRE stage after the first and the shoot-out. The halves' clock runs only while the game runs
// (NORMAL_START, FORCE_START, DIRECT_FREE_*), as the Game Controller's does; the breaks' clock runs
// always. next_stage() advances by hand with the same effects.
//
//   BuiltinReferee referee(*load_referee_profile("strict_ai"), FieldGeometry::division_b(),
//                          {.yellow = {"ER-Force", 0}, .blue = {"TIGERs", 1}, .max_allowed_bots = 6});
//   referee.command(Command::kStop, wall.now());
//   referee.step(observation_from(frame), wall.now());   // each vision frame
//   publish(referee.state());
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "libs/domain/division.h"
#include "libs/domain/field.h"
#include "libs/domain/rules.h"
#include "libs/common/result.h"
#include "libs/common/team.h"
#include "libs/geometry/vec2.h"
#include "libs/time/time.h"
#include "services/referee_gateway/builtin/profile.h"
#include "services/referee_gateway/core/types.h"

namespace ssl::referee {

struct TeamSetup {
  std::string name;
  std::uint32_t goalkeeper = 0;
};

struct MatchSetup {
  TeamSetup yellow;
  TeamSetup blue;
  Division division = Division::kB;  // the rules' division-dependent timers
  std::uint32_t max_allowed_bots = 6;  // per team: 11 in division A, 6 in division B
  bool blue_on_positive_half = kBlueOnPositiveHalfAtStart;  // blue defends the goal at +x (first half)
};

/// One vision frame as the referee needs it (SSL-Vision global frame, m, m/s).
struct ObservedRobot {
  TeamColor team = TeamColor::kYellow;
  std::uint32_t id = 0;  // 0..15 (vision patterns); others are ignored
  geom::Vec2 position = geom::Vec2::Zero();
  std::optional<geom::Vec2> velocity;  // m/s; absent: estimated from successive positions (over 0.1 s)
};

struct Observation {
  std::optional<geom::Vec2> ball_position;  // absent when the ball is not seen
  std::optional<geom::Vec2> ball_velocity;  // absent: estimated from successive positions
  std::vector<ObservedRobot> robots;
};

/// Inputs that were ignored, by reason (for system.health). Nothing is dropped without a count.
struct InputCounters {
  std::uint64_t observations = 0;         // step() calls accepted
  std::uint64_t time_went_backwards = 0;  // step() / command() with `now` before the previous one
  std::uint64_t missing_ball = 0;         // observations without a ball
  std::uint64_t invalid_ball = 0;         // NaN / infinite ball position or velocity (that value ignored)
  std::uint64_t invalid_robot = 0;        // NaN / infinite robot position
  std::uint64_t unknown_robot_id = 0;     // id above 15
  std::uint64_t duplicate_robot = 0;      // same team and id twice in one observation (first one kept)
  std::uint64_t rejected_commands = 0;    // operator commands refused (see command())
};

class BuiltinReferee {
 public:
  static constexpr std::uint32_t kMaxRobotId = 15;
  static constexpr double kTouchMargin = 0.02;     // m beyond robot + ball radius that counts as touch
  static constexpr double kDeflectionSpeed = 1.5;  // m/s change between observations: the ball hit something
  static constexpr double kInPlayDistance = rules::kInPlayDistance;  // m a kicked ball moves: in play
  static constexpr double kSpeedBaseline = 0.1;    // s over which an unmeasured ball speed is estimated
  static constexpr double kBallAtRestSpeed = 0.1;  // m/s
  static constexpr double kPlacementHold = 0.5;    // s the placed ball must stay placed and at rest
  static constexpr std::uint32_t kTimeoutsPerTeam = 4;
  static constexpr double kTimeoutBudget = 300;              // s per team
  static constexpr std::uint32_t kMaxPlacementFailures = 5;  // then the team may no longer place
  static constexpr double kRestartDefenseAreaDistance = rules::kRestartDefenseAreaDistance;  // m, the ball
  static constexpr double kFoulRepeat = rules::kFoulRepeat;  // s before a non-stopping foul is raised again
  static constexpr double kBoundaryCrossingWindow = 1.0;    // s after the ball left the field
  static constexpr double kCrashContactMargin = 0.01;       // m beyond two robot radii that counts as contact
  static constexpr double kDribblingReachMargin = 0.01;     // m beyond robot + ball radius: in the dribbler

  /// Starts in NORMAL_FIRST_HALF_PRE with HALT and the profile's kickoff as next_command (issued after a
  /// STOP by itself with auto_continue). The first step() or command() stamps the initial command time.
  BuiltinReferee(RefereeProfile profile, FieldGeometry field, MatchSetup match = {});

  /// One vision observation at `now` (Unix wall clock). Bad values are ignored and counted.
  void step(const Observation& observation, time::Timestamp now);

  /// An operator command at `now`. BALL_PLACEMENT_* needs a finite `designated_position` (m); other
  /// commands ignore it. Refused (error, counted, state unchanged): GOAL_* and INDIRECT_FREE_*
  /// (deprecated), values outside the enum, a placement without a valid target.
  Status command(Command command, time::Timestamp now, std::optional<geom::Vec2> designated_position = {});

  /// Picks a match up from `saved`, the last state this referee sent before its process ended (the
  /// service's state file), at `now`; before the first step(). Kept: the stage and its time left, both
  /// teams' info (score, cards and their clocks, fouls, timeouts, placement failures), the sides and the
  /// command counter. Started afresh: what the rules track between observations (touches, foul timers,
  /// the shoot-out's turns). The play goes on with one new command (reason "resumed after a restart of
  /// the referee"): HALT and a timeout stay as they were; a stoppage keeps its pending restart (a
  /// preparation becomes STOP with it pending, to be prepared again); a ball in play or a restart under way
  /// becomes STOP with FORCE_START pending; each automatic when the profile continues by itself (the ball
  /// is checked first, as before every FORCE_START). POST_GAME stays over (HALT).
  void resume(const RefereeState& saved, time::Timestamp now);

  /// Which goal blue defends (the referee swaps it by itself at half time). Not a new command.
  void set_blue_on_positive_half(bool blue_on_positive_half);

  /// Advances to the next stage by hand (see the header comment); an error in POST_GAME.
  Status next_stage(time::Timestamp now);

  const RefereeState& state() const { return state_; }
  const InputCounters& counters() const { return counters_; }
  /// True while the ball is in play (rules are judged).
  bool game_running() const { return phase_ == Phase::kRunning; }
  const RefereeProfile& profile() const { return profile_; }
  const FieldGeometry& field() const { return field_; }

 private:
  enum class Phase { kHalted, kStopped, kPlacing, kPreparing, kKickPending, kRunning, kTimeout };

  /// A command change with everything it brings; the one input of apply().
  struct Transition {
    Command command = Command::kHalt;
    std::optional<Command> next_command;
    std::optional<geom::Vec2> designated_position;
    bool next_is_automatic = false;  // STOP: issue next_command after stop_duration
    int placement_attempt = 0;       // BALL_PLACEMENT: 1 the first team, 2 the other after a failure
    bool awaiting_hand_placement = false;  // STOP: nobody places; the restart waits for the ball
    std::string reason;              // status_message
  };

  struct Touch {
    TeamColor team;
    std::uint32_t id;
  };

  struct CleanObservation {
    std::optional<geom::Vec2> ball;
    std::optional<double> ball_speed;  // m/s, measured or estimated from the previous position
    /// m/s, measured, or the displacement since the previous observation (noisy: used for deflections)
    std::optional<geom::Vec2> ball_velocity;
    std::vector<ObservedRobot> robots;
    /// The robot touching the ball in this observation: in reach now (toucher), or the one the ball
    /// bounced off since the previous observation (deflected_by).
    std::optional<Touch> touch;
    /// The touch is a robot in reach now (toucher), not one read off a change of the ball's velocity.
    bool touch_in_reach = false;
  };

  // The state machine's one transition function.
  void apply(const Transition& transition, time::Timestamp now);
  void enter_stage(Stage stage, time::Timestamp now);
  void start_running();
  /// Advances the clocks to `now` and stamps the packet; the first call also stamps the initial command.
  void begin(time::Timestamp now);
  Transition standard_transition(Command command, std::optional<geom::Vec2> designated_position,
                                 std::string reason) const;
  /// The command a resumed match goes on with (see resume()).
  Transition resumption(const RefereeState& saved) const;

  CleanObservation clean(const Observation& observation, time::Timestamp now);
  /// The robot touching the ball now: the nearest with centres within robot + ball radius + `margin`.
  std::optional<Touch> toucher(const CleanObservation& observation, double margin) const;
  /// The robot a fast ball bounced off between two observations (a contact shorter than their interval):
  /// the ball's velocity changed by more than kDeflectionSpeed, and the robot nearest the path it was on
  /// from `from` (the previous position, for `interval` s) is within touching distance of that path.
  std::optional<Touch> deflected_by(const CleanObservation& observation, const geom::Vec2& from,
                                    double interval) const;
  /// A team's own defense area, SSL-Vision frame.
  geom::Rectangle defense_area_of(TeamColor defending_team) const;
  void track_kick(const CleanObservation& observation);
  void update_last_touch(const CleanObservation& observation);

  // Rules: each returns the transition it decides (or nothing) and raises its events.
  std::optional<Transition> judge_running(const CleanObservation& observation, time::Timestamp now);
  std::optional<Transition> judge_ball_left_field(const geom::Vec2& ball, time::Timestamp now);
  std::optional<Transition> judge_defense_areas(const CleanObservation& observation, time::Timestamp now);
  std::optional<Transition> judge_placement(const CleanObservation& observation, time::Timestamp now);
  std::optional<Transition> judge_progress(const CleanObservation& observation, time::Timestamp now);
  std::optional<Transition> judge_kick_timeout(const CleanObservation& observation, time::Timestamp now);
  std::optional<Transition> automatic_continuation(const CleanObservation& observation, time::Timestamp now);
  /// Where the ball must be placed before `restart` can be issued (nullopt: it may be issued now).
  std::optional<geom::Vec2> placement_needed_for(Command restart, const std::optional<geom::Vec2>& ball) const;
  /// BALL_PLACEMENT before `restart` (by `placer`, else the restart's team, else the team that did not touch
  /// the ball last), or STOP until the ball is placed by hand when no team may place.
  Transition placement_before(Command restart, const geom::Vec2& target, bool restart_is_automatic,
                              std::optional<TeamColor> placer = std::nullopt) const;
  bool robots_ready_for_kickoff(const CleanObservation& observation) const;
  /// s the current kick-pending restart may wait for its kick (kickoff, free kick, penalty).
  double restart_timeout() const;
  /// A penalty's end (goal, failure, ball out): the shoot-out's next turn or the match's end, or nothing
  /// outside the shoot-out.
  std::optional<Transition> after_shootout_penalty(time::Timestamp now);
  bool match_decided_early() const;
  void judge_keep_out(const CleanObservation& observation, time::Timestamp now);

  // Fouls (builtin_referee_fouls.cpp).
  void estimate_robot_velocities(CleanObservation& observation, time::Timestamp now);
  std::optional<Transition> judge_running_fouls(const CleanObservation& observation, time::Timestamp now);
  void judge_crashes(const CleanObservation& observation, time::Timestamp now);
  void judge_ball_speed(const CleanObservation& observation, time::Timestamp now);
  std::optional<Transition> judge_double_touch(const CleanObservation& observation, time::Timestamp now);
  std::optional<Transition> judge_dribbling(const CleanObservation& observation, time::Timestamp now);
  std::optional<Transition> judge_keeper_held_ball(const CleanObservation& observation, time::Timestamp now);
  std::optional<Transition> judge_robot_count(const CleanObservation& observation, time::Timestamp now);
  void judge_boundary_crossing(const CleanObservation& observation, time::Timestamp now);
  void judge_stop_speed(const CleanObservation& observation, time::Timestamp now);
  void judge_defense_area_distance(const CleanObservation& observation, time::Timestamp now);
  void judge_placement_interference(const CleanObservation& observation, time::Timestamp now);
  /// STOP, then the other team's free kick where the ball was (placed first if that is no legal spot).
  Transition free_kick_after_foul(TeamColor offender, const std::optional<geom::Vec2>& ball,
                                  const std::string& reason) const;
  /// The nearest spot to `p` where a free kick may be taken (line_distance inside the lines, away from the
  /// defense areas); `p` itself when it is one.
  geom::Vec2 legal_free_kick_spot(const geom::Vec2& p) const;
  /// A non-stopping foul `key` may be raised now (not raised within kFoulRepeat before).
  bool may_raise_again(const std::string& key, time::Timestamp now);
  /// Cards for the team of a foul just counted.
  void book(TeamColor team, time::Timestamp now);
  /// Yellow cards count down with the playing time; expired ones give the robot back.
  void run_card_clocks(time::Duration elapsed);

  Transition free_kick_after_ball_left(TeamColor kicking_team, const geom::Vec2& placement_point,
                                       const std::string& reason) const;
  Transition after_goal(TeamColor conceding_team) const;
  void raise(GameEvent event, time::Timestamp now, bool is_foul);

  TeamInfo& team_info(TeamColor team);
  const TeamInfo& team_info(TeamColor team) const;
  double goal_x_of(TeamColor defending_team) const;  // +-field_length/2
  TeamColor defender_of_goal_at(double x) const;     // the team defending the goal on x's side
  geom::Vec2 penalty_mark_against(TeamColor defending_team) const;

  RefereeProfile profile_;
  FieldGeometry field_;
  Division division_;
  RefereeState state_;
  InputCounters counters_;

  Phase phase_ = Phase::kHalted;
  bool automatic_next_ = false;
  std::optional<TeamColor> executing_team_;  // kicker / placer of the current restart
  std::optional<time::Timestamp> last_now_;
  time::Timestamp command_since_;
  std::uint64_t event_sequence_ = 0;

  std::optional<geom::Vec2> last_ball_;  // latest valid ball position
  std::optional<time::Timestamp> last_ball_time_;
  std::optional<geom::Vec2> last_ball_velocity_;  // m/s, of the latest observation with a ball
  // Ball speed without a measured velocity: the displacement from a reference at least kSpeedBaseline old.
  std::optional<std::pair<geom::Vec2, time::Timestamp>> speed_reference_;
  std::optional<double> estimated_ball_speed_;  // m/s
  std::optional<geom::Vec2> kick_reference_ball_;        // where the ball was when the kick command came
  std::optional<geom::Vec2> ball_inside_since_running_;  // last in-field ball position while running
  std::optional<Touch> last_touch_;
  std::optional<geom::Vec2> progress_ball_;  // running: where the ball rests since progress_since_
  time::Timestamp progress_since_;
  std::optional<time::Timestamp> last_goal_;

  int placement_attempt_ = 0;                          // 1: first team, 2: the other team after a failure
  bool awaiting_hand_placement_ = false;  // both teams failed: no automatic placement until a restart
  std::optional<TeamColor> penalty_kicker_;  // from a penalty's NORMAL_START until it is decided
  // Shoot-out: penalties taken and scored per team (index: TeamColor).
  std::uint32_t shootout_taken_[2] = {0, 0};
  std::uint32_t shootout_scored_[2] = {0, 0};
  std::optional<time::Timestamp> placement_ok_since_;  // ball placed and at rest since

  // Keep-out: since when each robot (team, id) has been too close, and whether it was already reported.
  std::map<std::pair<TeamColor, std::uint32_t>, std::pair<time::Timestamp, bool>> keep_out_since_;
  // The same for placement interference and the distance to the opponent's defense area.
  std::map<std::pair<TeamColor, std::uint32_t>, std::pair<time::Timestamp, bool>> interference_since_;
  std::map<std::pair<TeamColor, std::uint32_t>, std::pair<time::Timestamp, bool>> area_distance_since_;
  double placement_extra_time_ = 0;  // s added to the current placement's time by interference fouls

  // Fouls: robot speeds over a baseline, repeats, and what each stopping rule tracks.
  std::map<std::pair<TeamColor, std::uint32_t>, std::pair<geom::Vec2, time::Timestamp>> robot_speed_reference_;
  std::map<std::pair<TeamColor, std::uint32_t>, geom::Vec2> robot_velocity_;
  std::map<std::string, time::Timestamp> last_raised_;
  std::set<std::pair<TeamColor, std::uint32_t>> too_fast_in_stop_;  // reported in this STOP
  bool ball_too_fast_ = false;  // the current kick was reported
  struct KickerWatch {  // double touch: the kicker of the restart now in play
    Touch kicker;
    geom::Vec2 kick_point;
    bool released = false;  // it was out of contact since
  };
  std::optional<KickerWatch> kicker_watch_;
  struct Dribble {
    Touch robot;
    geom::Vec2 start;
  };
  std::optional<Dribble> dribble_;
  std::optional<std::pair<TeamColor, time::Timestamp>> ball_in_own_area_since_;
  std::optional<time::Timestamp> too_many_since_[2];  // by TeamColor index
  std::optional<std::pair<time::Timestamp, std::optional<Touch>>> ball_left_field_;  // when, last toucher
  bool boundary_crossing_raised_ = false;
};

}  // namespace ssl::referee
