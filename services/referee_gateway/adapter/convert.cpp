#include "services/referee_gateway/adapter/convert.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace ssl::referee {
namespace {

namespace idl = ::ssl::idl;

constexpr std::int64_t kMaxMicros = std::numeric_limits<std::int64_t>::max() / 1000;

/// µs (signed) -> Duration, saturating at the int64 ns range.
time::Duration micros(std::int64_t us) {
  if (us > kMaxMicros) return time::Duration::max();
  if (us < -kMaxMicros) return time::Duration::min();
  return time::Duration(us * 1000);
}

/// Unix µs (unsigned, from the wire) -> Timestamp, saturating.
time::Timestamp unix_micros(std::uint64_t us) {
  if (us > static_cast<std::uint64_t>(kMaxMicros)) return time::Timestamp::max();
  return time::Timestamp::from_microseconds(static_cast<std::int64_t>(us));
}

std::optional<double> finite(bool has, float value) {
  if (!has || !std::isfinite(value)) return std::nullopt;
  return static_cast<double>(value);
}

std::optional<std::uint32_t> bot(bool has, std::uint32_t id) {
  if (!has) return std::nullopt;
  return id;
}

/// A game-event location (already metres).
std::optional<Vec2> location(bool has, const ::Vector2& point) {
  if (!has || !std::isfinite(point.x()) || !std::isfinite(point.y())) return std::nullopt;
  return Vec2(point.x(), point.y());
}

Team team_of(::Team team) {
  switch (team) {
    case ::YELLOW: return Team::kYellow;
    case ::BLUE: return Team::kBlue;
    default: return Team::kUnknown;
  }
}

Command command_of(::Referee::Command command) {
  const int value = static_cast<int>(command);
  return value >= 0 && value < kCommandCount ? static_cast<Command>(value) : Command::kHalt;
}

Stage stage_of(::Referee::Stage stage) {
  const int value = static_cast<int>(stage);
  return value >= 0 && value < kStageCount ? static_cast<Stage>(value) : Stage::kNormalFirstHalfPre;
}

MatchType match_type_of(::MatchType type) {
  switch (type) {
    case ::GROUP_PHASE: return MatchType::kGroupPhase;
    case ::ELIMINATION_PHASE: return MatchType::kEliminationPhase;
    case ::FRIENDLY: return MatchType::kFriendly;
    default: return MatchType::kUnknown;
  }
}

HullColor hull_color_of(::HullColor color) {
  switch (color) {
    case ::HULL_COLOR_DARK: return HullColor::kDark;
    case ::HULL_COLOR_LIGHT: return HullColor::kLight;
    default: return HullColor::kUnknown;
  }
}

// One filler per payload message; the type is set by the caller from the oneof case.

using Pb = ::GameEvent;

void fill(const Pb::BallLeftField& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
}

void fill(const Pb::AimlessKick& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.secondary_location = location(p.has_kick_location(), p.kick_location());
}

void fill(const Pb::Goal& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_kicking_bot(), p.kicking_bot());
  e.location = location(p.has_location(), p.location());
  e.secondary_location = location(p.has_kick_location(), p.kick_location());
  e.value = finite(p.has_max_ball_height(), p.max_ball_height());
  e.text = p.message();
}

void fill(const Pb::IndirectGoal& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.secondary_location = location(p.has_kick_location(), p.kick_location());
}

void fill(const Pb::ChippedGoal& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.secondary_location = location(p.has_kick_location(), p.kick_location());
  e.value = finite(p.has_max_ball_height(), p.max_ball_height());
}

void fill(const Pb::BotTooFastInStop& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.value = finite(p.has_speed(), p.speed());
}

void fill(const Pb::DefenderTooCloseToKickPoint& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.value = finite(p.has_distance(), p.distance());
}

void fill(const Pb::BotCrashDrawn& p, GameEvent& e) {
  e.by_team = Team::kUnknown;
  e.by_bot = bot(p.has_bot_yellow(), p.bot_yellow());
  e.other_bot = bot(p.has_bot_blue(), p.bot_blue());
  e.location = location(p.has_location(), p.location());
  e.value = finite(p.has_crash_speed(), p.crash_speed());
}

void fill(const Pb::BotCrashUnique& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_violator(), p.violator());
  e.other_bot = bot(p.has_victim(), p.victim());
  e.location = location(p.has_location(), p.location());
  e.value = finite(p.has_crash_speed(), p.crash_speed());
}

void fill(const Pb::BotPushedBot& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_violator(), p.violator());
  e.other_bot = bot(p.has_victim(), p.victim());
  e.location = location(p.has_location(), p.location());
  e.value = finite(p.has_pushed_distance(), p.pushed_distance());
}

void fill(const Pb::BotTippedOver& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.secondary_location = location(p.has_ball_location(), p.ball_location());
}

void fill(const Pb::BotDroppedParts& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.secondary_location = location(p.has_ball_location(), p.ball_location());
}

void fill(const Pb::DefenderInDefenseArea& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.value = finite(p.has_distance(), p.distance());
}

void fill(const Pb::DefenderInDefenseAreaPartially& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.secondary_location = location(p.has_ball_location(), p.ball_location());
  e.value = finite(p.has_distance(), p.distance());
}

void fill(const Pb::AttackerTouchedBallInDefenseArea& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.value = finite(p.has_distance(), p.distance());
}

void fill(const Pb::BotKickedBallTooFast& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.value = finite(p.has_initial_ball_speed(), p.initial_ball_speed());
  if (p.chipped()) e.text = "chipped";
}

void fill(const Pb::BotDribbledBallTooFar& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_start(), p.start());
  e.secondary_location = location(p.has_end(), p.end());
}

void fill(const Pb::AttackerTouchedOpponentInDefenseArea& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.other_bot = bot(p.has_victim(), p.victim());
  e.location = location(p.has_location(), p.location());
}

void fill(const Pb::AttackerDoubleTouchedBall& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
}

void fill(const Pb::AttackerTooCloseToDefenseArea& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.secondary_location = location(p.has_ball_location(), p.ball_location());
  e.value = finite(p.has_distance(), p.distance());
}

void fill(const Pb::BotHeldBallDeliberately& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
  e.value = finite(p.has_duration(), p.duration());
}

void fill(const Pb::BotInterferedPlacement& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.by_bot = bot(p.has_by_bot(), p.by_bot());
  e.location = location(p.has_location(), p.location());
}

void fill(const Pb::MultipleCards& p, GameEvent& e) { e.by_team = team_of(p.by_team()); }

void fill(const Pb::MultipleFouls& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  if (p.caused_game_events_size() == 0) return;
  e.text = "caused by: ";
  bool first = true;
  for (const auto& caused : p.caused_game_events()) {
    if (!first) e.text += ", ";
    first = false;
    e.text += to_string(game_event_type(caused));
  }
}

void fill(const Pb::MultiplePlacementFailures& p, GameEvent& e) { e.by_team = team_of(p.by_team()); }

void fill(const Pb::KickTimeout& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.location = location(p.has_location(), p.location());
  e.value = finite(p.has_time(), p.time());
}

void fill(const Pb::NoProgressInGame& p, GameEvent& e) {
  e.by_team = Team::kUnknown;
  e.location = location(p.has_location(), p.location());
  e.value = finite(p.has_time(), p.time());
}

