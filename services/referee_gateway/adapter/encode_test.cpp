// Encoding for the built-in referee (to_proto): a RefereeState becomes a league Referee packet that
// serialises and decodes back to the same state; every game event type travels in its own oneof member
// with the league's Type number and the slots it carries; out-of-range values saturate.
#include "services/referee_gateway/adapter/convert.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "services/referee_gateway/testing/referee_packets.h"

namespace ssl::referee {
namespace {

using namespace std::chrono_literals;
using T = GameEventType;

// ---------------------------------------------------------------------------------------------------------
// Game events

/// The slots of GameEvent that one type carries on the wire (the table in convert.h).
enum Slot : unsigned {
  kTeam = 1u << 0,   // by_team
  kBot = 1u << 1,    // by_bot
  kOther = 1u << 2,  // other_bot
  kLoc = 1u << 3,    // location
  kLoc2 = 1u << 4,   // secondary_location
  kValue = 1u << 5,  // value
  kText = 1u << 6,   // text (in the one format the type carries)
  kAllSlots = (1u << 7) - 1,
};

struct EventOnWire {
  GameEventType type;
  int oneof_field;  // field number of its oneof member (ssl-protocols.md section 8)
  int league_type;  // its GameEvent.Type value (ssl-protocols.md section 8)
  unsigned slots;
  std::string_view text;  // the text slot, when the type carries one
};

constexpr unsigned kBotLoc = kTeam | kBot | kLoc;
constexpr unsigned kGoalSlots = kTeam | kBot | kLoc | kLoc2 | kValue | kText;

// One row per type; the numbers are typed from ssl-protocols.md, not taken from the generated code.
constexpr EventOnWire kEvents[] = {
    {T::kBallLeftFieldTouchLine, 6, 6, kBotLoc, ""},
    {T::kBallLeftFieldGoalLine, 7, 7, kBotLoc, ""},
    {T::kAimlessKick, 11, 11, kBotLoc | kLoc2, ""},
    {T::kAttackerTooCloseToDefenseArea, 19, 19, kBotLoc | kLoc2 | kValue, ""},
    {T::kDefenderInDefenseArea, 31, 31, kBotLoc | kValue, ""},
    {T::kBoundaryCrossing, 43, 41, kTeam | kLoc, ""},
    {T::kKeeperHeldBall, 13, 13, kTeam | kLoc | kValue, ""},
    {T::kBotDribbledBallTooFar, 17, 17, kBotLoc | kLoc2, ""},
    {T::kBotPushedBot, 24, 24, kBotLoc | kOther | kValue, ""},
    {T::kBotHeldBallDeliberately, 26, 26, kBotLoc | kValue, ""},
    {T::kBotTippedOver, 27, 27, kBotLoc | kLoc2, ""},
    {T::kBotDroppedParts, 51, 47, kBotLoc | kLoc2, ""},
    {T::kAttackerTouchedBallInDefenseArea, 15, 15, kBotLoc | kValue, ""},
    {T::kBotKickedBallTooFast, 18, 18, kBotLoc | kValue | kText, "chipped"},
    {T::kBotCrashUnique, 22, 22, kBotLoc | kOther | kValue, ""},
    {T::kBotCrashDrawn, 21, 21, kBot | kOther | kLoc | kValue, ""},  // no by_team
    {T::kDefenderTooCloseToKickPoint, 29, 29, kBotLoc | kValue, ""},
    {T::kBotTooFastInStop, 28, 28, kBotLoc | kValue, ""},
    {T::kBotInterferedPlacement, 20, 20, kBotLoc, ""},
    {T::kExcessiveBotSubstitution, 52, 48, kTeam, ""},
    {T::kPossibleGoal, 39, 39, kGoalSlots, "ball entered the goal"},
    {T::kGoal, 8, 8, kGoalSlots, "goal by bot 3"},
    {T::kInvalidGoal, 44, 42, kGoalSlots, "ball too high"},
    {T::kAttackerDoubleTouchedBall, 14, 14, kBotLoc, ""},
    {T::kPlacementSucceeded, 5, 5, kTeam | kValue, ""},
    {T::kPenaltyKickFailed, 45, 43, kTeam | kLoc | kText, "keeper caught the ball"},
    {T::kNoProgressInGame, 2, 2, kLoc | kValue, ""},  // no by_team
    {T::kPlacementFailed, 3, 3, kTeam | kValue, ""},
    {T::kMultipleCards, 32, 32, kTeam, ""},
    {T::kMultipleFouls, 34, 34, kTeam | kText, "caused by: BOT_CRASH_UNIQUE, BOUNDARY_CROSSING"},
    {T::kBotSubstitution, 37, 37, kTeam, ""},
    {T::kTooManyRobots, 38, 38, kTeam | kLoc2 | kText, "7 on field, 6 allowed"},
    {T::kChallengeFlag, 46, 44, kTeam, ""},
    {T::kChallengeFlagHandled, 48, 46, kTeam | kText, "accepted"},
    {T::kEmergencyStop, 47, 45, kTeam, ""},
    {T::kUnsportingBehaviorMinor, 35, 35, kTeam | kText, "robot left the field without permission"},
    {T::kUnsportingBehaviorMajor, 36, 36, kTeam | kText, "repeated pushing"},
    {T::kPrepared, 1, 1, kValue, ""},  // no by_team
    {T::kIndirectGoal, 9, 9, kBotLoc | kLoc2, ""},
    {T::kChippedGoal, 10, 10, kBotLoc | kLoc2 | kValue, ""},
    {T::kKickTimeout, 12, 12, kTeam | kLoc | kValue, ""},
    {T::kAttackerTouchedOpponentInDefenseArea, 16, 16, kBotLoc | kOther, ""},
    {T::kAttackerTouchedOpponentInDefenseAreaSkipped, 42, 40, kBotLoc | kOther, ""},
    {T::kBotCrashUniqueSkipped, 23, 23, kBotLoc | kOther | kValue, ""},
    {T::kBotPushedBotSkipped, 25, 25, kBotLoc | kOther | kValue, ""},
    {T::kDefenderInDefenseAreaPartially, 30, 30, kBotLoc | kLoc2 | kValue, ""},
    {T::kMultiplePlacementFailures, 33, 33, kTeam, ""},
};

/// An event of `row`'s type with the common fields and the slots in `slots` set. Every value is exact in
/// the wire's float and µs, so a carried slot must come back bit for bit. A text slot the type does not
/// carry gets text no type parses.
GameEvent event_with(const EventOnWire& row, unsigned slots) {
  GameEvent event;
  event.id = std::string("ev-") + std::string(to_string(row.type));
  event.type = row.type;
  event.origins = {"TIGERs AutoRef", "ER-Force"};
  event.created_referee = time::Timestamp::from_microseconds(1'712'345'601'000'001);
  if (slots & kTeam) event.by_team = Team::kBlue;
  if (slots & kBot) event.by_bot = 3;
  if (slots & kOther) event.other_bot = 11;
  if (slots & kLoc) event.location = Vec2(1.5, -2.25);  // m
  if (slots & kLoc2) event.secondary_location = Vec2(-0.5, 4.0);
  if (slots & kValue) event.value = 2.75;  // SI
  if (slots & kText) event.text = (row.slots & kText) ? std::string(row.text) : "not carried";
  return event;
}

/// An event of `type` with exactly the slots it carries.
GameEvent carried_event(GameEventType type) {
  for (const auto& row : kEvents) {
    if (row.type == type) return event_with(row, row.slots);
  }
  ADD_FAILURE() << "no table row for " << to_string(type);
  return {};
}

/// The oneof member set in `event`: its field number, or 0 when none is set.
int oneof_field_number(const ::GameEvent& event) {
  const auto* oneof = ::GameEvent::descriptor()->FindOneofByName("event");
  const auto* field = event.GetReflection()->GetOneofFieldDescriptor(event, oneof);
  return field == nullptr ? 0 : field->number();
}

TEST(RefereeGatewayEncodeGameEvents, TheTableHasEveryTypeOnce) {
  std::set<GameEventType> types;
  for (const auto& row : kEvents) {
    EXPECT_NE(row.type, T::kUnknown);
    EXPECT_TRUE(types.insert(row.type).second) << to_string(row.type) << " twice";
  }
  EXPECT_EQ(types.size(), static_cast<std::size_t>(kGameEventTypeCount - 1));  // 47
}

TEST(RefereeGatewayEncodeGameEvents, EveryTypeSetsItsOwnOneofMemberAndTheLeagueTypeNumber) {
  for (const auto& row : kEvents) {
    SCOPED_TRACE(to_string(row.type));
    const ::GameEvent wire = to_proto(event_with(row, row.slots));
    EXPECT_TRUE(wire.IsInitialized()) << wire.InitializationErrorString();
    EXPECT_EQ(oneof_field_number(wire), row.oneof_field);
    ASSERT_TRUE(wire.has_type());
    EXPECT_EQ(static_cast<int>(wire.type()), row.league_type);
    EXPECT_EQ(::GameEvent::Type_Name(wire.type()), to_string(row.type));
  }
}

TEST(RefereeGatewayEncodeGameEvents, EveryTypeRoundTripsWithTheSlotsItCarries) {
  for (const auto& row : kEvents) {
    SCOPED_TRACE(to_string(row.type));
    const GameEvent event = event_with(row, row.slots);
    EXPECT_EQ(from_proto(to_proto(event)), event);

    ::GameEvent parsed;  // through the bytes, too
    ASSERT_TRUE(parsed.ParseFromString(to_proto(event).SerializeAsString()));
    EXPECT_EQ(from_proto(parsed), event);
  }
}

TEST(RefereeGatewayEncodeGameEvents, SlotsATypeDoesNotCarryAreDropped) {
  for (const auto& row : kEvents) {
    SCOPED_TRACE(to_string(row.type));
    const ::GameEvent wire = to_proto(event_with(row, kAllSlots));
    EXPECT_TRUE(wire.IsInitialized()) << wire.InitializationErrorString();
    EXPECT_EQ(from_proto(wire), event_with(row, row.slots));
  }
}

TEST(RefereeGatewayEncodeGameEvents, TheUnknownTypeSendsNoOneofMember) {
  GameEvent event;
  event.id = "ev-unknown";
  event.origins = {"autoref"};
  const ::GameEvent wire = to_proto(event);
  EXPECT_EQ(wire.event_case(), ::GameEvent::EVENT_NOT_SET);
  EXPECT_EQ(wire.type(), ::GameEvent::UNKNOWN_GAME_EVENT_TYPE);
  EXPECT_FALSE(wire.has_created_timestamp());
  EXPECT_EQ(from_proto(wire), event);

  event.type = static_cast<GameEventType>(200);  // outside the enum
  EXPECT_EQ(to_proto(event).event_case(), ::GameEvent::EVENT_NOT_SET);
  EXPECT_EQ(to_proto(event).type(), ::GameEvent::UNKNOWN_GAME_EVENT_TYPE);
}

TEST(RefereeGatewayEncodeGameEvents, TextSlotsAreParsedBackIntoTheirPayloadFields) {
  GameEvent kick;
  kick.type = T::kBotKickedBallTooFast;
  kick.text = "chipped";
  EXPECT_TRUE(to_proto(kick).bot_kicked_ball_too_fast().chipped());
  kick.text = "";
  EXPECT_FALSE(to_proto(kick).bot_kicked_ball_too_fast().chipped());
  EXPECT_EQ(from_proto(to_proto(kick)), kick);

  GameEvent handled;
  handled.type = T::kChallengeFlagHandled;
  handled.by_team = Team::kYellow;
  handled.text = "rejected";
  const ::GameEvent handled_wire = to_proto(handled);
  ASSERT_TRUE(handled_wire.challenge_flag_handled().has_accepted());  // required
  EXPECT_FALSE(handled_wire.challenge_flag_handled().accepted());
  EXPECT_EQ(from_proto(handled_wire), handled);

  GameEvent robots;
  robots.type = T::kTooManyRobots;
  robots.text = "-1 on field, 11 allowed";
  EXPECT_EQ(to_proto(robots).too_many_robots().num_robots_on_field(), -1);
  EXPECT_EQ(to_proto(robots).too_many_robots().num_robots_allowed(), 11);
  EXPECT_EQ(from_proto(to_proto(robots)), robots);
  for (const char* other : {"7 on field", "7 on field, 6 allowed!", "many on field, 6 allowed",
                            "99999999999 on field, 6 allowed"}) {
    robots.text = other;
    EXPECT_FALSE(to_proto(robots).too_many_robots().has_num_robots_on_field()) << other;
    EXPECT_FALSE(to_proto(robots).too_many_robots().has_num_robots_allowed()) << other;
  }

  GameEvent fouls;
  fouls.type = T::kMultipleFouls;
  fouls.by_team = Team::kBlue;
  fouls.text = "caused by: BOUNDARY_CROSSING, NOT_A_TYPE, BOT_DROPPED_PARTS";
  const ::GameEvent fouls_wire = to_proto(fouls);
  const auto& caused = fouls_wire.multiple_fouls().caused_game_events();
  ASSERT_EQ(caused.size(), 2);  // the unknown name is dropped
  EXPECT_EQ(caused[0].type(), ::GameEvent::BOUNDARY_CROSSING);
  EXPECT_EQ(oneof_field_number(caused[0]), 43);
  EXPECT_EQ(caused[0].boundary_crossing().by_team(), ::BLUE);
  EXPECT_EQ(caused[1].type(), ::GameEvent::BOT_DROPPED_PARTS);
  EXPECT_EQ(oneof_field_number(caused[1]), 51);
  EXPECT_EQ(from_proto(to_proto(fouls)).text, "caused by: BOUNDARY_CROSSING, BOT_DROPPED_PARTS");
}

// ---------------------------------------------------------------------------------------------------------
// Whole states

TeamInfo full_team(std::uint32_t base, const std::string& name, HullColor hull) {
  TeamInfo team;
  team.name = name;
  team.score = base + 1;
  team.red_cards = base + 2;
  team.yellow_card_times_left = {1'500'000us, std::chrono::microseconds(base * 1'000'000 + 250'000)};
  team.yellow_cards = base + 3;
  team.timeouts = base + 4;
  team.timeout_time_left = std::chrono::microseconds(base * 1'000'000 + 500'000);
  team.goalkeeper = base + 5;
  team.foul_counter = base + 6;
  team.ball_placement_failures = base + 7;
  team.can_place_ball = true;
  team.max_allowed_bots = base + 8;
  team.bot_substitution_intent = true;
  team.ball_placement_failures_reached = true;
  team.bot_substitution_allowed = true;
  team.bot_substitutions_left = base + 9;
  team.bot_substitution_time_left = std::chrono::microseconds(base * 1'000'000 + 750'000);
  team.hull_color = hull;
  return team;
}

/// Every field set, both teams different, events and proposals; all values exact in µs and float mm.
RefereeState full_state() {
  RefereeState state;
  state.source = RefereeSource::kBuiltin;
  state.source_identifier = "builtin-7d2e";
  state.match_type = MatchType::kFriendly;
  state.packet_referee = time::Timestamp::from_microseconds(1'712'345'678'901'234);
  state.receive_wall = time::Timestamp::from_nanoseconds(1'712'345'678'950'000'123);  // not on the wire
  state.stage = Stage::kExtraSecondHalf;
  state.stage_time_left = -5'000'000'123us;  // beyond 32 bits, negative: overran
  state.command = Command::kBallPlacementBlue;
  state.command_counter = 4'000'000'000u;
  state.command_referee = time::Timestamp::from_microseconds(1'712'345'600'000'001);
  state.yellow = full_team(10, "Yellow Tigers", HullColor::kDark);
  state.blue = full_team(20, "Blue Whales", HullColor::kLight);
  state.designated_position = Vec2(-1.2505, 3.0);  // m; -1250.5 mm and 3000 mm on the wire
  state.blue_team_on_positive_half = false;
  state.next_command = Command::kDirectFreeBlue;
  state.game_events = {carried_event(T::kBallLeftFieldTouchLine), carried_event(T::kBotDroppedParts)};
  state.game_event_proposals = {
      {"proposal-1", {carried_event(T::kPossibleGoal), carried_event(T::kBoundaryCrossing)}, true},
      {"proposal-2", {carried_event(T::kBotCrashDrawn)}, false},
  };
  state.current_action_time_remaining = -2'500'000'000us;
  state.status_message = "Ball placement by blue";
  return state;
}

/// from_proto with the two arguments that are not on the wire taken from `state`.
RefereeState decode_like(const ::Referee& packet, const RefereeState& state) {
  return from_proto(packet, state.receive_wall, state.source);
}

void expect_same_state(const RefereeState& got, const RefereeState& want) {
  EXPECT_EQ(got.yellow, want.yellow);  // the parts first, for a readable failure
  EXPECT_EQ(got.blue, want.blue);
  EXPECT_EQ(got.game_events, want.game_events);
  EXPECT_EQ(got.game_event_proposals, want.game_event_proposals);
  EXPECT_EQ(got, want);
}

TEST(RefereeGatewayEncode, AFullyPopulatedStateRoundTrips) {
  const RefereeState state = full_state();
  const ::Referee packet = to_proto(state);
  ASSERT_TRUE(packet.IsInitialized()) << packet.InitializationErrorString();
  expect_same_state(decode_like(packet, state), state);
}

TEST(RefereeGatewayEncode, AFullStateSetsEveryFieldOfTheLeagueMessage) {
  const ::Referee packet = to_proto(full_state());
  testing::expect_every_field_set(packet);
}

TEST(RefereeGatewayEncode, AbsentOptionalsAreNotSentAndStayAbsent) {
  RefereeState state;  // every optional absent, strings empty, no events
  state.command = Command::kStop;
  state.command_counter = 1;
  const ::Referee packet = to_proto(state);
  ASSERT_TRUE(packet.IsInitialized()) << packet.InitializationErrorString();
  EXPECT_FALSE(packet.has_source_identifier());
  EXPECT_FALSE(packet.has_stage_time_left());
  EXPECT_FALSE(packet.has_designated_position());
  EXPECT_FALSE(packet.has_blue_team_on_positive_half());
  EXPECT_FALSE(packet.has_next_command());
  EXPECT_FALSE(packet.has_current_action_time_remaining());
  EXPECT_FALSE(packet.has_status_message());
  EXPECT_EQ(packet.game_events_size(), 0);
  EXPECT_EQ(packet.game_event_proposals_size(), 0);
  expect_same_state(decode_like(packet, state), state);

  // Optionals set to values that equal the wire defaults are still sent, and stay present.
  state.stage_time_left = 0us;
  state.current_action_time_remaining = 0us;
  state.blue_team_on_positive_half = false;
  state.next_command = Command::kHalt;
  state.designated_position = Vec2(0.0, 0.0);
  const ::Referee with_zeros = to_proto(state);
  EXPECT_TRUE(with_zeros.has_stage_time_left());
  EXPECT_TRUE(with_zeros.has_designated_position());
  expect_same_state(decode_like(with_zeros, state), state);
}

TEST(RefereeGatewayEncode, TheSerialisedPacketParsesBackWithWireUnits) {
  const RefereeState state = full_state();
  const std::string bytes = to_proto(state).SerializeAsString();
  ::Referee parsed;
  ASSERT_TRUE(parsed.ParseFromString(bytes));
  EXPECT_FLOAT_EQ(parsed.designated_position().x(), -1250.5f);  // m -> mm
  EXPECT_FLOAT_EQ(parsed.designated_position().y(), 3000.0f);
  EXPECT_EQ(parsed.command_timestamp(), 1'712'345'600'000'001u);  // Unix µs
  EXPECT_EQ(parsed.packet_timestamp(), 1'712'345'678'901'234u);
  EXPECT_EQ(parsed.stage_time_left(), -5'000'000'123);  // µs
  EXPECT_EQ(parsed.current_action_time_remaining(), -2'500'000'000);
  EXPECT_EQ(parsed.yellow().timeout_time(), 10'500'000u);
  EXPECT_EQ(parsed.blue().bot_substitution_time_left(), 20'750'000u);
  expect_same_state(decode_like(parsed, state), state);

  // The same two fields checked by hand in the bytes. designated_position is field 9 (tag 0x4a), a
  // 10-byte Point: x = field 1 fixed32 (0x0d) -1250.5f = 0xC49C5000, y = field 2 (0x15) 3000.0f =
  // 0x453B8000, both little-endian.
  const std::string designated_position("\x4a\x0a\x0d\x00\x50\x9c\xc4\x15\x00\x80\x3b\x45", 12);
  EXPECT_NE(bytes.find(designated_position), std::string::npos);
  // command_timestamp is field 6 varint (tag 0x30): 1712345600000001 in 7-bit groups, low first.
  const std::string command_timestamp("\x30\x81\x80\xe2\xb9\xe8\xab\x85\x03", 9);
  EXPECT_NE(bytes.find(command_timestamp), std::string::npos);
}

TEST(RefereeGatewayEncode, AGameControllerPacketSurvivesDecodingAndReEncoding) {
  const auto receive_wall = time::Timestamp::from_nanoseconds(1'712'345'678'950'000'123);
  const RefereeState decoded = from_proto(testing::full_referee_packet(), receive_wall);
  expect_same_state(from_proto(to_proto(decoded), receive_wall), decoded);
}

TEST(RefereeGatewayEncode, OutOfRangeValuesSaturateAndNonFiniteOnesAreNotSent) {
  RefereeState state;
  state.packet_referee = time::Timestamp::from_nanoseconds(-1);  // before 1970
  state.command_referee = time::Timestamp::max();
  state.stage_time_left = -1'999ns;  // sub-µs: truncated toward zero
  state.current_action_time_remaining = time::Duration::min();
  state.command = static_cast<Command>(200);
  state.next_command = static_cast<Command>(18);
  state.stage = static_cast<Stage>(14);
  state.match_type = static_cast<MatchType>(9);
  state.yellow.yellow_card_times_left = {2h, -1s, 1'999ns};
  state.yellow.timeout_time_left = time::Duration::max();
  state.yellow.bot_substitution_time_left = -5s;
  state.yellow.hull_color = static_cast<HullColor>(7);
  state.designated_position = Vec2(1e36, -1e300);  // m: beyond a float's range in mm

  GameEvent event;
  event.type = T::kBotTooFastInStop;
  event.by_team = static_cast<Team>(5);
  event.location = Vec2(std::numeric_limits<double>::infinity(), 0.0);
  event.secondary_location = Vec2(1e39, -1e39);  // not carried by this type
  event.value = std::nan("");
  event.created_referee = time::Timestamp::from_seconds(-10.0);
  state.game_events = {event};
  event.type = T::kBotDribbledBallTooFar;
  event.location = Vec2(1e39, -1e39);
  event.value = 1e300;
  state.game_events.push_back(event);

  const ::Referee packet = to_proto(state);
  ASSERT_TRUE(packet.IsInitialized()) << packet.InitializationErrorString();
  constexpr float kMaxFloat = std::numeric_limits<float>::max();
  EXPECT_EQ(packet.packet_timestamp(), 0u);
  EXPECT_EQ(packet.command_timestamp(), static_cast<std::uint64_t>(time::Timestamp::max().microseconds()));
  EXPECT_EQ(packet.stage_time_left(), -1);
  EXPECT_EQ(packet.current_action_time_remaining(), time::Duration::min().count() / 1000);
  EXPECT_EQ(packet.command(), ::Referee::HALT);
  EXPECT_EQ(packet.next_command(), ::Referee::HALT);
  EXPECT_EQ(packet.stage(), ::Referee::NORMAL_FIRST_HALF_PRE);
  EXPECT_EQ(packet.match_type(), ::UNKNOWN_MATCH);
  ASSERT_EQ(packet.yellow().yellow_card_times_size(), 3);
  EXPECT_EQ(packet.yellow().yellow_card_times(0), std::numeric_limits<std::uint32_t>::max());  // 2 h
  EXPECT_EQ(packet.yellow().yellow_card_times(1), 0u);
  EXPECT_EQ(packet.yellow().yellow_card_times(2), 1u);
  EXPECT_EQ(packet.yellow().timeout_time(), std::numeric_limits<std::uint32_t>::max());
  EXPECT_EQ(packet.yellow().bot_substitution_time_left(), 0u);
  EXPECT_EQ(packet.yellow().hull_color(), ::HULL_COLOR_UNKNOWN);
  EXPECT_EQ(packet.designated_position().x(), kMaxFloat);
  EXPECT_EQ(packet.designated_position().y(), -kMaxFloat);

  const auto& too_fast = packet.game_events(0);
  EXPECT_EQ(too_fast.created_timestamp(), 0u);
  EXPECT_EQ(too_fast.bot_too_fast_in_stop().by_team(), ::UNKNOWN);
  EXPECT_FALSE(too_fast.bot_too_fast_in_stop().has_location());  // infinite
  EXPECT_FALSE(too_fast.bot_too_fast_in_stop().has_speed());     // NaN
  const auto& dribbled = packet.game_events(1).bot_dribbled_ball_too_far();
  EXPECT_EQ(dribbled.start().x(), kMaxFloat);
  EXPECT_EQ(dribbled.start().y(), -kMaxFloat);
  EXPECT_EQ(dribbled.end().x(), kMaxFloat);
  ::Referee parsed;
  EXPECT_TRUE(parsed.ParseFromString(packet.SerializeAsString()));

  state.designated_position = Vec2(std::nan(""), 0.0);
  EXPECT_FALSE(to_proto(state).has_designated_position());
}

}  // namespace
}  // namespace ssl::referee
