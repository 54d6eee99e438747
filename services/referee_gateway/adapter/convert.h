// Conversions at the referee gateway's two edges, done once:
//   league protobuf (Referee, GameEvent; µs, mm) -> core types (types.h; SI) -> IDL (referee.idl)
// and back to the wire for the built-in referee, which multicasts its RefereeState as a league packet:
//   core types -> league protobuf (to_proto)
//
// Wire -> core units: packet/command/created timestamps Unix µs -> Timestamp (ns); stage_time_left (sint64),
// current_action_time_remaining (int64), yellow card times, timeout_time and bot_substitution_time_left µs
// -> Duration; designated_position mm -> m; game-event locations are already m, speeds m/s, distances m,
// durations s. Out-of-range integers saturate, non-finite floats (NaN, inf) become "not sent"; nothing
// here fails or throws, whatever a decoded packet holds.
// Core -> IDL: Timestamps -> int64 Unix ns; Durations -> double s; optionals -> has_ flags (for
// stage_time_left, which has no flag in the IDL, "not sent" reads as 0 s).
// Core -> wire (to_proto), the inverse of from_proto: Timestamps -> Unix µs (truncated; before 1970 -> 0);
// Durations -> µs truncated toward zero (uint32 fields saturate at 0 and 2^32 - 1 µs, about 71 min);
// designated_position m -> mm; the float fields saturate at +-FLT_MAX, and a NaN or infinite point or
// number is not sent (from_proto treats it as not sent anyway). Every proto2 `required` field is set, so
// the packet serialises. Optionals of the core are sent exactly when present; strings (source_identifier,
// status_message, event id, Goal.message, PenaltyKickFailed.reason) only when not empty; every TeamInfo
// field is sent, as the Game Controller does. Receive time and source are not on the wire.
// from_proto(to_proto(state), state.receive_wall, state.source) == state for times in whole µs and
// numbers that are exact in a float (locations and values in m / SI, designated_position in mm).
//
// Game events are decoded by WHICH oneof field is set (the Type enum number differs from the oneof field
// number for several events), and flattened into GameEvent's slots. Only when no oneof field is set the
// optional `type` is used, by its NAME. The slots per payload message:
// Slot abbreviations: bot = by_bot, other = other_bot, loc = location, loc2 = secondary_location.
//   ball_left_field_touch_line, _goal_line     bot, loc
//   aimless_kick                               bot, loc, loc2 = kick_location
//   attacker_too_close_to_defense_area         bot, loc, loc2 = ball_location, value = distance (m)
//   defender_in_defense_area                   bot, loc, value = distance (m)
//   defender_in_defense_area_partially         bot, loc, loc2 = ball_location, value = distance (m)
//   boundary_crossing                          loc
//   keeper_held_ball                           loc, value = duration (s)
//   bot_dribbled_ball_too_far                  bot, loc = start, loc2 = end
//   bot_pushed_bot (+ _skipped)                bot = violator, other = victim, loc,
//                                              value = pushed_distance (m)
//   bot_held_ball_deliberately                 bot, loc, value = duration (s)
//   bot_tipped_over, bot_dropped_parts         bot, loc, loc2 = ball_location
//   attacker_touched_ball_in_defense_area      bot, loc, value = distance (m)
//   bot_kicked_ball_too_fast                   bot, loc, value = initial_ball_speed (m/s),
//                                              text = "chipped" when chipped
//   bot_crash_unique (+ _skipped)              bot = violator, other = victim, loc, value = crash_speed (m/s)
//   bot_crash_drawn                            by_team UNKNOWN, bot = bot_yellow, other = bot_blue, loc,
//                                              value = crash_speed (m/s)
//   defender_too_close_to_kick_point           bot, loc, value = distance (m)
//   bot_too_fast_in_stop                       bot, loc, value = speed (m/s)
//   bot_interfered_placement                   bot, loc
//   attacker_double_touched_ball               bot, loc
//   possible_goal, goal, invalid_goal (Goal)   bot = kicking_bot, loc, loc2 = kick_location,
//                                              value = max_ball_height (m), text = message
//   indirect_goal                              bot, loc, loc2 = kick_location
//   chipped_goal                               bot, loc, loc2 = kick_location, value = max_ball_height (m)
//   attacker_touched_opponent_in_defense_area (+ _skipped)   bot, other = victim, loc
//   placement_succeeded                        value = time_taken (s)
//   placement_failed                           value = remaining_distance (m)
//   no_progress_in_game                        by_team UNKNOWN, loc, value = time (s)
//   kick_timeout                               loc, value = time (s)
//   prepared                                   by_team UNKNOWN, value = time_taken (s)
//   too_many_robots                            loc2 = ball_location, text = "<n> on field, <m> allowed"
//   penalty_kick_failed                        loc, text = reason
//   unsporting_behavior_minor, _major          text = reason
//   challenge_flag_handled                     text = "accepted" or "rejected"
//   multiple_fouls                             text = "caused by: <TYPE>, <TYPE>" (the caused events' types)
//   multiple_cards, multiple_placement_failures, bot_substitution, excessive_bot_substitution,
//   challenge_flag, emergency_stop             by_team only
//
// by_team is the payload's by_team everywhere it exists (the scoring team for goals). Not carried (the
// IDL has no slot): Goal.kicking_team / num_robots_by_team / last_touch_by_team, crash speed_diff and
// crash_angle, PlacementSucceeded.precision and .distance, PlacementFailed.nearest_own_bot_distance, and
// the caused events of multiple_fouls beyond their type names.
//
// to_proto(GameEvent) sets the oneof member of the event's type with its payload filled back from the
// slots above, and `type` to the league's Type number (by name: BOUNDARY_CROSSING = 41 in oneof field
// 43). Slots the type does not carry are dropped, as are by_team for bot_crash_drawn,
// no_progress_in_game and prepared. Text slots are parsed back: "chipped" -> chipped = true;
// "accepted" -> accepted = true (anything else: false); "<n> on field, <m> allowed" -> the two counts
// (other text is dropped); "caused by: A, B" -> one caused event per known type name, with this event's
// by_team (unknown names are dropped). kUnknown sends type UNKNOWN_GAME_EVENT_TYPE and no oneof member.
//
//   RefereeState state = from_proto(*referee, wall.now());
//   idl::referee::RefereeState sample = to_idl(state);
//   ::Referee packet = to_proto(builtin_state);   // from_proto(packet, ...) gives builtin_state back
#pragma once