void fill(const Pb::PlacementFailed& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.value = finite(p.has_remaining_distance(), p.remaining_distance());
}

void fill(const Pb::UnsportingBehaviorMinor& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.text = p.reason();
}

void fill(const Pb::UnsportingBehaviorMajor& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.text = p.reason();
}

void fill(const Pb::KeeperHeldBall& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.location = location(p.has_location(), p.location());
  e.value = finite(p.has_duration(), p.duration());
}

void fill(const Pb::PlacementSucceeded& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.value = finite(p.has_time_taken(), p.time_taken());
}

void fill(const Pb::Prepared& p, GameEvent& e) {
  e.by_team = Team::kUnknown;
  e.value = finite(p.has_time_taken(), p.time_taken());
}

void fill(const Pb::BotSubstitution& p, GameEvent& e) { e.by_team = team_of(p.by_team()); }
void fill(const Pb::ExcessiveBotSubstitution& p, GameEvent& e) { e.by_team = team_of(p.by_team()); }
void fill(const Pb::ChallengeFlag& p, GameEvent& e) { e.by_team = team_of(p.by_team()); }
void fill(const Pb::EmergencyStop& p, GameEvent& e) { e.by_team = team_of(p.by_team()); }

void fill(const Pb::ChallengeFlagHandled& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.text = p.accepted() ? "accepted" : "rejected";
}

void fill(const Pb::TooManyRobots& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.secondary_location = location(p.has_ball_location(), p.ball_location());
  if (p.has_num_robots_on_field() || p.has_num_robots_allowed()) {
    e.text = std::to_string(p.num_robots_on_field()) + " on field, " +
             std::to_string(p.num_robots_allowed()) + " allowed";
  }
}

void fill(const Pb::BoundaryCrossing& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.location = location(p.has_location(), p.location());
}

void fill(const Pb::PenaltyKickFailed& p, GameEvent& e) {
  e.by_team = team_of(p.by_team());
  e.location = location(p.has_location(), p.location());
  e.text = p.reason();
}

