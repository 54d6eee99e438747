// Team play of the base strategy (seeds/001), below the coach: the roles of the coach's style assigned to the
// field players, the one main play (a dynamic pass, or the attacker's shot / clearance / challenge) and every
// other robot's role default (wingers and support open up, defenders block shooting lanes, markers stay
// goal-side of the most dangerous opponents, never two on one). Plain functions of the tick's Situation and
// the team's TeamPlayMemory (the blackboard: style, roles, pass intent, formation positions), called by the
// planner's tree (planner.cpp). All positions in the TEAM frame.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "services/planner/core/assignment.h"
#include "services/planner/core/coach.h"
#include "services/planner/core/plays.h"

namespace ssl::planner {

/// A pass the team is playing: the passer kicks to `point`, where the receiver takes it.
struct PassIntent {
  enum class Phase { kSetUp, kInFlight };
  std::uint32_t passer = 0;
  std::uint32_t receiver = 0;
  Vec2 point = Vec2::Zero();
  Phase phase = Phase::kSetUp;
  double since = 0;  // s (Situation::now) the phase began
  std::optional<double> ball_at_passer;  // s the ball last touched the passer's dribbler (set-up)
  std::optional<double> ball_at_robot;   // s the ball was last within reach of any robot (in flight)
  bool one_touch = false;  // the receiver shoots the ball on at their goal with its first touch (redirect)
};

/// Our restart as a set play (seeds/001), chosen on the restart's first tick: a free kick passed to a
/// teammate who shoots it on at the first touch, from where the goal is more open than from the ball; a
/// kickoff passed to a teammate waiting in our half.
struct RestartPlay {
  double since = 0;       // s (Situation::now) of the restart's first tick
  double last_tick = 0;   // s of its last tick: a gap means a new restart
  bool shoot = false;     // no set play (none rated, or it could not be set up in time): the straight shot
};

/// A teammate rated as the receiver of a pass from the ball.
struct PassOption {
  std::uint32_t receiver = 0;
  Vec2 point = Vec2::Zero();
  double score = 0;          // higher is better (see rate_passes)
  double margin = 0;         // s the ball is ahead of the quickest opponent to its line
  double open_angle = 0;     // rad between the pass line and the nearest opponent in front of the receiver
  double progress = 0;       // m towards their goal
  double receiver_shot = 0;  // shot_quality at the point
};

struct TeamPlayParams {
  double arrival_speed = 1.5;        // m/s a pass arrives at the receiver with (what receive controls)
  double min_pass = 0.8;             // m
  double max_pass = 5.5;             // m
  double min_margin = 0.2;           // s the ball must be ahead of every opponent along its line
  double keep_margin = -0.1;         // s: a pass being set up is called off below this (hysteresis)
  double min_open_angle = 0.17;      // rad (10 degrees)
  double min_lane_clearance = 0.1;   // m between every opponent's body and the ball's path (as it stands now)
  double opponent_speed = 2.5;       // m/s an opponent reaches the line at, at most
  double opponent_acceleration = 3.0;  // m/s^2 it gets there with, from standing
  double opponent_reaction = 0.2;    // s before it turns towards the ball's line (it drifts meanwhile)
  double shoot_quality = 0.45;       // a shot at least this good is taken rather than a pass
  double pass_advantage = 0.1;       // a pass must score this much above the shot from the ball
  double turn_cost = 0.6;            // score lost by a pass straight back from where the attacker comes
  double set_up_timeout = 2.5;       // s for the passer to kick
  double flight_timeout = 3.5;       // s for the ball to reach the receiver
  double contested_distance = 0.4;   // m, opponent centre to ball: the ball is challenged, not shot
  double hold_below = 0.45;          // attacking, a shot worse than this is not taken: the ball is kept
  double hold_pass_turn = 0.3;       // rad: a held ball is passed once the holder faces the pass this well
  // s the attacker keeps the ball at most (hold_below); then it is played on as when nothing is kept. Held
  // under a challenge the ball does not move, and past the rules' no-progress time (5 s in division A, 10 s
  // in B) the referee restarts it there, again and again (3 times in a row in match_test's second half).
  double max_hold = 4.0;
  // The free kick's set play (RestartPlay).
  double redirect_arrival_speed = 2.5;  // m/s the pass arrives at the redirecting teammate with
  double redirect_max_angle = 0.8;      // rad between the pass coming back and the shot going on
  double redirect_min_pass = 1.0;       // m
  double redirect_max_pass = 3.5;       // m
  double redirect_advantage = 0.15;     // the shot from the point must be this much better than from the ball
  double redirect_min_shot = 0.35;      // and at least this good
  double redirect_max_reach = 3.0;      // s for the receiver to get to its spot, at most
  double redirect_set_up_timeout = 4.0; // s from the restart's first tick to the kick, else the straight shot
  // The kickoff's set play (RestartPlay).
  double kickoff_set_up_timeout = 3.0;  // s from NORMAL_START to the kick, else the straight shot
};

/// What the team's strategy remembers between ticks (the blackboard of seeds/001).
struct TeamPlayMemory {
  explicit TeamPlayMemory(double hysteresis = 0.3) : roles(hysteresis), attacker(hysteresis) {}

