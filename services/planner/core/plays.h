// Plays: what the team does in each game situation, as motion intents for every robot. The tree's
// actions (planner.cpp) call these; they are plain functions of the tick's Situation and the team's
// PlayMemory (stable role choices, the placement phase), so they can be tested on their own.
//
// Roles, tactics, skills (seeds/001): a play (e.g. "our_free_kick") fills formation slots, each slot a
// role ("kicker", "wall", "defender", "support", "goalkeeper"); the tactic names the team-level behaviour
// the role belongs to; the skill is what the robot executes ("move_to", "approach_ball", "kick",
// "dribble_to", "halt"). The goalkeeper named by the referee always keeps its role (except in HALT).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "libs/time/time.h"
#include "services/planner/core/assignment.h"
#include "services/planner/core/motion.h"
#include "services/planner/core/planner.h"
#include "libs/domain/team_field.h"
#include "libs/domain/game_state.h"
#include "libs/domain/world.h"

namespace ssl::planner {

/// Everything a play reads in one tick (TEAM frame).
struct Situation {
  const PlannerConfig* config = nullptr;
  wm::Field field;
  const wm::GameState* game = nullptr;
  bool ball_known = false;
  Vec2 ball = Vec2::Zero();  // the field centre when unknown
  Vec2 ball_velocity = Vec2::Zero();
  std::optional<wm::RefereeCommand> next_command;
  bool we_are_blue = true;
  bool can_place_ball = true;
  std::optional<Vec2> placement_target;    // designated position, team frame
  std::span<const wm::RobotState> robots;  // our visible robots (id < 16), by id
  std::span<const wm::RobotState> enemies;
  std::optional<std::uint32_t> keeper;  // the referee's goalkeeper id, when visible
  Zones zones;                          // the base zones of this tick
  wm::Possession possession = wm::Possession::kNone;  // world_model's reading
  std::optional<std::uint32_t> possessing_robot;      // of the possessing team
  double now = 0;                                      // s, the tick's time (only differences matter)
  std::optional<std::uint32_t> restart_kicker;         // PlayMemory::restart_kicker: not to touch the ball
  double ball_at_rest_for = 0;  // s the ball has lain (below kBallAtRestSpeed, within kBallAtRestDrift)
};

/// The ball lies at rest below this speed (m/s) and while it stays within this distance (m) of where it
/// came to rest (Situation::ball_at_rest_for).
constexpr double kBallAtRestSpeed = 0.1;
constexpr double kBallAtRestDrift = 0.05;

/// What the team remembers between ticks for stable decisions.
struct PlayMemory {
  // Approach the ball from behind (seen from the target), carry it there, let it go. A ball too near a
  // wall to be approached from behind is first pulled back: taken from the field side, then dribbled
  // backwards away from the wall (kPullBack), released, and placed as usual.
  enum class PlacePhase { kApproach, kCarry, kRelease, kPullBack };

  explicit PlayMemory(double hysteresis = 0.3)
      : assigner(hysteresis), kicker(hysteresis), placer(hysteresis) {}