/// The type and payload of one event, by its oneof case. Returns false when no case is set.
bool fill_payload(const ::GameEvent& in, GameEvent& e) {
  using T = GameEventType;
  switch (in.event_case()) {
    case Pb::kBallLeftFieldTouchLine:
      e.type = T::kBallLeftFieldTouchLine;
      fill(in.ball_left_field_touch_line(), e);
      break;
    case Pb::kBallLeftFieldGoalLine:
      e.type = T::kBallLeftFieldGoalLine;
      fill(in.ball_left_field_goal_line(), e);
      break;
    case Pb::kAimlessKick:
      e.type = T::kAimlessKick;
      fill(in.aimless_kick(), e);
      break;
    case Pb::kAttackerTooCloseToDefenseArea:
      e.type = T::kAttackerTooCloseToDefenseArea;
      fill(in.attacker_too_close_to_defense_area(), e);
      break;
    case Pb::kDefenderInDefenseArea:
      e.type = T::kDefenderInDefenseArea;
      fill(in.defender_in_defense_area(), e);
      break;
    case Pb::kBoundaryCrossing:
      e.type = T::kBoundaryCrossing;
      fill(in.boundary_crossing(), e);
      break;
    case Pb::kKeeperHeldBall:
      e.type = T::kKeeperHeldBall;
      fill(in.keeper_held_ball(), e);
      break;
    case Pb::kBotDribbledBallTooFar:
      e.type = T::kBotDribbledBallTooFar;
      fill(in.bot_dribbled_ball_too_far(), e);
      break;
    case Pb::kBotPushedBot:
      e.type = T::kBotPushedBot;
      fill(in.bot_pushed_bot(), e);
      break;
    case Pb::kBotHeldBallDeliberately:
      e.type = T::kBotHeldBallDeliberately;
      fill(in.bot_held_ball_deliberately(), e);
      break;
    case Pb::kBotTippedOver:
      e.type = T::kBotTippedOver;
      fill(in.bot_tipped_over(), e);
      break;
    case Pb::kBotDroppedParts:
      e.type = T::kBotDroppedParts;
      fill(in.bot_dropped_parts(), e);
      break;
    case Pb::kAttackerTouchedBallInDefenseArea:
      e.type = T::kAttackerTouchedBallInDefenseArea;
      fill(in.attacker_touched_ball_in_defense_area(), e);
      break;
    case Pb::kBotKickedBallTooFast:
      e.type = T::kBotKickedBallTooFast;
      fill(in.bot_kicked_ball_too_fast(), e);
      break;
    case Pb::kBotCrashUnique:
      e.type = T::kBotCrashUnique;
      fill(in.bot_crash_unique(), e);
      break;
    case Pb::kBotCrashDrawn:
      e.type = T::kBotCrashDrawn;
      fill(in.bot_crash_drawn(), e);
      break;
    case Pb::kDefenderTooCloseToKickPoint:
      e.type = T::kDefenderTooCloseToKickPoint;
      fill(in.defender_too_close_to_kick_point(), e);
      break;
    case Pb::kBotTooFastInStop:
      e.type = T::kBotTooFastInStop;
      fill(in.bot_too_fast_in_stop(), e);
      break;
    case Pb::kBotInterferedPlacement:
      e.type = T::kBotInterferedPlacement;
      fill(in.bot_interfered_placement(), e);
      break;
    case Pb::kExcessiveBotSubstitution:
      e.type = T::kExcessiveBotSubstitution;
      fill(in.excessive_bot_substitution(), e);
      break;
    case Pb::kPossibleGoal:
      e.type = T::kPossibleGoal;
      fill(in.possible_goal(), e);
      break;
    case Pb::kGoal:
      e.type = T::kGoal;
      fill(in.goal(), e);
      break;
    case Pb::kInvalidGoal:
      e.type = T::kInvalidGoal;
      fill(in.invalid_goal(), e);
      break;
    case Pb::kAttackerDoubleTouchedBall:
      e.type = T::kAttackerDoubleTouchedBall;
      fill(in.attacker_double_touched_ball(), e);
      break;
    case Pb::kPlacementSucceeded:
      e.type = T::kPlacementSucceeded;
      fill(in.placement_succeeded(), e);
      break;
    case Pb::kPenaltyKickFailed:
      e.type = T::kPenaltyKickFailed;
      fill(in.penalty_kick_failed(), e);
      break;
    case Pb::kNoProgressInGame:
      e.type = T::kNoProgressInGame;
      fill(in.no_progress_in_game(), e);
      break;
    case Pb::kPlacementFailed:
      e.type = T::kPlacementFailed;
      fill(in.placement_failed(), e);
      break;
    case Pb::kMultipleCards:
      e.type = T::kMultipleCards;
      fill(in.multiple_cards(), e);
      break;
    case Pb::kMultipleFouls:
      e.type = T::kMultipleFouls;
      fill(in.multiple_fouls(), e);
      break;
    case Pb::kBotSubstitution:
      e.type = T::kBotSubstitution;
      fill(in.bot_substitution(), e);
      break;
    case Pb::kTooManyRobots:
      e.type = T::kTooManyRobots;
      fill(in.too_many_robots(), e);
      break;
    case Pb::kChallengeFlag:
      e.type = T::kChallengeFlag;
      fill(in.challenge_flag(), e);
      break;
    case Pb::kChallengeFlagHandled:
      e.type = T::kChallengeFlagHandled;
      fill(in.challenge_flag_handled(), e);
      break;
    case Pb::kEmergencyStop:
      e.type = T::kEmergencyStop;
      fill(in.emergency_stop(), e);
      break;
    case Pb::kUnsportingBehaviorMinor:
      e.type = T::kUnsportingBehaviorMinor;
      fill(in.unsporting_behavior_minor(), e);
      break;
    case Pb::kUnsportingBehaviorMajor:
      e.type = T::kUnsportingBehaviorMajor;
      fill(in.unsporting_behavior_major(), e);
      break;
    case Pb::kPrepared:
      e.type = T::kPrepared;
      fill(in.prepared(), e);
      break;
    case Pb::kIndirectGoal:
      e.type = T::kIndirectGoal;
      fill(in.indirect_goal(), e);
      break;
    case Pb::kChippedGoal:
      e.type = T::kChippedGoal;
      fill(in.chipped_goal(), e);
      break;
    case Pb::kKickTimeout:
      e.type = T::kKickTimeout;
      fill(in.kick_timeout(), e);
      break;
    case Pb::kAttackerTouchedOpponentInDefenseArea:
      e.type = T::kAttackerTouchedOpponentInDefenseArea;
      fill(in.attacker_touched_opponent_in_defense_area(), e);
      break;
    case Pb::kAttackerTouchedOpponentInDefenseAreaSkipped:
      e.type = T::kAttackerTouchedOpponentInDefenseAreaSkipped;
      fill(in.attacker_touched_opponent_in_defense_area_skipped(), e);
      break;
    case Pb::kBotCrashUniqueSkipped:
      e.type = T::kBotCrashUniqueSkipped;
      fill(in.bot_crash_unique_skipped(), e);
      break;
    case Pb::kBotPushedBotSkipped:
      e.type = T::kBotPushedBotSkipped;
      fill(in.bot_pushed_bot_skipped(), e);
      break;
    case Pb::kDefenderInDefenseAreaPartially:
      e.type = T::kDefenderInDefenseAreaPartially;
      fill(in.defender_in_defense_area_partially(), e);
      break;
    case Pb::kMultiplePlacementFailures:
      e.type = T::kMultiplePlacementFailures;
      fill(in.multiple_placement_failures(), e);
      break;
    case Pb::EVENT_NOT_SET: return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------------------
// Core -> wire (to_proto): the inverse of the decoding above.

constexpr double kMaxFloat = std::numeric_limits<float>::max();

/// A double for a float field of the wire, saturating at +-FLT_MAX (the caller has dropped NaN).
float saturated_float(double value) { return static_cast<float>(std::clamp(value, -kMaxFloat, kMaxFloat)); }

/// Duration -> µs, truncated toward zero (always in range: ns / 1000).
std::int64_t to_micros(time::Duration duration) {
  return std::chrono::duration_cast<std::chrono::microseconds>(duration).count();
}

/// Duration -> µs for the uint32 fields, saturating at 0 and 2^32 - 1 µs.
std::uint32_t to_uint32_micros(time::Duration duration) {
  constexpr std::int64_t kMax = std::numeric_limits<std::uint32_t>::max();
  return static_cast<std::uint32_t>(std::clamp<std::int64_t>(to_micros(duration), 0, kMax));
}

/// Timestamp -> Unix µs (uint64), truncated; times before the epoch saturate at 0.
std::uint64_t to_unix_micros(time::Timestamp t) {
  return t.nanoseconds() < 0 ? 0 : static_cast<std::uint64_t>(t.microseconds());
}

/// A number slot for a float field; nullopt (not sent) when absent, NaN or infinite.
std::optional<float> wire_float(const std::optional<double>& slot) {
  if (!slot || !std::isfinite(*slot)) return std::nullopt;
  return saturated_float(*slot);
}

/// A location slot (m) for a Vector2 field (m); nullopt (not sent) when absent or not finite.
std::optional<::Vector2> wire_location(const std::optional<Vec2>& slot) {
  if (!slot || !std::isfinite(slot->x()) || !std::isfinite(slot->y())) return std::nullopt;
  ::Vector2 point;
  point.set_x(saturated_float(slot->x()));
  point.set_y(saturated_float(slot->y()));
  return point;
}

// The core enums below have the league's values; a value outside the enum becomes the league's default.

::Team wire_team(Team team) {
  const int value = static_cast<int>(team);
  return ::Team_IsValid(value) ? static_cast<::Team>(value) : ::UNKNOWN;
}

::Referee::Command wire_command(Command command) {
  const int value = static_cast<int>(command);
  return ::Referee::Command_IsValid(value) ? static_cast<::Referee::Command>(value) : ::Referee::HALT;
}

::Referee::Stage wire_stage(Stage stage) {
  const int value = static_cast<int>(stage);
  return ::Referee::Stage_IsValid(value) ? static_cast<::Referee::Stage>(value)
                                         : ::Referee::NORMAL_FIRST_HALF_PRE;
}

::MatchType wire_match_type(MatchType type) {
  const int value = static_cast<int>(type);
  return ::MatchType_IsValid(value) ? static_cast<::MatchType>(value) : ::UNKNOWN_MATCH;
}

::HullColor wire_hull_color(HullColor color) {
  const int value = static_cast<int>(color);
  return ::HullColor_IsValid(value) ? static_cast<::HullColor>(value) : ::HULL_COLOR_UNKNOWN;
}

/// Removes `literal` from the front of `text`; false (text unchanged) when `text` does not start with it.
bool consume(std::string_view& text, std::string_view literal) {
  if (!text.starts_with(literal)) return false;
  text.remove_prefix(literal.size());
  return true;
}

/// Reads a decimal int32 from the front of `text`; false when there is none or it is out of range.
bool consume_int(std::string_view& text, std::int32_t& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{}) return false;
  text.remove_prefix(static_cast<std::size_t>(end - text.data()));
  return true;
}

// One filler per payload message, the inverse of the fill() above: slots -> payload fields. Every
// `required` field is set.

void fill_wire(const GameEvent& e, Pb::BallLeftField& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
}

void fill_wire(const GameEvent& e, Pb::AimlessKick& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto loc = wire_location(e.secondary_location)) *p.mutable_kick_location() = *loc;
}

void fill_wire(const GameEvent& e, Pb::Goal& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_kicking_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto loc = wire_location(e.secondary_location)) *p.mutable_kick_location() = *loc;
  if (auto height = wire_float(e.value)) p.set_max_ball_height(*height);
  if (!e.text.empty()) p.set_message(e.text);
}

void fill_wire(const GameEvent& e, Pb::IndirectGoal& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto loc = wire_location(e.secondary_location)) *p.mutable_kick_location() = *loc;
}

void fill_wire(const GameEvent& e, Pb::ChippedGoal& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto loc = wire_location(e.secondary_location)) *p.mutable_kick_location() = *loc;
  if (auto height = wire_float(e.value)) p.set_max_ball_height(*height);
}

