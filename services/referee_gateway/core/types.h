// Domain types of the referee gateway core: the Game Controller's Referee message in SI units, as the
// adapter hands it over after decoding and converting the wire format once (adapter/convert.h).
//
// Units: metres (designated_position arrives in MILLIMETRES and is converted by the adapter; game-event
// locations arrive in metres), m/s, seconds held as ssl::time::Duration (the league sends microseconds).
// Frame: the SSL-Vision global frame; the gateway never flips anything.
// Clocks (a Timestamp does not carry its clock, so every name says it):
//   * `packet_referee`, `command_referee`, `GameEvent::created_referee`: the REFEREE HOST's wall clock
//     (Unix), as sent by the Game Controller;
//   * `receive_wall`: this host's wall clock (Unix) when the datagram arrived; stamped on outputs only.
// The core's timing rules (heartbeat, staleness, source switching) use a separate monotonic `now` that the
// caller passes in (see gateway.h), never these wall-clock stamps.
//
// Enums keep the league's names and, where the league's values are dense, its order and values. Game
// events are flattened into one GameEvent whose typed slots (by_bot, other_bot, location,
// secondary_location, value, text) mean different things per type; adapter/convert.h documents the
// mapping of every payload message.
//
//   RefereeState state;
//   state.command = Command::kStop;
//   state.designated_position = Vec2(1.5, -0.25);   // m
//   if (!same_meaning(state, previous)) publish(state);
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "libs/common/team.h"
#include "libs/geometry/vec2.h"
#include "libs/time/time.h"