  StableAssigner assigner;
  StableChoice kicker;  // kickoff / penalty / free kick taker and the attacker in normal play
  StableChoice placer;
  PlacePhase place_phase = PlacePhase::kApproach;
  std::array<std::uint32_t, wm::kMaxRobotsPerTeam> wander_leg{};  // play_wander: each robot's waypoint
  std::optional<std::uint32_t> current_placer;
  // Our restart's kicker once it may kick: it must not touch the ball again before another robot did (double
  // touch). Cleared by the planner when another robot touches the ball or play stops.
  std::optional<std::uint32_t> restart_kicker;
  // Robots leaving the field for a card (substitution.h), ascending; sticky from tick to tick.
  std::vector<std::uint32_t> leaving;
  // Where and since when (Situation::now) the ball lies at rest; nullopt while it moves or is unknown.
  std::optional<std::pair<Vec2, double>> ball_rest;
};

/// The intents of the whole team for one tick, indexed by robot id.
struct TeamIntents {
  std::string_view play = "none";
  std::array<MotionIntent, wm::kMaxRobotsPerTeam> robots{};
};

// ---- the plays (each fills `out` for every robot in `s.robots`) ----------------------------------------
void play_halt(const Situation& s, TeamIntents& out);
/// The wander strategy: each robot drives to a waypoint of its own (a fixed pseudo-random sequence per
/// robot id, inside the field and clear of both defense areas) and takes the next one on arrival.
void play_wander(const Situation& s, PlayMemory& memory, TeamIntents& out);
/// The ball_chaser strategy, the baseline to beat: the referee's goalkeeper guards the goal; every other
/// robot runs for the ball, and the one nearest to it shoots at the goal (no passes, no positions).
void play_ball_chaser(const Situation& s, PlayMemory& memory, TeamIntents& out);
/// STOP (and GOAL): keep the STOP limits, pre-positioning for `s.next_command`.
void play_stop(const Situation& s, PlayMemory& memory, TeamIntents& out, std::string_view play = "stop");
void play_timeout(const Situation& s, PlayMemory& memory, TeamIntents& out);
void play_our_ball_placement(const Situation& s, PlayMemory& memory, TeamIntents& out);
void play_their_ball_placement(const Situation& s, PlayMemory& memory, TeamIntents& out);
void play_our_kickoff(const Situation& s, PlayMemory& memory, TeamIntents& out);
void play_their_kickoff(const Situation& s, PlayMemory& memory, TeamIntents& out);
void play_our_penalty(const Situation& s, PlayMemory& memory, TeamIntents& out);
void play_their_penalty(const Situation& s, PlayMemory& memory, TeamIntents& out);
void play_our_free_kick(const Situation& s, PlayMemory& memory, TeamIntents& out);
void play_their_free_kick(const Situation& s, PlayMemory& memory, TeamIntents& out);

// ---- shared by the strategies (team_play.h: the base strategy's steps) ----------------------------------
/// The goalkeeper in normal play: clears a slow ball at our defense area (true: no field player may go for
/// it), else guards the goal.
bool strategy_goalkeeper(const Situation& s, TeamIntents& out);
/// An active intent at the robot's full speed, under `tactic`; and one within STOP's limits (speed, ball
/// distance with our margin).
MotionIntent base_intent(const Situation& s, std::string_view tactic);
MotionIntent stop_intent(const Situation& s, std::string_view tactic);
/// Writes robot `id`'s intent, its target moved out of the tick's zones.
void write_intent(const Situation& s, TeamIntents& out, std::uint32_t id, const MotionIntent& intent);
/// The base strategy's penalty (PenaltyPlay::kAdvance), from NORMAL_START until a new command ends it (the
/// rules let its attacker touch the ball again): a ball out of shot range (0.8 m beyond their defense area)
/// is played on towards a spot 0.4 m in front of the area, and the kicker runs with it, closing on it without
/// a kick, until it is in range; then the shot as hard as the rules allow at the open part of the goal, from
/// close in, where the keeper has a fraction of the time to react. A ball that stops out of range is played
/// on again.
MotionIntent penalty_attack(const Situation& s, const wm::RobotState& kicker);
/// The attacker's shot: the shoot skill (it gets behind the ball, then kicks at the open part of the goal).
void strategy_approach(const Situation& s, std::uint32_t attacker, TeamIntents& out);

/// Whether a robot other than our kicker may stand at `p` before our kickoff is in play: in our half and out
/// of the centre circle, its whole body with our keep-away margin (keep_kickoff_legal moves targets there).
bool legal_before_our_kickoff(const Situation& s, const Vec2& p);

/// Robot state by id, nullptr if not visible.
const wm::RobotState* find_robot(const Situation& s, std::uint32_t id);

}  // namespace ssl::planner