void fill_wire(const GameEvent& e, Pb::BotTooFastInStop& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto speed = wire_float(e.value)) p.set_speed(*speed);
}

void fill_wire(const GameEvent& e, Pb::DefenderTooCloseToKickPoint& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto distance = wire_float(e.value)) p.set_distance(*distance);
}

void fill_wire(const GameEvent& e, Pb::BotCrashDrawn& p) {  // no by_team on the wire
  if (e.by_bot) p.set_bot_yellow(*e.by_bot);
  if (e.other_bot) p.set_bot_blue(*e.other_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto speed = wire_float(e.value)) p.set_crash_speed(*speed);
}

void fill_wire(const GameEvent& e, Pb::BotCrashUnique& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_violator(*e.by_bot);
  if (e.other_bot) p.set_victim(*e.other_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto speed = wire_float(e.value)) p.set_crash_speed(*speed);
}

void fill_wire(const GameEvent& e, Pb::BotPushedBot& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_violator(*e.by_bot);
  if (e.other_bot) p.set_victim(*e.other_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto distance = wire_float(e.value)) p.set_pushed_distance(*distance);
}

void fill_wire(const GameEvent& e, Pb::BotTippedOver& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto loc = wire_location(e.secondary_location)) *p.mutable_ball_location() = *loc;
}

void fill_wire(const GameEvent& e, Pb::BotDroppedParts& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto loc = wire_location(e.secondary_location)) *p.mutable_ball_location() = *loc;
}

void fill_wire(const GameEvent& e, Pb::DefenderInDefenseArea& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto distance = wire_float(e.value)) p.set_distance(*distance);
}

void fill_wire(const GameEvent& e, Pb::DefenderInDefenseAreaPartially& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto loc = wire_location(e.secondary_location)) *p.mutable_ball_location() = *loc;
  if (auto distance = wire_float(e.value)) p.set_distance(*distance);
}

void fill_wire(const GameEvent& e, Pb::AttackerTouchedBallInDefenseArea& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto distance = wire_float(e.value)) p.set_distance(*distance);
}

void fill_wire(const GameEvent& e, Pb::BotKickedBallTooFast& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto speed = wire_float(e.value)) p.set_initial_ball_speed(*speed);
  p.set_chipped(e.text == "chipped");
}

void fill_wire(const GameEvent& e, Pb::BotDribbledBallTooFar& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto start = wire_location(e.location)) *p.mutable_start() = *start;
  if (auto end = wire_location(e.secondary_location)) *p.mutable_end() = *end;
}

void fill_wire(const GameEvent& e, Pb::AttackerTouchedOpponentInDefenseArea& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (e.other_bot) p.set_victim(*e.other_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
}

void fill_wire(const GameEvent& e, Pb::AttackerDoubleTouchedBall& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
}

void fill_wire(const GameEvent& e, Pb::AttackerTooCloseToDefenseArea& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto loc = wire_location(e.secondary_location)) *p.mutable_ball_location() = *loc;
  if (auto distance = wire_float(e.value)) p.set_distance(*distance);
}

void fill_wire(const GameEvent& e, Pb::BotHeldBallDeliberately& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto duration = wire_float(e.value)) p.set_duration(*duration);
}

void fill_wire(const GameEvent& e, Pb::BotInterferedPlacement& p) {
  p.set_by_team(wire_team(e.by_team));
  if (e.by_bot) p.set_by_bot(*e.by_bot);
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
}

void fill_wire(const GameEvent& e, Pb::MultipleCards& p) { p.set_by_team(wire_team(e.by_team)); }

/// text "caused by: A, B" -> one caused event per known league type name (its oneof member, `type` and
/// this event's by_team; the caused events' own slots are not carried).
void fill_wire(const GameEvent& e, Pb::MultipleFouls& p) {
  p.set_by_team(wire_team(e.by_team));
  std::string_view names = e.text;
  if (!consume(names, "caused by: ")) return;
  while (!names.empty()) {
    const std::size_t separator = names.find(", ");
    if (const auto caused_type = parse_game_event_type(names.substr(0, separator))) {
      GameEvent caused;
      caused.type = *caused_type;
      caused.by_team = e.by_team;
      *p.add_caused_game_events() = to_proto(caused);
    }
    if (separator == std::string_view::npos) break;
    names.remove_prefix(separator + 2);
  }
}

void fill_wire(const GameEvent& e, Pb::MultiplePlacementFailures& p) { p.set_by_team(wire_team(e.by_team)); }

void fill_wire(const GameEvent& e, Pb::KickTimeout& p) {
  p.set_by_team(wire_team(e.by_team));
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto time_s = wire_float(e.value)) p.set_time(*time_s);
}

void fill_wire(const GameEvent& e, Pb::NoProgressInGame& p) {  // no by_team on the wire
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto time_s = wire_float(e.value)) p.set_time(*time_s);
}

void fill_wire(const GameEvent& e, Pb::PlacementFailed& p) {
  p.set_by_team(wire_team(e.by_team));
  if (auto distance = wire_float(e.value)) p.set_remaining_distance(*distance);
}

void fill_wire(const GameEvent& e, Pb::UnsportingBehaviorMinor& p) {
  p.set_by_team(wire_team(e.by_team));
  p.set_reason(e.text);  // required
}

void fill_wire(const GameEvent& e, Pb::UnsportingBehaviorMajor& p) {
  p.set_by_team(wire_team(e.by_team));
  p.set_reason(e.text);  // required
}

void fill_wire(const GameEvent& e, Pb::KeeperHeldBall& p) {
  p.set_by_team(wire_team(e.by_team));
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (auto duration = wire_float(e.value)) p.set_duration(*duration);
}

void fill_wire(const GameEvent& e, Pb::PlacementSucceeded& p) {
  p.set_by_team(wire_team(e.by_team));
  if (auto time_taken = wire_float(e.value)) p.set_time_taken(*time_taken);
}

void fill_wire(const GameEvent& e, Pb::Prepared& p) {  // no by_team on the wire
  if (auto time_taken = wire_float(e.value)) p.set_time_taken(*time_taken);
}

void fill_wire(const GameEvent& e, Pb::BotSubstitution& p) { p.set_by_team(wire_team(e.by_team)); }
void fill_wire(const GameEvent& e, Pb::ExcessiveBotSubstitution& p) { p.set_by_team(wire_team(e.by_team)); }
void fill_wire(const GameEvent& e, Pb::ChallengeFlag& p) { p.set_by_team(wire_team(e.by_team)); }
void fill_wire(const GameEvent& e, Pb::EmergencyStop& p) { p.set_by_team(wire_team(e.by_team)); }

void fill_wire(const GameEvent& e, Pb::ChallengeFlagHandled& p) {
  p.set_by_team(wire_team(e.by_team));
  p.set_accepted(e.text == "accepted");  // required
}

/// text "<n> on field, <m> allowed" -> the two counts; other text is not sent.
void fill_wire(const GameEvent& e, Pb::TooManyRobots& p) {
  p.set_by_team(wire_team(e.by_team));
  if (auto loc = wire_location(e.secondary_location)) *p.mutable_ball_location() = *loc;
  std::string_view text = e.text;
  std::int32_t on_field = 0;
  std::int32_t allowed = 0;
  if (consume_int(text, on_field) && consume(text, " on field, ") && consume_int(text, allowed) &&
      consume(text, " allowed") && text.empty()) {
    p.set_num_robots_on_field(on_field);
    p.set_num_robots_allowed(allowed);
  }
}

