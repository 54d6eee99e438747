// The coach: the top of the base strategy (seeds/001). Each tick it reads the game from the situation
// (possession, the third the ball is in, the team's momentum, the numbers around the ball) and picks the
// team's style of play, with hysteresis so that it does not flicker; each style has its team mode (attacking,
// defending, contesting) and its set of field-player roles, by priority. Pure and deterministic: time comes
// in the situation.
//
//   Coach coach;
//   const GameReading reading = coach.read(situation);
//   const Style style = coach.decide(reading, situation.now);   // roles_of(style), mode_of(style)
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "libs/domain/world.h"
#include "services/planner/core/plays.h"

namespace ssl::planner {

enum class TeamMode { kAttacking, kDefending, kContesting };

/// The finer modes: how the team plays within its mode.
enum class Style {
  kBuildUpAttack,       // ours, in our half or midfield: pass forward, wingers and support open up
  kHighPressureAttack,  // ours, in their third: shoot when open, wingers near the goal
  kHoldPossession,      // ours, outnumbered around the ball: keep it, short safe passes
  kClearance,           // ours, in our third and outnumbered: get it away from our goal
  kScrambleDefence,     // theirs (or loose), in our third: everybody back, lanes blocked, danger marked
  kPressBall,           // theirs, elsewhere: press the carrier, mark the receivers
  kContestBall,         // loose ball: win it
};

enum class Third { kOurs, kMiddle, kTheirs };

/// A field player's job (the goalkeeper is the referee's, apart).
enum class Role {
  kGoalie,
  kAttacker,         // has or goes for the ball: shoots or passes
  kReceiver,         // the pass's target
  kWinger,           // wide and ahead of the ball: a pass option near their goal
  kMidfieldSupport,  // beside and behind the ball: a safe pass option
  kDefender,         // blocks a shooting lane in front of our defense area
  kMarker,           // stays goal-side of one dangerous opponent (one marker per opponent)
  kPresser,          // challenges the opponent with the ball
};

std::string_view to_string(TeamMode mode);
std::string_view to_string(Style style);
std::string_view to_string(Role role);

/// What the game analysis reads in one tick.
struct GameReading {
  wm::Possession possession = wm::Possession::kNone;
  Third ball_third = Third::kMiddle;
  double momentum = 0;  // -1..1: the ball's recent drift towards their goal (+) or ours (-)
  int advantage = 0;    // our robots minus theirs within CoachParams::advantage_radius of the ball
};

struct CoachParams {
  double switch_delay = 0.3;      // s a new style must be asked for before the team switches
  double advantage_radius = 1.5;  // m around the ball where numbers count
  double momentum_time = 2.0;     // s, the momentum's time constant
  double momentum_speed = 2.0;    // m/s of the ball towards a goal that is a momentum of 1
};

TeamMode mode_of(Style style);
/// The style `reading` asks for (no hysteresis).
Style style_for(const GameReading& reading);
/// The field players' roles in `style`, by priority; a team with more field players than roles repeats the
/// last ones (support and marking).
std::span<const Role> roles_of(Style style);

class Coach {
 public:
  explicit Coach(CoachParams params = {}) : params_(params) {}

  /// Reads the game (updates the momentum).
  GameReading read(const Situation& s);
  /// The style after hysteresis: a new one once it was asked for switch_delay in a row (at once when the
  /// team has none yet, or for a scramble defence: danger does not wait).
  Style decide(const GameReading& reading, double now);

  std::optional<Style> style() const { return style_; }

 private:
  CoachParams params_;
  double momentum_ = 0;
  std::optional<double> last_read_;
  std::optional<Style> style_;
  std::optional<Style> candidate_;
  double candidate_since_ = 0;
};

}  // namespace ssl::planner