namespace ssl::referee {

using geom::Vec2;

/// The league's Referee.Command (same order and values). GOAL_* are deprecated but still sent once per
/// awarded goal by the Game Controller for compatibility; INDIRECT_FREE_* are deprecated.
enum class Command : std::uint8_t {
  kHalt = 0,
  kStop = 1,
  kNormalStart = 2,
  kForceStart = 3,
  kPrepareKickoffYellow = 4,
  kPrepareKickoffBlue = 5,
  kPreparePenaltyYellow = 6,
  kPreparePenaltyBlue = 7,
  kDirectFreeYellow = 8,
  kDirectFreeBlue = 9,
  kIndirectFreeYellow = 10,
  kIndirectFreeBlue = 11,
  kTimeoutYellow = 12,
  kTimeoutBlue = 13,
  kGoalYellow = 14,
  kGoalBlue = 15,
  kBallPlacementYellow = 16,
  kBallPlacementBlue = 17,
};
inline constexpr int kCommandCount = 18;

/// The league's Referee.Stage (same order and values).
enum class Stage : std::uint8_t {
  kNormalFirstHalfPre = 0,
  kNormalFirstHalf = 1,
  kNormalHalfTime = 2,
  kNormalSecondHalfPre = 3,
  kNormalSecondHalf = 4,
  kExtraTimeBreak = 5,
  kExtraFirstHalfPre = 6,
  kExtraFirstHalf = 7,
  kExtraHalfTime = 8,
  kExtraSecondHalfPre = 9,
  kExtraSecondHalf = 10,
  kPenaltyShootoutBreak = 11,
  kPenaltyShootout = 12,
  kPostGame = 13,
};
inline constexpr int kStageCount = 14;

/// The league's MatchType (same values).
enum class MatchType : std::uint8_t { kUnknown = 0, kGroupPhase = 1, kEliminationPhase = 2, kFriendly = 3 };

/// The league's HullColor (same values).
enum class HullColor : std::uint8_t { kUnknown = 0, kDark = 1, kLight = 2 };

/// The league's Team (ssl_gc_common.proto, same values): who caused an event.
enum class Team : std::uint8_t { kUnknown = 0, kYellow = 1, kBlue = 2 };

/// Where the referee state comes from.
enum class RefereeSource : std::uint8_t { kGameController, kBuiltin };

/// Game event kinds, in OUR order (the IDL's GameEventType order). The league's GameEvent.Type values are
/// sparse and differ from the oneof field numbers for several events, so the adapter maps the oneof CASE
/// onto these by name. The names returned by to_string are the league's Type names.
enum class GameEventType : std::uint8_t {
  kUnknown,
  kBallLeftFieldTouchLine,
  kBallLeftFieldGoalLine,
  kAimlessKick,
  kAttackerTooCloseToDefenseArea,
  kDefenderInDefenseArea,
  kBoundaryCrossing,
  kKeeperHeldBall,
  kBotDribbledBallTooFar,
  kBotPushedBot,
  kBotHeldBallDeliberately,
  kBotTippedOver,
  kBotDroppedParts,
  kAttackerTouchedBallInDefenseArea,
  kBotKickedBallTooFast,
  kBotCrashUnique,
  kBotCrashDrawn,
  kDefenderTooCloseToKickPoint,
  kBotTooFastInStop,
  kBotInterferedPlacement,
  kExcessiveBotSubstitution,
  kPossibleGoal,
  kGoal,
  kInvalidGoal,
  kAttackerDoubleTouchedBall,
  kPlacementSucceeded,
  kPenaltyKickFailed,
  kNoProgressInGame,
  kPlacementFailed,
  kMultipleCards,
  kMultipleFouls,
  kBotSubstitution,
  kTooManyRobots,
  kChallengeFlag,
  kChallengeFlagHandled,
  kEmergencyStop,
  kUnsportingBehaviorMinor,
  kUnsportingBehaviorMajor,
  kPrepared,
  kIndirectGoal,
  kChippedGoal,
  kKickTimeout,
  kAttackerTouchedOpponentInDefenseArea,
  kAttackerTouchedOpponentInDefenseAreaSkipped,
  kBotCrashUniqueSkipped,
  kBotPushedBotSkipped,
  kDefenderInDefenseAreaPartially,
  kMultiplePlacementFailures,
};
inline constexpr int kGameEventTypeCount = 48;  // kUnknown included

/// League names: "STOP", "NORMAL_FIRST_HALF", "BOUNDARY_CROSSING" (GameEvent.Type names, so
/// "UNKNOWN_GAME_EVENT_TYPE" for kUnknown); "UNKNOWN" for values outside the enum.
std::string_view to_string(Command command);
std::string_view to_string(Stage stage);
std::string_view to_string(GameEventType type);
/// The team a command is for (kicker, placer, team in timeout, scorer); nullopt for HALT, STOP,
/// NORMAL_START and FORCE_START.
std::optional<TeamColor> team_of(Command command);
/// PREPARE_KICKOFF of either team.
bool is_kickoff(Command command);
/// PREPARE_PENALTY of either team.
bool is_penalty(Command command);
/// A free kick of either team: DIRECT_FREE, or INDIRECT_FREE (no longer in the rules, a free kick all the same).
bool is_free_kick(Command command);

/// A foul of the rules (section "Fouls"): stopping fouls, non-stopping fouls and their "skipped" variants
/// (raised with advantage). Not fouls: ball out, goals, placements, no progress, cards, substitutions.
bool is_foul(GameEventType type);
/// A foul a team commits by its own play alone and can always avoid, whatever the opponent does: keep-out
/// distances, speed in STOP, defense areas, double touch, crashes. The bar for a team's play: zero of them.
bool is_avoidable_foul(GameEventType type);
/// The type whose league name is `league_name` (e.g. "BOT_DROPPED_PARTS"); nullopt for unknown names.
std::optional<GameEventType> parse_game_event_type(std::string_view league_name);

/// One game event, flattened. Slots without a value for this type stay empty (nullopt / "").
struct GameEvent {
  std::string id;  // globally unique when the referee sets it; may be empty
  GameEventType type = GameEventType::kUnknown;
  std::vector<std::string> origins;                // autoRef names; empty when raised by the Game Controller
  std::optional<time::Timestamp> created_referee;  // Unix, referee host clock
  Team by_team = Team::kUnknown;                   // team that caused it (scoring team for goals)
  std::optional<std::uint32_t> by_bot;     // violator / kicker / last toucher / yellow bot of a drawn crash
  std::optional<std::uint32_t> other_bot;  // victim / blue bot of a drawn crash
  std::optional<Vec2> location;            // m
  std::optional<Vec2> secondary_location;  // m: kick location, ball location or dribbling end
  std::optional<double> value;             // SI: speed m/s, distance m, duration s or ball height m
  std::string text;                        // reason or message, when the event carries one