void fill_wire(const GameEvent& e, Pb::BoundaryCrossing& p) {
  p.set_by_team(wire_team(e.by_team));
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
}

void fill_wire(const GameEvent& e, Pb::PenaltyKickFailed& p) {
  p.set_by_team(wire_team(e.by_team));
  if (auto loc = wire_location(e.location)) *p.mutable_location() = *loc;
  if (!e.text.empty()) p.set_reason(e.text);
}

/// The league `type` and the oneof member (with its payload) of one event. The Type constants are the
/// league's numbers, which differ from the oneof field numbers for several events.
void set_payload(const GameEvent& e, ::GameEvent& out) {
  using T = GameEventType;
  out.set_type(Pb::UNKNOWN_GAME_EVENT_TYPE);  // kUnknown and values outside the enum: no oneof member
  switch (e.type) {
    case T::kUnknown: break;
    case T::kBallLeftFieldTouchLine:
      out.set_type(Pb::BALL_LEFT_FIELD_TOUCH_LINE);
      fill_wire(e, *out.mutable_ball_left_field_touch_line());
      break;
    case T::kBallLeftFieldGoalLine:
      out.set_type(Pb::BALL_LEFT_FIELD_GOAL_LINE);
      fill_wire(e, *out.mutable_ball_left_field_goal_line());
      break;
    case T::kAimlessKick:
      out.set_type(Pb::AIMLESS_KICK);
      fill_wire(e, *out.mutable_aimless_kick());
      break;
    case T::kAttackerTooCloseToDefenseArea:
      out.set_type(Pb::ATTACKER_TOO_CLOSE_TO_DEFENSE_AREA);
      fill_wire(e, *out.mutable_attacker_too_close_to_defense_area());
      break;
    case T::kDefenderInDefenseArea:
      out.set_type(Pb::DEFENDER_IN_DEFENSE_AREA);
      fill_wire(e, *out.mutable_defender_in_defense_area());
      break;
    case T::kBoundaryCrossing:
      out.set_type(Pb::BOUNDARY_CROSSING);
      fill_wire(e, *out.mutable_boundary_crossing());
      break;
    case T::kKeeperHeldBall:
      out.set_type(Pb::KEEPER_HELD_BALL);
      fill_wire(e, *out.mutable_keeper_held_ball());
      break;
    case T::kBotDribbledBallTooFar:
      out.set_type(Pb::BOT_DRIBBLED_BALL_TOO_FAR);
      fill_wire(e, *out.mutable_bot_dribbled_ball_too_far());
      break;
    case T::kBotPushedBot:
      out.set_type(Pb::BOT_PUSHED_BOT);
      fill_wire(e, *out.mutable_bot_pushed_bot());
      break;
    case T::kBotHeldBallDeliberately:
      out.set_type(Pb::BOT_HELD_BALL_DELIBERATELY);
      fill_wire(e, *out.mutable_bot_held_ball_deliberately());
      break;
    case T::kBotTippedOver:
      out.set_type(Pb::BOT_TIPPED_OVER);
      fill_wire(e, *out.mutable_bot_tipped_over());
      break;
    case T::kBotDroppedParts:
      out.set_type(Pb::BOT_DROPPED_PARTS);
      fill_wire(e, *out.mutable_bot_dropped_parts());
      break;
    case T::kAttackerTouchedBallInDefenseArea:
      out.set_type(Pb::ATTACKER_TOUCHED_BALL_IN_DEFENSE_AREA);
      fill_wire(e, *out.mutable_attacker_touched_ball_in_defense_area());
      break;
    case T::kBotKickedBallTooFast:
      out.set_type(Pb::BOT_KICKED_BALL_TOO_FAST);
      fill_wire(e, *out.mutable_bot_kicked_ball_too_fast());
      break;
    case T::kBotCrashUnique:
      out.set_type(Pb::BOT_CRASH_UNIQUE);
      fill_wire(e, *out.mutable_bot_crash_unique());
      break;
    case T::kBotCrashDrawn:
      out.set_type(Pb::BOT_CRASH_DRAWN);
      fill_wire(e, *out.mutable_bot_crash_drawn());
      break;
    case T::kDefenderTooCloseToKickPoint:
      out.set_type(Pb::DEFENDER_TOO_CLOSE_TO_KICK_POINT);
      fill_wire(e, *out.mutable_defender_too_close_to_kick_point());
      break;
    case T::kBotTooFastInStop:
      out.set_type(Pb::BOT_TOO_FAST_IN_STOP);
      fill_wire(e, *out.mutable_bot_too_fast_in_stop());
      break;
    case T::kBotInterferedPlacement:
      out.set_type(Pb::BOT_INTERFERED_PLACEMENT);
      fill_wire(e, *out.mutable_bot_interfered_placement());
      break;
    case T::kExcessiveBotSubstitution:
      out.set_type(Pb::EXCESSIVE_BOT_SUBSTITUTION);
      fill_wire(e, *out.mutable_excessive_bot_substitution());
      break;
    case T::kPossibleGoal:
      out.set_type(Pb::POSSIBLE_GOAL);
      fill_wire(e, *out.mutable_possible_goal());
      break;
    case T::kGoal:
      out.set_type(Pb::GOAL);
      fill_wire(e, *out.mutable_goal());
      break;
    case T::kInvalidGoal:
      out.set_type(Pb::INVALID_GOAL);
      fill_wire(e, *out.mutable_invalid_goal());
      break;
    case T::kAttackerDoubleTouchedBall:
      out.set_type(Pb::ATTACKER_DOUBLE_TOUCHED_BALL);
      fill_wire(e, *out.mutable_attacker_double_touched_ball());
      break;
    case T::kPlacementSucceeded:
      out.set_type(Pb::PLACEMENT_SUCCEEDED);
      fill_wire(e, *out.mutable_placement_succeeded());
      break;
    case T::kPenaltyKickFailed:
      out.set_type(Pb::PENALTY_KICK_FAILED);
      fill_wire(e, *out.mutable_penalty_kick_failed());
      break;
    case T::kNoProgressInGame:
      out.set_type(Pb::NO_PROGRESS_IN_GAME);
      fill_wire(e, *out.mutable_no_progress_in_game());
      break;
    case T::kPlacementFailed:
      out.set_type(Pb::PLACEMENT_FAILED);
      fill_wire(e, *out.mutable_placement_failed());
      break;
    case T::kMultipleCards:
      out.set_type(Pb::MULTIPLE_CARDS);
      fill_wire(e, *out.mutable_multiple_cards());
      break;
    case T::kMultipleFouls:
      out.set_type(Pb::MULTIPLE_FOULS);
      fill_wire(e, *out.mutable_multiple_fouls());
      break;
    case T::kBotSubstitution:
      out.set_type(Pb::BOT_SUBSTITUTION);
      fill_wire(e, *out.mutable_bot_substitution());
      break;
    case T::kTooManyRobots:
      out.set_type(Pb::TOO_MANY_ROBOTS);
      fill_wire(e, *out.mutable_too_many_robots());
      break;
    case T::kChallengeFlag:
      out.set_type(Pb::CHALLENGE_FLAG);
      fill_wire(e, *out.mutable_challenge_flag());
      break;
    case T::kChallengeFlagHandled:
      out.set_type(Pb::CHALLENGE_FLAG_HANDLED);
      fill_wire(e, *out.mutable_challenge_flag_handled());
      break;
    case T::kEmergencyStop:
      out.set_type(Pb::EMERGENCY_STOP);
      fill_wire(e, *out.mutable_emergency_stop());
      break;
    case T::kUnsportingBehaviorMinor:
      out.set_type(Pb::UNSPORTING_BEHAVIOR_MINOR);
      fill_wire(e, *out.mutable_unsporting_behavior_minor());
      break;
    case T::kUnsportingBehaviorMajor:
      out.set_type(Pb::UNSPORTING_BEHAVIOR_MAJOR);
      fill_wire(e, *out.mutable_unsporting_behavior_major());
      break;
    case T::kPrepared:
      out.set_type(Pb::PREPARED);
      fill_wire(e, *out.mutable_prepared());
      break;
    case T::kIndirectGoal:
      out.set_type(Pb::INDIRECT_GOAL);
      fill_wire(e, *out.mutable_indirect_goal());
      break;
    case T::kChippedGoal:
      out.set_type(Pb::CHIPPED_GOAL);
      fill_wire(e, *out.mutable_chipped_goal());
      break;
    case T::kKickTimeout:
      out.set_type(Pb::KICK_TIMEOUT);
      fill_wire(e, *out.mutable_kick_timeout());
      break;
    case T::kAttackerTouchedOpponentInDefenseArea:
      out.set_type(Pb::ATTACKER_TOUCHED_OPPONENT_IN_DEFENSE_AREA);
      fill_wire(e, *out.mutable_attacker_touched_opponent_in_defense_area());
      break;
    case T::kAttackerTouchedOpponentInDefenseAreaSkipped:
      out.set_type(Pb::ATTACKER_TOUCHED_OPPONENT_IN_DEFENSE_AREA_SKIPPED);
      fill_wire(e, *out.mutable_attacker_touched_opponent_in_defense_area_skipped());
      break;
    case T::kBotCrashUniqueSkipped:
      out.set_type(Pb::BOT_CRASH_UNIQUE_SKIPPED);
      fill_wire(e, *out.mutable_bot_crash_unique_skipped());
      break;
    case T::kBotPushedBotSkipped:
      out.set_type(Pb::BOT_PUSHED_BOT_SKIPPED);
      fill_wire(e, *out.mutable_bot_pushed_bot_skipped());
      break;
    case T::kDefenderInDefenseAreaPartially:
      out.set_type(Pb::DEFENDER_IN_DEFENSE_AREA_PARTIALLY);
      fill_wire(e, *out.mutable_defender_in_defense_area_partially());
      break;
    case T::kMultiplePlacementFailures:
      out.set_type(Pb::MULTIPLE_PLACEMENT_FAILURES);
      fill_wire(e, *out.mutable_multiple_placement_failures());
      break;
  }
}