#include "idl/referee.h"
#include "libs/time/time.h"
#include "proto/ssl_gc_referee_message.pb.h"
#include "services/referee_gateway/core/types.h"

namespace ssl::referee {

/// A whole Referee packet; `receive_wall` is this host's wall clock when it arrived.
RefereeState from_proto(const ::Referee& packet, time::Timestamp receive_wall,
                        RefereeSource source = RefereeSource::kGameController);
TeamInfo from_proto(const ::Referee::TeamInfo& team);
GameEvent from_proto(const ::GameEvent& event);

/// The game event type of a league event: by its oneof case, else by the name of its `type`.
GameEventType game_event_type(const ::GameEvent& event);

/// The inverse of from_proto, for multicasting a referee state as a league packet (IsInitialized() holds).
/// `receive_wall` and `source` are not on the wire; from_proto takes them as arguments.
::Referee to_proto(const RefereeState& state);
::Referee::TeamInfo to_proto(const TeamInfo& team);
/// The event's type as its oneof member (with the payload of its slots) and as `type`.
::GameEvent to_proto(const GameEvent& event);

idl::referee::RefereeState to_idl(const RefereeState& state);
idl::referee::RefereeEvent to_idl(const RefereeEvent& event);
idl::referee::GameEvent to_idl(const GameEvent& event);
idl::referee::TeamInfo to_idl(const TeamInfo& team);

/// The inverses of to_idl, for readers of referee.state and referee.event (the console, tools). Enumerators
/// outside the core's range become the first one (HALT, unknown event, ...).
RefereeState from_idl(const idl::referee::RefereeState& state);
RefereeEvent from_idl(const idl::referee::RefereeEvent& event);
GameEvent from_idl(const idl::referee::GameEvent& event);
TeamInfo from_idl(const idl::referee::TeamInfo& team);

}  // namespace ssl::referee