  TeamPlayParams params;
  Coach coach;
  GameReading reading;
  Style style = Style::kContestBall;
  std::optional<PassIntent> pass;
  std::optional<RestartPlay> restart;
  StableAssigner roles;
  StableChoice attacker;
  std::array<std::optional<Role>, wm::kMaxRobotsPerTeam> role_of{};    // each robot's role this tick
  std::array<Vec2, wm::kMaxRobotsPerTeam> formation{};                // each robot's role position
  std::array<std::optional<std::uint32_t>, wm::kMaxRobotsPerTeam> marked{};  // the opponent it marks
  std::optional<double> last_tick;  // s (Situation::now) of the last strategy tick
  // The attacker keeping the ball (its id) and since when (s, Situation::now); reset when it plays it on.
  std::optional<std::pair<std::uint32_t, double>> keeping;
};

/// How good a shot at their goal is from `from` (0..1): the widest open part of the mouth (1 at 0.25 rad or
/// more) times the distance (1 up to 2 m, 0 from 4.5 m: farther shots seldom score).
double shot_quality(const Situation& s, const Vec2& from, std::optional<std::uint32_t> shooter = std::nullopt);

/// Every teammate of `passer` (not the keeper) that a pass from the ball can reach, best first. Rejected:
/// shorter than min_pass or longer than max_pass, back to within 1 m of our defense area, an opponent that could reach the ball's line before the
/// ball (min_margin), stands within min_open_angle of it in front of the receiver or within
/// min_lane_clearance of the ball's path. Score: the receiver's
/// shot quality, progress towards their goal and the margin.
std::vector<PassOption> rate_passes(const Situation& s, std::uint32_t passer, const TeamPlayParams& params = {});
/// One pass from the ball to `point` for `receiver`, rated as rate_passes does; nullopt when rejected.
std::optional<PassOption> rate_pass(const Situation& s, std::uint32_t receiver, const Vec2& point,
                                    const TeamPlayParams& params = {});

/// The free kick's best one-touch pass from the ball for a field player other than `passer` and the keeper
/// (its receiver the one quickest to the point): the point is reachable in redirect_max_reach, outside their
/// defense area with the free kick's distance, redirect_min_pass..redirect_max_pass from the ball; the pass
/// rates as rate_pass rates it (at redirect_arrival_speed) and turns at most redirect_max_angle towards the
/// open part of their goal. PassOption::receiver_shot is the shot quality from the point; nullopt when no
/// point is better than the straight shot by redirect_advantage.
std::optional<PassOption> rate_redirect(const Situation& s, std::uint32_t passer, const TeamPlayParams& params = {});
/// The free kick's pass (FreeKickPlay::kPass) where no one-touch pass rates: when the straight shot is poor
/// (below shoot_quality), the best of rate_passes that beats it by pass_advantage and whose point keeps the
/// free kick's distance from their defense area; nullopt otherwise (the straight shot).
std::optional<PassOption> rate_free_kick_pass(const Situation& s, std::uint32_t passer,
                                              const TeamPlayParams& params = {});

// ---- the base strategy's steps (planner.cpp's tree calls them in this order) ----------------------------
/// The coach reads the game and decides the style.
void read_game(const Situation& s, TeamPlayMemory& m);
/// The keeper, the attacker (the field player quickest to the ball, stable; the pass's receiver when a pass
/// flies) and every other field player's role of the style with its default intent. Returns the attacker.
std::optional<std::uint32_t> assign_roles(const Situation& s, TeamPlayMemory& m, TeamIntents& out);
/// True while a pass is being played (updates its phase; ends it when taken, lost or late).
bool pass_in_progress(const Situation& s, TeamPlayMemory& m);
/// The passer's kick (set-up phase) and the receiver's reception: the seeds' Parallel "dynamic pass".
void pass_ball(const Situation& s, TeamPlayMemory& m, TeamIntents& out);
void receive_pass(const Situation& s, TeamPlayMemory& m, TeamIntents& out);
/// Our free kick in the base strategy, after the free kick play (plays.h) gave the kicker its straight shot:
/// on the restart's first tick the set play is chosen (rate_redirect); its receiver goes to the point and
/// waits there, kicker armed, and the kicker passes once the receiver is in place. With FreeKickPlay::kPass
/// and no one-touch pass rated, a pass to a teammate where it stands (rate_free_kick_pass), kicked at once.
/// The pass is the strategy's pass intent: once the ball is in play the dynamic pass goes on with it.
void free_kick_set_play(const Situation& s, TeamPlayMemory& m, TeamIntents& out);
/// Our kickoff in the base strategy, after the kickoff play gave the kicker its straight shot: once the
/// kickoff may be taken (the kickoff play names the kicker, Situation::restart_kicker), the kicker passes to
/// the teammate rate_passes rates best of those waiting in our half (the kickoff's wings beside the centre
/// circle), who takes it where it stands; the pass is the strategy's pass intent, which goes on as a dynamic
/// pass once the ball is in play. With no pass rated, or none kicked within kickoff_set_up_timeout, the
/// straight shot stands.
void kickoff_set_play(const Situation& s, TeamPlayMemory& m, TeamIntents& out);
/// The attacker in the coach's style: shoots when the shot is good, starts a pass when one is clearly
/// better, clears in a clearance, challenges the carrier when they have the ball. With a shot that would give
/// the ball away (below hold_below; not on the edge of their defense area) and a teammate within a pass's
/// length, it keeps the ball on its dribbler instead (building up at once, otherwise when no pass rates
/// better now), turned towards the most nearly open teammate (or its back to the nearest opponent), and
/// passes to any teammate a pass rates for once it faces the pass.
void attack(const Situation& s, TeamPlayMemory& m, std::uint32_t attacker, TeamIntents& out);
/// The attacker keeping the ball (see attack): takes it on its dribbler, turns, passes.
void hold_ball(const Situation& s, TeamPlayMemory& m, const wm::RobotState& robot, TeamIntents& out);

}  // namespace ssl::planner