::GameEventProposalGroup proposal_group_to_proto(const GameEventProposal& proposal) {
  ::GameEventProposalGroup out;
  if (!proposal.id.empty()) out.set_id(proposal.id);
  for (const auto& event : proposal.events) *out.add_game_events() = to_proto(event);
  out.set_accepted(proposal.accepted);
  return out;
}

// ---------------------------------------------------------------------------------------------------------
// Core -> IDL

idl::common::Vec2 to_idl(const Vec2& v) {
  idl::common::Vec2 out;
  out.x(v.x());
  out.y(v.y());
  return out;
}

double seconds(time::Duration d) { return time::to_seconds(d); }

}  // namespace

GameEventType game_event_type(const ::GameEvent& event) {
  GameEvent scratch;
  if (event.event_case() != Pb::EVENT_NOT_SET) {
    fill_payload(event, scratch);
    return scratch.type;
  }
  if (!event.has_type()) return GameEventType::kUnknown;
  return parse_game_event_type(::GameEvent_Type_Name(event.type())).value_or(GameEventType::kUnknown);
}

GameEvent from_proto(const ::GameEvent& event) {
  GameEvent out;
  out.id = event.id();
  out.origins.assign(event.origin().begin(), event.origin().end());
  if (event.has_created_timestamp()) out.created_referee = unix_micros(event.created_timestamp());
  if (!fill_payload(event, out)) out.type = game_event_type(event);
  return out;
}

TeamInfo from_proto(const ::Referee::TeamInfo& team) {
  TeamInfo out;
  out.name = team.name();
  out.score = team.score();
  out.red_cards = team.red_cards();
  out.yellow_card_times_left.reserve(static_cast<std::size_t>(team.yellow_card_times_size()));
  for (std::uint32_t us : team.yellow_card_times()) out.yellow_card_times_left.push_back(micros(us));
  out.yellow_cards = team.yellow_cards();
  out.timeouts = team.timeouts();
  out.timeout_time_left = micros(team.timeout_time());
  out.goalkeeper = team.goalkeeper();
  out.foul_counter = team.foul_counter();
  out.ball_placement_failures = team.ball_placement_failures();
  out.can_place_ball = team.can_place_ball();
  out.max_allowed_bots = team.max_allowed_bots();
  out.bot_substitution_intent = team.bot_substitution_intent();
  out.ball_placement_failures_reached = team.ball_placement_failures_reached();
  out.bot_substitution_allowed = team.bot_substitution_allowed();
  out.bot_substitutions_left = team.bot_substitutions_left();
  out.bot_substitution_time_left = micros(team.bot_substitution_time_left());
  out.hull_color = hull_color_of(team.hull_color());
  return out;
}

RefereeState from_proto(const ::Referee& packet, time::Timestamp receive_wall, RefereeSource source) {
  RefereeState out;
  out.source = source;
  out.source_identifier = packet.source_identifier();
  out.match_type = match_type_of(packet.match_type());
  out.packet_referee = unix_micros(packet.packet_timestamp());
  out.receive_wall = receive_wall;
  out.stage = stage_of(packet.stage());
  if (packet.has_stage_time_left()) out.stage_time_left = micros(packet.stage_time_left());
  out.command = command_of(packet.command());
  out.command_counter = packet.command_counter();
  out.command_referee = unix_micros(packet.command_timestamp());
  out.yellow = from_proto(packet.yellow());
  out.blue = from_proto(packet.blue());
  if (packet.has_designated_position()) {
    const auto& point = packet.designated_position();
    if (std::isfinite(point.x()) && std::isfinite(point.y())) {
      out.designated_position = Vec2(point.x() / 1000.0, point.y() / 1000.0);  // mm -> m
    }
  }
  if (packet.has_blue_team_on_positive_half()) {
    out.blue_team_on_positive_half = packet.blue_team_on_positive_half();
  }
  if (packet.has_next_command()) out.next_command = command_of(packet.next_command());
  out.game_events.reserve(static_cast<std::size_t>(packet.game_events_size()));
  for (const auto& event : packet.game_events()) out.game_events.push_back(from_proto(event));
  out.game_event_proposals.reserve(static_cast<std::size_t>(packet.game_event_proposals_size()));
  for (const auto& group : packet.game_event_proposals()) {
    GameEventProposal proposal;
    proposal.id = group.id();
    proposal.accepted = group.accepted();
    proposal.events.reserve(static_cast<std::size_t>(group.game_events_size()));
    for (const auto& event : group.game_events()) proposal.events.push_back(from_proto(event));
    out.game_event_proposals.push_back(std::move(proposal));
  }
  if (packet.has_current_action_time_remaining()) {
    out.current_action_time_remaining = micros(packet.current_action_time_remaining());
  }
  out.status_message = packet.status_message();
  return out;
}

