#include "services/referee_gateway/core/types.h"

#include <array>
#include <cstdio>
#include <string>
#include <type_traits>

namespace ssl::referee {
namespace {

constexpr std::array<std::string_view, kCommandCount> kCommandNames = {
    "HALT",
    "STOP",
    "NORMAL_START",
    "FORCE_START",
    "PREPARE_KICKOFF_YELLOW",
    "PREPARE_KICKOFF_BLUE",
    "PREPARE_PENALTY_YELLOW",
    "PREPARE_PENALTY_BLUE",
    "DIRECT_FREE_YELLOW",
    "DIRECT_FREE_BLUE",
    "INDIRECT_FREE_YELLOW",
    "INDIRECT_FREE_BLUE",
    "TIMEOUT_YELLOW",
    "TIMEOUT_BLUE",
    "GOAL_YELLOW",
    "GOAL_BLUE",
    "BALL_PLACEMENT_YELLOW",
    "BALL_PLACEMENT_BLUE",
};

constexpr std::array<std::string_view, kStageCount> kStageNames = {
    "NORMAL_FIRST_HALF_PRE",  "NORMAL_FIRST_HALF",  "NORMAL_HALF_TIME",
    "NORMAL_SECOND_HALF_PRE", "NORMAL_SECOND_HALF", "EXTRA_TIME_BREAK",
    "EXTRA_FIRST_HALF_PRE",   "EXTRA_FIRST_HALF",   "EXTRA_HALF_TIME",
    "EXTRA_SECOND_HALF_PRE",  "EXTRA_SECOND_HALF",  "PENALTY_SHOOTOUT_BREAK",
    "PENALTY_SHOOTOUT",       "POST_GAME",
};

// In GameEventType order.
constexpr std::array<std::string_view, kGameEventTypeCount> kGameEventNames = {
    "UNKNOWN_GAME_EVENT_TYPE",
    "BALL_LEFT_FIELD_TOUCH_LINE",
    "BALL_LEFT_FIELD_GOAL_LINE",
    "AIMLESS_KICK",
    "ATTACKER_TOO_CLOSE_TO_DEFENSE_AREA",
    "DEFENDER_IN_DEFENSE_AREA",
    "BOUNDARY_CROSSING",
    "KEEPER_HELD_BALL",
    "BOT_DRIBBLED_BALL_TOO_FAR",
    "BOT_PUSHED_BOT",
    "BOT_HELD_BALL_DELIBERATELY",
    "BOT_TIPPED_OVER",
    "BOT_DROPPED_PARTS",
    "ATTACKER_TOUCHED_BALL_IN_DEFENSE_AREA",
    "BOT_KICKED_BALL_TOO_FAST",
    "BOT_CRASH_UNIQUE",
    "BOT_CRASH_DRAWN",
    "DEFENDER_TOO_CLOSE_TO_KICK_POINT",
    "BOT_TOO_FAST_IN_STOP",
    "BOT_INTERFERED_PLACEMENT",
    "EXCESSIVE_BOT_SUBSTITUTION",
    "POSSIBLE_GOAL",
    "GOAL",
    "INVALID_GOAL",
    "ATTACKER_DOUBLE_TOUCHED_BALL",
    "PLACEMENT_SUCCEEDED",
    "PENALTY_KICK_FAILED",
    "NO_PROGRESS_IN_GAME",
    "PLACEMENT_FAILED",
    "MULTIPLE_CARDS",
    "MULTIPLE_FOULS",
    "BOT_SUBSTITUTION",
    "TOO_MANY_ROBOTS",
    "CHALLENGE_FLAG",
    "CHALLENGE_FLAG_HANDLED",
    "EMERGENCY_STOP",
    "UNSPORTING_BEHAVIOR_MINOR",
    "UNSPORTING_BEHAVIOR_MAJOR",
    "PREPARED",
    "INDIRECT_GOAL",
    "CHIPPED_GOAL",
    "KICK_TIMEOUT",
    "ATTACKER_TOUCHED_OPPONENT_IN_DEFENSE_AREA",
    "ATTACKER_TOUCHED_OPPONENT_IN_DEFENSE_AREA_SKIPPED",
    "BOT_CRASH_UNIQUE_SKIPPED",
    "BOT_PUSHED_BOT_SKIPPED",
    "DEFENDER_IN_DEFENSE_AREA_PARTIALLY",
    "MULTIPLE_PLACEMENT_FAILURES",
};
static_assert(static_cast<int>(GameEventType::kMultiplePlacementFailures) == kGameEventTypeCount - 1);
static_assert(static_cast<int>(Command::kBallPlacementBlue) == kCommandCount - 1);
static_assert(static_cast<int>(Stage::kPostGame) == kStageCount - 1);

template <std::size_t N, typename Enum>
std::string_view name_of(const std::array<std::string_view, N>& names, Enum value) {
  const auto index = static_cast<std::size_t>(value);
  return index < N ? names[index] : std::string_view("UNKNOWN");
}

/// Appends a double with round-trip precision (so keys of distinct values never collide).
void append_double(std::string& out, double value) {
  char buffer[32];
  const int length = std::snprintf(buffer, sizeof buffer, "%.17g", value);
  if (length > 0) out.append(buffer, static_cast<std::size_t>(length));
}

template <typename T>
void append_optional_number(std::string& out, const std::optional<T>& value) {
  if (!value) {
    out += '-';
  } else if constexpr (std::is_floating_point_v<T>) {
    append_double(out, *value);
  } else {
    out += std::to_string(*value);
  }
  out += '|';
}

void append_optional_vec(std::string& out, const std::optional<Vec2>& value) {
  if (!value) {
    out += "-|";
    return;
  }
  append_double(out, value->x());
  out += ',';
  append_double(out, value->y());
  out += '|';
}

/// Strings may contain the separator, so they are length-prefixed.
void append_string(std::string& out, const std::string& text) {
  out += std::to_string(text.size());
  out += ':';
  out += text;
  out += '|';
}

/// Team info without its running clocks (see same_meaning).
bool same_team_meaning(const TeamInfo& a, const TeamInfo& b) {
  return a.name == b.name && a.score == b.score && a.red_cards == b.red_cards &&
         a.yellow_card_times_left.size() == b.yellow_card_times_left.size() &&
         a.yellow_cards == b.yellow_cards && a.timeouts == b.timeouts && a.goalkeeper == b.goalkeeper &&
         a.foul_counter == b.foul_counter && a.ball_placement_failures == b.ball_placement_failures &&
         a.can_place_ball == b.can_place_ball && a.max_allowed_bots == b.max_allowed_bots &&
         a.bot_substitution_intent == b.bot_substitution_intent &&
         a.ball_placement_failures_reached == b.ball_placement_failures_reached &&
         a.bot_substitution_allowed == b.bot_substitution_allowed &&
         a.bot_substitutions_left == b.bot_substitutions_left && a.hull_color == b.hull_color;
}

}  // namespace

std::string_view to_string(Command command) { return name_of(kCommandNames, command); }
std::string_view to_string(Stage stage) { return name_of(kStageNames, stage); }
std::string_view to_string(GameEventType type) { return name_of(kGameEventNames, type); }

std::optional<TeamColor> team_of(Command command) {
  switch (command) {
    case Command::kPrepareKickoffYellow:
    case Command::kPreparePenaltyYellow:
    case Command::kDirectFreeYellow:
    case Command::kIndirectFreeYellow:
    case Command::kTimeoutYellow:
    case Command::kGoalYellow:
    case Command::kBallPlacementYellow:
      return TeamColor::kYellow;
    case Command::kPrepareKickoffBlue:
    case Command::kPreparePenaltyBlue:
    case Command::kDirectFreeBlue:
    case Command::kIndirectFreeBlue:
    case Command::kTimeoutBlue:
    case Command::kGoalBlue:
    case Command::kBallPlacementBlue:
      return TeamColor::kBlue;
    case Command::kHalt:
    case Command::kStop:
    case Command::kNormalStart:
    case Command::kForceStart:
      return std::nullopt;
  }
  return std::nullopt;
}

bool is_kickoff(Command command) {
  return command == Command::kPrepareKickoffYellow || command == Command::kPrepareKickoffBlue;
}

bool is_penalty(Command command) {
  return command == Command::kPreparePenaltyYellow || command == Command::kPreparePenaltyBlue;
}

bool is_free_kick(Command command) {
  return command == Command::kDirectFreeYellow || command == Command::kDirectFreeBlue ||
         command == Command::kIndirectFreeYellow || command == Command::kIndirectFreeBlue;
}

bool is_foul(GameEventType type) {
  using T = GameEventType;
  switch (type) {
    case T::kAttackerTooCloseToDefenseArea:
    case T::kDefenderInDefenseArea:
    case T::kDefenderInDefenseAreaPartially:
    case T::kBoundaryCrossing:
    case T::kKeeperHeldBall:
    case T::kBotDribbledBallTooFar:
    case T::kBotPushedBot:
    case T::kBotPushedBotSkipped:
    case T::kBotHeldBallDeliberately:
    case T::kBotTippedOver:
    case T::kBotDroppedParts:
    case T::kAttackerTouchedBallInDefenseArea:
    case T::kAttackerTouchedOpponentInDefenseArea:
    case T::kAttackerTouchedOpponentInDefenseAreaSkipped:
    case T::kBotKickedBallTooFast:
    case T::kBotCrashUnique:
    case T::kBotCrashUniqueSkipped:
    case T::kBotCrashDrawn:
    case T::kDefenderTooCloseToKickPoint:
    case T::kBotTooFastInStop:
    case T::kBotInterferedPlacement:
    case T::kAttackerDoubleTouchedBall:
      return true;
    default:
      return false;
  }
}

bool is_avoidable_foul(GameEventType type) {
  using T = GameEventType;
  switch (type) {
    case T::kDefenderTooCloseToKickPoint:
    case T::kBotTooFastInStop:
    case T::kDefenderInDefenseArea:
    case T::kDefenderInDefenseAreaPartially:
    case T::kAttackerTouchedBallInDefenseArea:
    case T::kAttackerTooCloseToDefenseArea:
    case T::kAttackerDoubleTouchedBall:
    case T::kBotCrashUnique:
    case T::kBotCrashUniqueSkipped:
    case T::kBotCrashDrawn:
      return true;
    default:
      return false;
  }
}

std::optional<GameEventType> parse_game_event_type(std::string_view league_name) {
  for (std::size_t i = 0; i < kGameEventNames.size(); ++i) {
    if (kGameEventNames[i] == league_name) return static_cast<GameEventType>(i);
  }
  return std::nullopt;
}

bool same_meaning(const RefereeState& a, const RefereeState& b) {
  return a.source == b.source && a.source_identifier == b.source_identifier && a.stage == b.stage &&
         a.command == b.command && a.command_counter == b.command_counter &&
         a.command_referee == b.command_referee && a.next_command == b.next_command &&
         a.designated_position == b.designated_position &&
         a.blue_team_on_positive_half == b.blue_team_on_positive_half &&
         a.stage_time_left.has_value() == b.stage_time_left.has_value() &&
         a.current_action_time_remaining.has_value() == b.current_action_time_remaining.has_value() &&
         same_team_meaning(a.yellow, b.yellow) && same_team_meaning(a.blue, b.blue);
}

std::string event_key(const GameEvent& event) {
  if (!event.id.empty()) return "id:" + event.id;
  std::string key = "content:";
  key += std::to_string(static_cast<int>(event.type));
  key += '|';
  key += std::to_string(event.origins.size());
  key += '|';
  for (const auto& origin : event.origins) append_string(key, origin);
  std::optional<std::int64_t> created;
  if (event.created_referee) created = event.created_referee->nanoseconds();
  append_optional_number(key, created);
  key += std::to_string(static_cast<int>(event.by_team));
  key += '|';
  append_optional_number(key, event.by_bot);
  append_optional_number(key, event.other_bot);
  append_optional_vec(key, event.location);
  append_optional_vec(key, event.secondary_location);
  append_optional_number(key, event.value);
  append_string(key, event.text);
  return key;
}

}  // namespace ssl::referee