  friend bool operator==(const GameEvent&, const GameEvent&) = default;
};

/// Game events proposed together by autoRefs (GameEventProposalGroup).
struct GameEventProposal {
  std::string id;
  std::vector<GameEvent> events;
  bool accepted = false;

  friend bool operator==(const GameEventProposal&, const GameEventProposal&) = default;
};

/// Referee.TeamInfo. Optional league fields that were not sent read as 0 / false (the Game Controller
/// always sends them; old referee boxes may not).
struct TeamInfo {
  std::string name;
  std::uint32_t score = 0;
  std::uint32_t red_cards = 0;
  std::vector<time::Duration> yellow_card_times_left;  // per active yellow card, ascending
  std::uint32_t yellow_cards = 0;                      // total ever issued
  std::uint32_t timeouts = 0;                          // left, the current one excluded
  time::Duration timeout_time_left{0};
  std::uint32_t goalkeeper = 0;
  std::uint32_t foul_counter = 0;
  std::uint32_t ball_placement_failures = 0;
  bool can_place_ball = false;
  std::uint32_t max_allowed_bots = 0;
  bool bot_substitution_intent = false;
  bool ball_placement_failures_reached = false;
  bool bot_substitution_allowed = false;
  std::uint32_t bot_substitutions_left = 0;
  time::Duration bot_substitution_time_left{0};
  HullColor hull_color = HullColor::kUnknown;

  friend bool operator==(const TeamInfo&, const TeamInfo&) = default;
};

/// The whole referee state of one Referee packet (every field of the league's message).
struct RefereeState {
  RefereeSource source = RefereeSource::kGameController;
  std::string source_identifier;  // UUID of the Game Controller instance; "" when not sent
  MatchType match_type = MatchType::kUnknown;
  time::Timestamp packet_referee;  // when the referee sent it (referee host clock, Unix)
  time::Timestamp receive_wall;    // when the gateway received it (this host's wall clock, Unix)
  Stage stage = Stage::kNormalFirstHalfPre;
  std::optional<time::Duration> stage_time_left;  // negative when the stage overran
  Command command = Command::kHalt;
  std::uint32_t command_counter = 0;  // increments (mod 2^32) on every new command
  time::Timestamp command_referee;    // when the command was issued (referee host clock, Unix)
  TeamInfo yellow;
  TeamInfo blue;
  std::optional<Vec2> designated_position;  // m, ball placement target
  std::optional<bool> blue_team_on_positive_half;
  std::optional<Command> next_command;
  std::vector<GameEvent> game_events;  // since the last running state
  std::vector<GameEventProposal> game_event_proposals;
  std::optional<time::Duration> current_action_time_remaining;  // may be negative
  std::string status_message;

  friend bool operator==(const RefereeState&, const RefereeState&) = default;
};

/// A game event as published once on referee.event, with the command in force when it was first seen.
struct RefereeEvent {
  GameEvent event;
  Command command = Command::kHalt;
  std::uint32_t command_counter = 0;
  time::Timestamp receive_wall;  // this host's wall clock (Unix)

  friend bool operator==(const RefereeEvent&, const RefereeEvent&) = default;
};

/// True when `a` and `b` describe the same situation, i.e. a consumer would act the same on both. This
/// decides whether a packet is republished on referee.state before the heartbeat is due.
///
/// Compared: source, source_identifier, stage, command, command_counter, command time, next_command,
/// designated_position, blue_team_on_positive_half, whether stage_time_left and
/// current_action_time_remaining are present, and every TeamInfo field except its running clocks (for
/// yellow cards: the NUMBER of active cards, not their times).
/// Ignored, as the referee integration design requires: game_events, game_event_proposals, match_type
/// and status_message. Also ignored: the clocks that change in every Game Controller packet (about 40 per
/// second) — packet and receive time, stage_time_left, current_action_time_remaining, yellow card times,
/// timeout_time_left, bot_substitution_time_left; the heartbeat carries them.
bool same_meaning(const RefereeState& a, const RefereeState& b);

/// The identity of a game event for "publish each event once": "id:<id>" when the referee gave it an id,
/// otherwise "content:<every field>" (type, origins, created time, team, bots, locations, value, text).
std::string event_key(const GameEvent& event);

}  // namespace ssl::referee