::GameEvent to_proto(const GameEvent& event) {
  ::GameEvent out;
  if (!event.id.empty()) out.set_id(event.id);
  for (const auto& origin : event.origins) out.add_origin(origin);
  if (event.created_referee) out.set_created_timestamp(to_unix_micros(*event.created_referee));
  set_payload(event, out);
  return out;
}

::Referee::TeamInfo to_proto(const TeamInfo& team) {
  ::Referee::TeamInfo out;
  out.set_name(team.name);
  out.set_score(team.score);
  out.set_red_cards(team.red_cards);
  for (const auto& left : team.yellow_card_times_left) out.add_yellow_card_times(to_uint32_micros(left));
  out.set_yellow_cards(team.yellow_cards);
  out.set_timeouts(team.timeouts);
  out.set_timeout_time(to_uint32_micros(team.timeout_time_left));
  out.set_goalkeeper(team.goalkeeper);
  out.set_foul_counter(team.foul_counter);
  out.set_ball_placement_failures(team.ball_placement_failures);
  out.set_can_place_ball(team.can_place_ball);
  out.set_max_allowed_bots(team.max_allowed_bots);
  out.set_bot_substitution_intent(team.bot_substitution_intent);
  out.set_ball_placement_failures_reached(team.ball_placement_failures_reached);
  out.set_bot_substitution_allowed(team.bot_substitution_allowed);
  out.set_bot_substitutions_left(team.bot_substitutions_left);
  out.set_bot_substitution_time_left(to_uint32_micros(team.bot_substitution_time_left));
  out.set_hull_color(wire_hull_color(team.hull_color));
  return out;
}

::Referee to_proto(const RefereeState& state) {
  ::Referee out;
  if (!state.source_identifier.empty()) out.set_source_identifier(state.source_identifier);
  out.set_match_type(wire_match_type(state.match_type));
  out.set_packet_timestamp(to_unix_micros(state.packet_referee));
  out.set_stage(wire_stage(state.stage));
  if (state.stage_time_left) out.set_stage_time_left(to_micros(*state.stage_time_left));
  out.set_command(wire_command(state.command));
  out.set_command_counter(state.command_counter);
  out.set_command_timestamp(to_unix_micros(state.command_referee));
  *out.mutable_yellow() = to_proto(state.yellow);
  *out.mutable_blue() = to_proto(state.blue);
  if (state.designated_position && std::isfinite(state.designated_position->x()) &&
      std::isfinite(state.designated_position->y())) {
    auto* point = out.mutable_designated_position();
    point->set_x(saturated_float(state.designated_position->x() * 1000.0));  // m -> mm
    point->set_y(saturated_float(state.designated_position->y() * 1000.0));
  }
  if (state.blue_team_on_positive_half) out.set_blue_team_on_positive_half(*state.blue_team_on_positive_half);
  if (state.next_command) out.set_next_command(wire_command(*state.next_command));
  for (const auto& event : state.game_events) *out.add_game_events() = to_proto(event);
  for (const auto& proposal : state.game_event_proposals) {
    *out.add_game_event_proposals() = proposal_group_to_proto(proposal);
  }
  if (state.current_action_time_remaining) {
    out.set_current_action_time_remaining(to_micros(*state.current_action_time_remaining));
  }
  if (!state.status_message.empty()) out.set_status_message(state.status_message);
  return out;
}

idl::referee::GameEvent to_idl(const GameEvent& event) {
  idl::referee::GameEvent out;
  out.id(event.id);
  out.type(static_cast<idl::referee::GameEventType>(static_cast<int>(event.type)));
  out.origins(event.origins);
  out.created_unix_ns(event.created_referee ? event.created_referee->nanoseconds() : 0);
  out.by_team(static_cast<idl::common::TeamColor>(static_cast<int>(event.by_team)));
  out.has_by_bot(event.by_bot.has_value());
  out.by_bot(event.by_bot.value_or(0));
  out.has_other_bot(event.other_bot.has_value());
  out.other_bot(event.other_bot.value_or(0));
  out.has_location(event.location.has_value());
  if (event.location) out.location(to_idl(*event.location));
  out.has_secondary_location(event.secondary_location.has_value());
  if (event.secondary_location) out.secondary_location(to_idl(*event.secondary_location));
  out.has_value(event.value.has_value());
  out.value(event.value.value_or(0.0));
  out.text(event.text);
  return out;
}

idl::referee::TeamInfo to_idl(const TeamInfo& team) {
  idl::referee::TeamInfo out;
  out.name(team.name);
  out.score(team.score);
  out.red_cards(team.red_cards);
  std::vector<double> card_times;
  card_times.reserve(team.yellow_card_times_left.size());
  for (const auto& left : team.yellow_card_times_left) card_times.push_back(seconds(left));
  out.yellow_card_times_left(std::move(card_times));
  out.yellow_cards(team.yellow_cards);
  out.timeouts(team.timeouts);
  out.timeout_time_left(seconds(team.timeout_time_left));
  out.goalkeeper(team.goalkeeper);
  out.foul_counter(team.foul_counter);
  out.ball_placement_failures(team.ball_placement_failures);
  out.can_place_ball(team.can_place_ball);
  out.max_allowed_bots(team.max_allowed_bots);
  out.bot_substitution_intent(team.bot_substitution_intent);
  out.ball_placement_failures_reached(team.ball_placement_failures_reached);
  out.bot_substitution_allowed(team.bot_substitution_allowed);
  out.bot_substitutions_left(team.bot_substitutions_left);
  out.bot_substitution_time_left(seconds(team.bot_substitution_time_left));
  out.hull_color(static_cast<idl::referee::HullColor>(static_cast<int>(team.hull_color)));
  return out;
}

idl::referee::RefereeState to_idl(const RefereeState& state) {
  idl::referee::RefereeState out;
  out.source(state.source == RefereeSource::kBuiltin ? idl::referee::REFEREE_SOURCE_BUILTIN
                                                     : idl::referee::REFEREE_SOURCE_GAME_CONTROLLER);
  out.source_identifier(state.source_identifier);
  out.match_type(static_cast<idl::referee::MatchType>(static_cast<int>(state.match_type)));
  out.packet_unix_ns(state.packet_referee.nanoseconds());
  out.receive_unix_ns(state.receive_wall.nanoseconds());
  out.stage(static_cast<idl::referee::Stage>(static_cast<int>(state.stage)));
  out.stage_time_left(state.stage_time_left ? seconds(*state.stage_time_left) : 0.0);
  out.command(static_cast<idl::referee::Command>(static_cast<int>(state.command)));
  out.command_counter(state.command_counter);
  out.command_unix_ns(state.command_referee.nanoseconds());
  out.yellow(to_idl(state.yellow));
  out.blue(to_idl(state.blue));
  out.has_designated_position(state.designated_position.has_value());
  if (state.designated_position) out.designated_position(to_idl(*state.designated_position));
  out.has_blue_team_on_positive_half(state.blue_team_on_positive_half.has_value());
  out.blue_team_on_positive_half(state.blue_team_on_positive_half.value_or(false));
  out.has_next_command(state.next_command.has_value());
  const Command next = state.next_command.value_or(Command::kHalt);
  out.next_command(static_cast<idl::referee::Command>(static_cast<int>(next)));
  std::vector<idl::referee::GameEvent> events;
  events.reserve(state.game_events.size());
  for (const auto& event : state.game_events) events.push_back(to_idl(event));
  out.game_events(std::move(events));
  std::vector<idl::referee::GameEventProposal> proposals;
  proposals.reserve(state.game_event_proposals.size());
  for (const auto& proposal : state.game_event_proposals) {
    idl::referee::GameEventProposal group;
    group.id(proposal.id);
    group.accepted(proposal.accepted);
    std::vector<idl::referee::GameEvent> group_events;
    group_events.reserve(proposal.events.size());
    for (const auto& event : proposal.events) group_events.push_back(to_idl(event));
    group.events(std::move(group_events));
    proposals.push_back(std::move(group));
  }
  out.game_event_proposals(std::move(proposals));
  out.has_current_action_time_remaining(state.current_action_time_remaining.has_value());
  out.current_action_time_remaining(
      state.current_action_time_remaining ? seconds(*state.current_action_time_remaining) : 0.0);
  out.status_message(state.status_message);
  return out;
}

idl::referee::RefereeEvent to_idl(const RefereeEvent& event) {
  idl::referee::RefereeEvent out;
  out.event(to_idl(event.event));
  out.command(static_cast<idl::referee::Command>(static_cast<int>(event.command)));
  out.command_counter(event.command_counter);
  out.receive_unix_ns(event.receive_wall.nanoseconds());
  return out;
}

}  // namespace ssl::referee

// ---------------------------------------------------------------------------------------------------------
// IDL -> core

namespace ssl::referee {
namespace {

/// `value` as the core enum E when it is within [0, last], else E{} (the first enumerator).
template <typename E>
E enum_in_range(int value, E last) {
  return value >= 0 && value <= static_cast<int>(last) ? static_cast<E>(value) : E{};
}

Vec2 from_idl(const idl::common::Vec2& v) { return {v.x(), v.y()}; }

}  // namespace

GameEvent from_idl(const idl::referee::GameEvent& event) {
  GameEvent out;
  out.id = event.id();
  out.type = enum_in_range(static_cast<int>(event.type()), GameEventType::kMultiplePlacementFailures);
  out.origins = event.origins();
  if (event.created_unix_ns() != 0) out.created_referee = time::Timestamp::from_nanoseconds(event.created_unix_ns());
  out.by_team = enum_in_range(static_cast<int>(event.by_team()), Team::kBlue);
  if (event.has_by_bot()) out.by_bot = event.by_bot();
  if (event.has_other_bot()) out.other_bot = event.other_bot();
  if (event.has_location()) out.location = from_idl(event.location());
  if (event.has_secondary_location()) out.secondary_location = from_idl(event.secondary_location());
  if (event.has_value()) out.value = event.value();
  out.text = event.text();
  return out;
}

TeamInfo from_idl(const idl::referee::TeamInfo& team) {
  TeamInfo out;
  out.name = team.name();
  out.score = team.score();
  out.red_cards = team.red_cards();
  for (double left : team.yellow_card_times_left()) out.yellow_card_times_left.push_back(time::duration_from_seconds(left));
  out.yellow_cards = team.yellow_cards();
  out.timeouts = team.timeouts();
  out.timeout_time_left = time::duration_from_seconds(team.timeout_time_left());
  out.goalkeeper = team.goalkeeper();
  out.foul_counter = team.foul_counter();
  out.ball_placement_failures = team.ball_placement_failures();
  out.can_place_ball = team.can_place_ball();
  out.max_allowed_bots = team.max_allowed_bots();
  out.bot_substitution_intent = team.bot_substitution_intent();
  out.ball_placement_failures_reached = team.ball_placement_failures_reached();
  out.bot_substitution_allowed = team.bot_substitution_allowed();
  out.bot_substitutions_left = team.bot_substitutions_left();
  out.bot_substitution_time_left = time::duration_from_seconds(team.bot_substitution_time_left());
  out.hull_color = enum_in_range(static_cast<int>(team.hull_color()), HullColor::kLight);
  return out;
}

RefereeState from_idl(const idl::referee::RefereeState& state) {
  RefereeState out;
  out.source = state.source() == idl::referee::REFEREE_SOURCE_BUILTIN ? RefereeSource::kBuiltin
                                                                       : RefereeSource::kGameController;
  out.source_identifier = state.source_identifier();
  out.match_type = enum_in_range(static_cast<int>(state.match_type()), MatchType::kFriendly);
  out.packet_referee = time::Timestamp::from_nanoseconds(state.packet_unix_ns());
  out.receive_wall = time::Timestamp::from_nanoseconds(state.receive_unix_ns());
  out.stage = enum_in_range(static_cast<int>(state.stage()), Stage::kPostGame);
  out.stage_time_left = time::duration_from_seconds(state.stage_time_left());
  out.command = enum_in_range(static_cast<int>(state.command()), Command::kBallPlacementBlue);
  out.command_counter = state.command_counter();
  out.command_referee = time::Timestamp::from_nanoseconds(state.command_unix_ns());
  out.yellow = from_idl(state.yellow());
  out.blue = from_idl(state.blue());
  if (state.has_designated_position()) out.designated_position = from_idl(state.designated_position());
  if (state.has_blue_team_on_positive_half()) out.blue_team_on_positive_half = state.blue_team_on_positive_half();
  if (state.has_next_command()) {
    out.next_command = enum_in_range(static_cast<int>(state.next_command()), Command::kBallPlacementBlue);
  }
  for (const auto& event : state.game_events()) out.game_events.push_back(from_idl(event));
  for (const auto& group : state.game_event_proposals()) {
    GameEventProposal proposal;
    proposal.id = group.id();
    proposal.accepted = group.accepted();
    for (const auto& event : group.events()) proposal.events.push_back(from_idl(event));
    out.game_event_proposals.push_back(std::move(proposal));
  }
  if (state.has_current_action_time_remaining()) {
    out.current_action_time_remaining = time::duration_from_seconds(state.current_action_time_remaining());
  }
  out.status_message = state.status_message();
  return out;
}

RefereeEvent from_idl(const idl::referee::RefereeEvent& event) {
  RefereeEvent out;
  out.event = from_idl(event.event());
  out.command = enum_in_range(static_cast<int>(event.command()), Command::kBallPlacementBlue);
  out.command_counter = event.command_counter();
  out.receive_wall = time::Timestamp::from_nanoseconds(event.receive_unix_ns());
  return out;
}

}  // namespace ssl::referee
