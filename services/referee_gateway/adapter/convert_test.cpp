// Conversions of the referee gateway: every Referee and TeamInfo field reaches the IDL sample in SI units,
// and every game-event oneof case maps onto its GameEventType (by the case, never by the Type number) with
// its slots filled as convert.h documents.
#include "services/referee_gateway/adapter/convert.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "idl/idl_json.h"
#include "services/referee_gateway/testing/referee_packets.h"

namespace ssl::referee {

namespace {

using testing::expect_every_field_set;
using testing::full_referee_packet;
using testing::game_event;
using testing::referee_packet;
using T = GameEventType;
namespace idl = ::ssl::idl;

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

/// Converts one event written in protobuf text format and compares it with the expected flat event.
void expect_event(std::string_view text, const GameEvent& want) {
  const GameEvent got = from_proto(game_event(text));
  EXPECT_EQ(got, want) << text;
}

// ---------------------------------------------------------------------------------------------------------
// Referee -> RefereeState -> IDL

void expect_team(const idl::referee::TeamInfo& team, std::uint32_t base, const std::string& name,
                 idl::referee::HullColor hull) {
  SCOPED_TRACE(name);
  EXPECT_EQ(team.name(), name);
  EXPECT_EQ(team.score(), base + 1);
  EXPECT_EQ(team.red_cards(), base + 2);
  ASSERT_EQ(team.yellow_card_times_left().size(), 2u);
  EXPECT_DOUBLE_EQ(team.yellow_card_times_left()[0], 1.5);  // µs -> s
  EXPECT_DOUBLE_EQ(team.yellow_card_times_left()[1], base + 0.25);
  EXPECT_EQ(team.yellow_cards(), base + 3);
  EXPECT_EQ(team.timeouts(), base + 4);
  EXPECT_DOUBLE_EQ(team.timeout_time_left(), base + 0.5);
  EXPECT_EQ(team.goalkeeper(), base + 5);
  EXPECT_EQ(team.foul_counter(), base + 6);
  EXPECT_EQ(team.ball_placement_failures(), base + 7);
  EXPECT_TRUE(team.can_place_ball());
  EXPECT_EQ(team.max_allowed_bots(), base + 8);
  EXPECT_TRUE(team.bot_substitution_intent());
  EXPECT_TRUE(team.ball_placement_failures_reached());
  EXPECT_TRUE(team.bot_substitution_allowed());
  EXPECT_EQ(team.bot_substitutions_left(), base + 9);
  EXPECT_DOUBLE_EQ(team.bot_substitution_time_left(), base + 0.75);
  EXPECT_EQ(team.hull_color(), hull);
}

TEST(RefereeGatewayConvert, TheFullTestPacketSetsEveryFieldOfTheLeagueMessage) {
  // Guards the next test: a field added to the .proto must be added to full_referee_packet (and mapped).
  const ::Referee packet = full_referee_packet();
  expect_every_field_set(packet);
  EXPECT_EQ(::Referee::descriptor()->field_count(), 17);            // the 17 fields of ssl-protocols.md section 7
  EXPECT_EQ(::Referee::TeamInfo::descriptor()->field_count(), 18);  // TeamInfo fields 1-10 and 12-19
}

TEST(RefereeGatewayConvert, EveryRefereeFieldIsMappedWithItsUnits) {
  const auto receive_wall = time::Timestamp::from_nanoseconds(1'712'345'678'950'000'123);
  const RefereeState state = from_proto(full_referee_packet(), receive_wall);
  const idl::referee::RefereeState s = to_idl(state);

  EXPECT_EQ(s.source(), idl::referee::REFEREE_SOURCE_GAME_CONTROLLER);
  EXPECT_EQ(s.source_identifier(), "6f1c2a4e-1b2d-4c3e-9f00-0123456789ab");
  EXPECT_EQ(s.match_type(), idl::referee::MATCH_TYPE_ELIMINATION_PHASE);
  EXPECT_EQ(s.packet_unix_ns(), 1'712'345'678'901'234'000);  // µs -> ns
  EXPECT_EQ(s.receive_unix_ns(), 1'712'345'678'950'000'123);
  EXPECT_EQ(s.stage(), idl::referee::STAGE_EXTRA_SECOND_HALF);
  EXPECT_DOUBLE_EQ(s.stage_time_left(), -5000.000123);  // 64-bit µs -> s, negative on overrun
  EXPECT_EQ(s.command(), idl::referee::COMMAND_BALL_PLACEMENT_BLUE);
  EXPECT_EQ(s.command_counter(), 4'000'000'000u);
  EXPECT_EQ(s.command_unix_ns(), 1'712'345'600'000'001'000);
  expect_team(s.yellow(), 10, "Yellow Tigers", idl::referee::HULL_COLOR_DARK);
  expect_team(s.blue(), 20, "Blue Whales", idl::referee::HULL_COLOR_LIGHT);
  EXPECT_TRUE(s.has_designated_position());
  EXPECT_DOUBLE_EQ(s.designated_position().x(), -1.2505);  // mm -> m
  EXPECT_DOUBLE_EQ(s.designated_position().y(), 3.0);
  EXPECT_TRUE(s.has_blue_team_on_positive_half());
  EXPECT_TRUE(s.blue_team_on_positive_half());
  EXPECT_TRUE(s.has_next_command());
  EXPECT_EQ(s.next_command(), idl::referee::COMMAND_DIRECT_FREE_BLUE);

  ASSERT_EQ(s.game_events().size(), 2u);
  const auto& ball_out = s.game_events()[0];
  EXPECT_EQ(ball_out.id(), "ev-1");
  EXPECT_EQ(ball_out.type(), idl::referee::GAME_EVENT_BALL_LEFT_FIELD_TOUCH_LINE);
  EXPECT_EQ(ball_out.origins(), (std::vector<std::string>{"TIGERs AutoRef", "ER-Force"}));
  EXPECT_EQ(ball_out.created_unix_ns(), 1'712'345'601'000'000'000);
  EXPECT_EQ(ball_out.by_team(), idl::common::TEAM_COLOR_YELLOW);
  EXPECT_TRUE(ball_out.has_by_bot());
  EXPECT_EQ(ball_out.by_bot(), 7u);
  EXPECT_FALSE(ball_out.has_other_bot());
  EXPECT_TRUE(ball_out.has_location());
  EXPECT_DOUBLE_EQ(ball_out.location().x(), 1.5);  // game events: already metres
  EXPECT_DOUBLE_EQ(ball_out.location().y(), -4.5);
  EXPECT_FALSE(ball_out.has_secondary_location());
  EXPECT_FALSE(ball_out.has_value());
  EXPECT_EQ(ball_out.text(), "");
  const auto& dropped = s.game_events()[1];
  EXPECT_EQ(dropped.type(), idl::referee::GAME_EVENT_BOT_DROPPED_PARTS);
  EXPECT_EQ(dropped.by_team(), idl::common::TEAM_COLOR_BLUE);
  EXPECT_EQ(dropped.created_unix_ns(), 0);  // not sent
  EXPECT_TRUE(dropped.origins().empty());
  EXPECT_TRUE(dropped.has_secondary_location());
  EXPECT_DOUBLE_EQ(dropped.secondary_location().x(), -1.0);
  EXPECT_DOUBLE_EQ(dropped.secondary_location().y(), 2.0);

  ASSERT_EQ(s.game_event_proposals().size(), 1u);
  EXPECT_EQ(s.game_event_proposals()[0].id(), "proposal-9");
  EXPECT_TRUE(s.game_event_proposals()[0].accepted());
  ASSERT_EQ(s.game_event_proposals()[0].events().size(), 1u);
  EXPECT_EQ(s.game_event_proposals()[0].events()[0].type(), idl::referee::GAME_EVENT_POSSIBLE_GOAL);
  EXPECT_EQ(s.game_event_proposals()[0].events()[0].by_bot(), 4u);

  EXPECT_TRUE(s.has_current_action_time_remaining());
  EXPECT_DOUBLE_EQ(s.current_action_time_remaining(), -2500.0);
  EXPECT_EQ(s.status_message(), "Ball placement by blue");
}

TEST(RefereeGatewayConvert, OptionalFieldsThatWereNotSentClearTheirFlags) {
  const idl::referee::RefereeState s =
      to_idl(from_proto(referee_packet(::Referee::HALT, 1, ""), time::Timestamp::from_seconds(1.0)));
  EXPECT_EQ(s.source_identifier(), "");
  EXPECT_EQ(s.match_type(), idl::referee::MATCH_TYPE_UNKNOWN);
  EXPECT_DOUBLE_EQ(s.stage_time_left(), 0.0);
  EXPECT_FALSE(s.has_designated_position());
  EXPECT_FALSE(s.has_blue_team_on_positive_half());
  EXPECT_FALSE(s.has_next_command());
  EXPECT_FALSE(s.has_current_action_time_remaining());
  EXPECT_TRUE(s.game_events().empty());
  EXPECT_TRUE(s.game_event_proposals().empty());
  EXPECT_EQ(s.status_message(), "");
  EXPECT_EQ(s.yellow().foul_counter(), 0u);
  EXPECT_FALSE(s.yellow().can_place_ball());
  EXPECT_EQ(s.yellow().hull_color(), idl::referee::HULL_COLOR_UNKNOWN);
  EXPECT_DOUBLE_EQ(s.yellow().timeout_time_left(), 300.0);
}

TEST(RefereeGatewayConvert, SixtyFourBitClocksKeepTheirRangeAndSign) {
  ::Referee packet = referee_packet(::Referee::STOP, 1);
  packet.set_stage_time_left(9'000'000'000'000ll);                 // 9e6 s: far beyond 32 bits of µs
  packet.set_current_action_time_remaining(-4'294'967'296'000ll);  // -2^32 ms
  const RefereeState state = from_proto(packet, {});
  EXPECT_DOUBLE_EQ(to_idl(state).stage_time_left(), 9.0e6);
  EXPECT_DOUBLE_EQ(to_idl(state).current_action_time_remaining(), -4'294'967.296);
  // Values past the nanosecond range saturate instead of overflowing.
  packet.set_stage_time_left(std::numeric_limits<std::int64_t>::min());
  packet.set_packet_timestamp(std::numeric_limits<std::uint64_t>::max());
  const RefereeState extreme = from_proto(packet, {});
  EXPECT_EQ(*extreme.stage_time_left, time::Duration::min());
  EXPECT_EQ(extreme.packet_referee, time::Timestamp::max());
}

TEST(RefereeGatewayConvert, NonFiniteDesignatedPositionIsTreatedAsNotSent) {
  ::Referee packet = referee_packet(::Referee::BALL_PLACEMENT_YELLOW, 1);
  packet.mutable_designated_position()->set_x(std::nanf(""));
  packet.mutable_designated_position()->set_y(0);
  EXPECT_FALSE(from_proto(packet, {}).designated_position);
}

TEST(RefereeGatewayConvert, EveryCommandStageAndEnumKeepsItsLeagueName) {
  for (int i = 0; i < kCommandCount; ++i) {
    ::Referee packet = referee_packet(static_cast<::Referee::Command>(i), 1);
    packet.set_next_command(static_cast<::Referee::Command>(i));
    const RefereeState state = from_proto(packet, {});
    const std::string league = ::Referee::Command_Name(static_cast<::Referee::Command>(i));
    EXPECT_EQ(to_string(state.command), league);
    EXPECT_EQ(idl::referee::to_string(to_idl(state).command()), "COMMAND_" + league);
    EXPECT_EQ(idl::referee::to_string(to_idl(state).next_command()), "COMMAND_" + league);
  }
  for (int i = 0; i < kStageCount; ++i) {
    ::Referee packet = referee_packet(::Referee::STOP, 1);
    packet.set_stage(static_cast<::Referee::Stage>(i));
    const std::string league = ::Referee::Stage_Name(static_cast<::Referee::Stage>(i));
    EXPECT_EQ(idl::referee::to_string(to_idl(from_proto(packet, {})).stage()), "STAGE_" + league);
  }
  for (::MatchType type : {::UNKNOWN_MATCH, ::GROUP_PHASE, ::ELIMINATION_PHASE, ::FRIENDLY}) {
    ::Referee packet = referee_packet(::Referee::STOP, 1);
    packet.set_match_type(type);
    const std::string name(idl::referee::to_string(to_idl(from_proto(packet, {})).match_type()));
    EXPECT_EQ(name, type == ::UNKNOWN_MATCH ? "MATCH_TYPE_UNKNOWN" : "MATCH_TYPE_" + ::MatchType_Name(type));
  }
}

TEST(RefereeGatewayConvert, DeprecatedGoalCommandsAreMapped) {
  // The Game Controller still sends one GOAL_* packet per awarded goal for compatibility.
  for (auto [league, idl_command] : {std::pair{::Referee::GOAL_YELLOW, idl::referee::COMMAND_GOAL_YELLOW},
                                     std::pair{::Referee::GOAL_BLUE, idl::referee::COMMAND_GOAL_BLUE}}) {
    ::Referee packet = referee_packet(league, 12);
    packet.set_next_command(::Referee::PREPARE_KICKOFF_BLUE);
    const idl::referee::RefereeState s = to_idl(from_proto(packet, {}));
    EXPECT_EQ(s.command(), idl_command);
    EXPECT_EQ(s.next_command(), idl::referee::COMMAND_PREPARE_KICKOFF_BLUE);
  }
}

// ---------------------------------------------------------------------------------------------------------
// Game events: every oneof case

TEST(RefereeGatewayGameEvents, EveryOneofCaseMapsToTheTypeOfItsNameNeverByNumber) {
  const auto* descriptor = ::GameEvent::descriptor();
  const auto* oneof = descriptor->FindOneofByName("event");
  ASSERT_NE(oneof, nullptr);
  ASSERT_EQ(oneof->field_count(), 47);
  std::set<GameEventType> types;
  for (int i = 0; i < oneof->field_count(); ++i) {
    const auto* field = oneof->field(i);
    const std::string name = upper(field->name());
    SCOPED_TRACE(name);
    ::GameEvent event;
    auto* payload = event.GetReflection()->MutableMessage(&event, field);
    const auto* payload_reflection = payload->GetReflection();
    const auto* payload_descriptor = payload->GetDescriptor();
    const auto* by_team = payload_descriptor->FindFieldByName("by_team");
    if (by_team != nullptr) payload_reflection->SetEnumValue(payload, by_team, ::BLUE);
    if (const auto* reason = payload_descriptor->FindFieldByName("reason")) {
      payload_reflection->SetString(payload, reason, "why");
    }
    if (const auto* accepted = payload_descriptor->FindFieldByName("accepted")) {
      payload_reflection->SetBool(payload, accepted, true);
    }
    ASSERT_TRUE(event.IsInitialized()) << event.InitializationErrorString();
    // A `type` whose NUMBER equals the oneof field number: a decoder that trusts numbers gets it wrong
    // for the events where the two differ. Leave it unset where no such Type exists.
    if (::GameEvent::Type_IsValid(field->number()))
      event.set_type(static_cast<::GameEvent::Type>(field->number()));

    // Through the wire and back, as the gateway sees it.
    std::string bytes;
    ASSERT_TRUE(event.SerializeToString(&bytes));
    ::GameEvent decoded;
    ASSERT_TRUE(decoded.ParseFromString(bytes));
    const GameEvent converted = from_proto(decoded);
    EXPECT_EQ(to_string(converted.type), name);
    ::GameEvent::Type league_type{};
    EXPECT_TRUE(::GameEvent::Type_Parse(name, &league_type)) << "the league's Type has the same name";
    EXPECT_EQ(converted.by_team, by_team != nullptr ? Team::kBlue : Team::kUnknown);
    EXPECT_EQ(idl::referee::to_string(to_idl(converted).type()), "GAME_EVENT_" + name);
    types.insert(converted.type);
  }
  EXPECT_EQ(types.size(), 47u);
}

TEST(RefereeGatewayGameEvents, CoreTypesHaveTheIdlOrder) {
  for (int i = 0; i < kGameEventTypeCount; ++i) {
    const auto type = static_cast<GameEventType>(i);
    const std::string idl_name(idl::referee::to_string(to_idl(GameEvent{.type = type}).type()));
    EXPECT_EQ(idl_name,
              type == T::kUnknown ? "GAME_EVENT_UNKNOWN" : "GAME_EVENT_" + std::string(to_string(type)));
  }
}

TEST(RefereeGatewayGameEvents, WithoutAOneofCaseTheTypeIsReadByName) {
  EXPECT_EQ(from_proto(game_event("type: BOUNDARY_CROSSING")).type, T::kBoundaryCrossing);  // 41
  EXPECT_EQ(from_proto(game_event("type: EMERGENCY_STOP")).type, T::kEmergencyStop);        // 45
  EXPECT_EQ(from_proto(game_event("id: \"x\"")).type, T::kUnknown);
  EXPECT_EQ(from_proto(game_event("type: UNKNOWN_GAME_EVENT_TYPE")).type, T::kUnknown);
}

TEST(RefereeGatewayGameEvents, TheOneofCaseWinsOverAContradictingType) {
  // boundary_crossing is oneof field 43; Type 43 is PENALTY_KICK_FAILED.
  expect_event("type: PENALTY_KICK_FAILED boundary_crossing { by_team: YELLOW location { x: -6.5 y: 4.75 } }",
               {.type = T::kBoundaryCrossing, .by_team = Team::kYellow, .location = Vec2(-6.5, 4.75)});
}

TEST(RefereeGatewayGameEvents, CommonFieldsIdOriginsAndCreationTime) {
  const GameEvent e = from_proto(game_event(
      R"(id: "abc" origin: "TIGERs" origin: "ER-Force" created_timestamp: 1712345601234567
         multiple_cards { by_team: YELLOW })"));
  EXPECT_EQ(e.id, "abc");
  EXPECT_EQ(e.origins, (std::vector<std::string>{"TIGERs", "ER-Force"}));
  ASSERT_TRUE(e.created_referee);
  EXPECT_EQ(e.created_referee->nanoseconds(), 1'712'345'601'234'567'000);
}

TEST(RefereeGatewayGameEvents, NonFiniteNumbersBecomeNotSent) {
  expect_event("bot_too_fast_in_stop { by_team: BLUE by_bot: 1 location { x: nan y: 0 } speed: inf }",
               {.type = T::kBotTooFastInStop, .by_team = Team::kBlue, .by_bot = 1u});
}

TEST(RefereeGatewayGameEvents, IdlSlotsCarryHasFlags) {
  const idl::referee::GameEvent empty = to_idl(GameEvent{.type = T::kMultipleCards, .by_team = Team::kBlue});
  EXPECT_FALSE(empty.has_by_bot());
  EXPECT_FALSE(empty.has_other_bot());
  EXPECT_FALSE(empty.has_location());
  EXPECT_FALSE(empty.has_secondary_location());
  EXPECT_FALSE(empty.has_value());
  const idl::referee::GameEvent full = to_idl(GameEvent{.type = T::kBotPushedBot,
                                                        .by_team = Team::kYellow,
                                                        .by_bot = 3u,
                                                        .other_bot = 4u,
                                                        .location = Vec2(1, 2),
                                                        .secondary_location = Vec2(3, 4),
                                                        .value = 0.5,
                                                        .text = "t"});
  EXPECT_EQ(full.by_team(), idl::common::TEAM_COLOR_YELLOW);
  EXPECT_TRUE(full.has_by_bot() && full.has_other_bot() && full.has_location() &&
              full.has_secondary_location() && full.has_value());
  EXPECT_EQ(full.by_bot(), 3u);
  EXPECT_EQ(full.other_bot(), 4u);
  EXPECT_DOUBLE_EQ(full.location().y(), 2.0);
  EXPECT_DOUBLE_EQ(full.secondary_location().x(), 3.0);
  EXPECT_DOUBLE_EQ(full.value(), 0.5);
  EXPECT_EQ(full.text(), "t");
}

// ---------------------------------------------------------------------------------------------------------
// Game events: one test per payload message (values exactly representable as float)

TEST(RefereeGatewayGameEvents, BallLeftField) {
  expect_event(
      "ball_left_field_touch_line { by_team: YELLOW by_bot: 3 location { x: 4.5 y: 3 } }",
      {.type = T::kBallLeftFieldTouchLine, .by_team = Team::kYellow, .by_bot = 3u, .location = Vec2(4.5, 3)});
  expect_event("ball_left_field_goal_line { by_team: BLUE location { x: -6 y: 0.5 } }",
               {.type = T::kBallLeftFieldGoalLine, .by_team = Team::kBlue, .location = Vec2(-6, 0.5)});
}

TEST(RefereeGatewayGameEvents, AimlessKick) {
  expect_event(
      "aimless_kick { by_team: BLUE by_bot: 1 location { x: -6 y: 1 } kick_location { x: 2 y: 0.5 } }",
      {.type = T::kAimlessKick,
       .by_team = Team::kBlue,
       .by_bot = 1u,
       .location = Vec2(-6, 1),
       .secondary_location = Vec2(2, 0.5)});
}

TEST(RefereeGatewayGameEvents, GoalPossibleGoalAndInvalidGoal) {
  const GameEvent goal{.type = T::kGoal,
                       .by_team = Team::kBlue,
                       .by_bot = 4u,
                       .location = Vec2(6, 0.25),
                       .secondary_location = Vec2(2, -1),
                       .value = 0.125,
                       .text = "nice"};
  const std::string payload =
      "{ by_team: BLUE kicking_team: YELLOW kicking_bot: 4 location { x: 6 y: 0.25 } kick_location { x: 2 y: "
      "-1 } "
      "max_ball_height: 0.125 num_robots_by_team: 6 last_touch_by_team: 1712345601000000 message: \"nice\" }";
  expect_event("goal " + payload, goal);
  GameEvent possible = goal;
  possible.type = T::kPossibleGoal;
  expect_event("possible_goal " + payload, possible);
  GameEvent invalid = goal;
  invalid.type = T::kInvalidGoal;
  expect_event("invalid_goal " + payload, invalid);
}

TEST(RefereeGatewayGameEvents, IndirectGoal) {
  expect_event(
      "indirect_goal { by_team: YELLOW by_bot: 2 location { x: 6 y: 0 } kick_location { x: 1 y: 1 } }",
      {.type = T::kIndirectGoal,
       .by_team = Team::kYellow,
       .by_bot = 2u,
       .location = Vec2(6, 0),
       .secondary_location = Vec2(1, 1)});
}

TEST(RefereeGatewayGameEvents, ChippedGoal) {
  expect_event(
      "chipped_goal { by_team: BLUE by_bot: 9 location { x: -6 y: 0 } kick_location { x: -1 y: 2 } "
      "max_ball_height: 0.5 }",
      {.type = T::kChippedGoal,
       .by_team = Team::kBlue,
       .by_bot = 9u,
       .location = Vec2(-6, 0),
       .secondary_location = Vec2(-1, 2),
       .value = 0.5});
}

TEST(RefereeGatewayGameEvents, BotTooFastInStop) {
  expect_event("bot_too_fast_in_stop { by_team: YELLOW by_bot: 5 location { x: 1 y: 2 } speed: 2.25 }",
               {.type = T::kBotTooFastInStop,
                .by_team = Team::kYellow,
                .by_bot = 5u,
                .location = Vec2(1, 2),
                .value = 2.25});
}

TEST(RefereeGatewayGameEvents, DefenderTooCloseToKickPoint) {
  expect_event(
      "defender_too_close_to_kick_point { by_team: BLUE by_bot: 6 location { x: 0 y: 1 } distance: 0.375 }",
      {.type = T::kDefenderTooCloseToKickPoint,
       .by_team = Team::kBlue,
       .by_bot = 6u,
       .location = Vec2(0, 1),
       .value = 0.375});
}

TEST(RefereeGatewayGameEvents, BotCrashDrawn) {
  expect_event(
      "bot_crash_drawn { bot_yellow: 2 bot_blue: 5 location { x: 1 y: -1 } crash_speed: 3.5 "
      "speed_diff: 0.25 crash_angle: 1.5 }",
      {.type = T::kBotCrashDrawn,
       .by_team = Team::kUnknown,
       .by_bot = 2u,
       .other_bot = 5u,
       .location = Vec2(1, -1),
       .value = 3.5});
}

TEST(RefereeGatewayGameEvents, BotCrashUniqueAndSkipped) {
  const std::string payload =
      "{ by_team: YELLOW violator: 3 victim: 6 location { x: 2 y: 2 } crash_speed: 4 speed_diff: 1 "
      "crash_angle: 0.5 }";
  const GameEvent crash{.type = T::kBotCrashUnique,
                        .by_team = Team::kYellow,
                        .by_bot = 3u,
                        .other_bot = 6u,
                        .location = Vec2(2, 2),
                        .value = 4.0};
  expect_event("bot_crash_unique " + payload, crash);
  GameEvent skipped = crash;
  skipped.type = T::kBotCrashUniqueSkipped;
  expect_event("bot_crash_unique_skipped " + payload, skipped);
}

TEST(RefereeGatewayGameEvents, BotPushedBotAndSkipped) {
  const std::string payload =
      "{ by_team: BLUE violator: 1 victim: 2 location { x: -3 y: 0 } pushed_distance: 0.75 }";
  const GameEvent pushed{.type = T::kBotPushedBot,
                         .by_team = Team::kBlue,
                         .by_bot = 1u,
                         .other_bot = 2u,
                         .location = Vec2(-3, 0),
                         .value = 0.75};
  expect_event("bot_pushed_bot " + payload, pushed);
  GameEvent skipped = pushed;
  skipped.type = T::kBotPushedBotSkipped;
  expect_event("bot_pushed_bot_skipped " + payload, skipped);
}

TEST(RefereeGatewayGameEvents, BotTippedOver) {
  expect_event(
      "bot_tipped_over { by_team: YELLOW by_bot: 8 location { x: 1 y: 1 } ball_location { x: 2 y: 2 } }",
      {.type = T::kBotTippedOver,
       .by_team = Team::kYellow,
       .by_bot = 8u,
       .location = Vec2(1, 1),
       .secondary_location = Vec2(2, 2)});
}

TEST(RefereeGatewayGameEvents, BotDroppedParts) {
  // oneof field 51, Type 47.
  expect_event(
      "bot_dropped_parts { by_team: BLUE by_bot: 0 location { x: 3 y: 1 } ball_location { x: 0 y: 0 } }",
      {.type = T::kBotDroppedParts,
       .by_team = Team::kBlue,
       .by_bot = 0u,
       .location = Vec2(3, 1),
       .secondary_location = Vec2(0, 0)});
}

TEST(RefereeGatewayGameEvents, DefenderInDefenseArea) {
  expect_event(
      "defender_in_defense_area { by_team: YELLOW by_bot: 1 location { x: -5.5 y: 0 } distance: 0.125 }",
      {.type = T::kDefenderInDefenseArea,
       .by_team = Team::kYellow,
       .by_bot = 1u,
       .location = Vec2(-5.5, 0),
       .value = 0.125});
}

TEST(RefereeGatewayGameEvents, DefenderInDefenseAreaPartially) {
  expect_event(
      "defender_in_defense_area_partially { by_team: BLUE by_bot: 2 location { x: 5.5 y: 0.5 } "
      "distance: 0.0625 ball_location { x: 5 y: 0 } }",
      {.type = T::kDefenderInDefenseAreaPartially,
       .by_team = Team::kBlue,
       .by_bot = 2u,
       .location = Vec2(5.5, 0.5),
       .secondary_location = Vec2(5, 0),
       .value = 0.0625});
}

TEST(RefereeGatewayGameEvents, AttackerTouchedBallInDefenseArea) {
  expect_event(
      "attacker_touched_ball_in_defense_area { by_team: YELLOW by_bot: 4 location { x: 5 y: 0 } "
      "distance: 0.25 }",
      {.type = T::kAttackerTouchedBallInDefenseArea,
       .by_team = Team::kYellow,
       .by_bot = 4u,
       .location = Vec2(5, 0),
       .value = 0.25});
}

TEST(RefereeGatewayGameEvents, BotKickedBallTooFast) {
  expect_event(
      "bot_kicked_ball_too_fast { by_team: BLUE by_bot: 3 location { x: 0 y: 0 } initial_ball_speed: 6.75 "
      "chipped: true }",
      {.type = T::kBotKickedBallTooFast,
       .by_team = Team::kBlue,
       .by_bot = 3u,
       .location = Vec2(0, 0),
       .value = 6.75,
       .text = "chipped"});
  expect_event("bot_kicked_ball_too_fast { by_team: BLUE by_bot: 3 initial_ball_speed: 7 chipped: false }",
               {.type = T::kBotKickedBallTooFast, .by_team = Team::kBlue, .by_bot = 3u, .value = 7.0});
}

TEST(RefereeGatewayGameEvents, BotDribbledBallTooFar) {
  expect_event(
      "bot_dribbled_ball_too_far { by_team: YELLOW by_bot: 7 start { x: 0 y: 0 } end { x: 1.25 y: 0.5 } }",
      {.type = T::kBotDribbledBallTooFar,
       .by_team = Team::kYellow,
       .by_bot = 7u,
       .location = Vec2(0, 0),
       .secondary_location = Vec2(1.25, 0.5)});
}

TEST(RefereeGatewayGameEvents, AttackerTouchedOpponentInDefenseAreaAndSkipped) {
  const std::string payload = "{ by_team: BLUE by_bot: 2 victim: 0 location { x: -5 y: 0.5 } }";
  const GameEvent touched{.type = T::kAttackerTouchedOpponentInDefenseArea,
                          .by_team = Team::kBlue,
                          .by_bot = 2u,
                          .other_bot = 0u,
                          .location = Vec2(-5, 0.5)};
  expect_event("attacker_touched_opponent_in_defense_area " + payload, touched);
  GameEvent skipped = touched;
  skipped.type = T::kAttackerTouchedOpponentInDefenseAreaSkipped;  // oneof 42, Type 40
  expect_event("attacker_touched_opponent_in_defense_area_skipped " + payload, skipped);
}

TEST(RefereeGatewayGameEvents, AttackerDoubleTouchedBall) {
  expect_event("attacker_double_touched_ball { by_team: YELLOW by_bot: 5 location { x: 0 y: 0.5 } }",
               {.type = T::kAttackerDoubleTouchedBall,
                .by_team = Team::kYellow,
                .by_bot = 5u,
                .location = Vec2(0, 0.5)});
}

TEST(RefereeGatewayGameEvents, AttackerTooCloseToDefenseArea) {
  expect_event(
      "attacker_too_close_to_defense_area { by_team: BLUE by_bot: 6 location { x: 4 y: 0 } distance: 0.25 "
      "ball_location { x: 3 y: 0 } }",
      {.type = T::kAttackerTooCloseToDefenseArea,
       .by_team = Team::kBlue,
       .by_bot = 6u,
       .location = Vec2(4, 0),
       .secondary_location = Vec2(3, 0),
       .value = 0.25});
}

TEST(RefereeGatewayGameEvents, BotHeldBallDeliberately) {
  expect_event(
      "bot_held_ball_deliberately { by_team: YELLOW by_bot: 1 location { x: 1 y: 0 } duration: 10.5 }",
      {.type = T::kBotHeldBallDeliberately,
       .by_team = Team::kYellow,
       .by_bot = 1u,
       .location = Vec2(1, 0),
       .value = 10.5});
}

TEST(RefereeGatewayGameEvents, BotInterferedPlacement) {
  expect_event(
      "bot_interfered_placement { by_team: BLUE by_bot: 4 location { x: 2 y: -2 } }",
      {.type = T::kBotInterferedPlacement, .by_team = Team::kBlue, .by_bot = 4u, .location = Vec2(2, -2)});
}

TEST(RefereeGatewayGameEvents, MultipleCards) {
  expect_event("multiple_cards { by_team: YELLOW }", {.type = T::kMultipleCards, .by_team = Team::kYellow});
}

TEST(RefereeGatewayGameEvents, MultipleFoulsNamesTheCausedEvents) {
  expect_event(
      "multiple_fouls { by_team: YELLOW caused_game_events { bot_too_fast_in_stop { by_team: YELLOW } } "
      "caused_game_events { boundary_crossing { by_team: YELLOW } } }",
      {.type = T::kMultipleFouls,
       .by_team = Team::kYellow,
       .text = "caused by: BOT_TOO_FAST_IN_STOP, BOUNDARY_CROSSING"});
  expect_event("multiple_fouls { by_team: BLUE }", {.type = T::kMultipleFouls, .by_team = Team::kBlue});
}

TEST(RefereeGatewayGameEvents, MultiplePlacementFailures) {
  expect_event("multiple_placement_failures { by_team: BLUE }",
               {.type = T::kMultiplePlacementFailures, .by_team = Team::kBlue});
}

TEST(RefereeGatewayGameEvents, KickTimeout) {
  expect_event("kick_timeout { by_team: YELLOW location { x: 1 y: 1 } time: 10 }",
               {.type = T::kKickTimeout, .by_team = Team::kYellow, .location = Vec2(1, 1), .value = 10.0});
}

TEST(RefereeGatewayGameEvents, NoProgressInGame) {
  expect_event(
      "no_progress_in_game { location { x: -1 y: 0.5 } time: 5.5 }",
      {.type = T::kNoProgressInGame, .by_team = Team::kUnknown, .location = Vec2(-1, 0.5), .value = 5.5});
}

TEST(RefereeGatewayGameEvents, PlacementFailed) {
  expect_event("placement_failed { by_team: BLUE remaining_distance: 0.5 nearest_own_bot_distance: 0.25 }",
               {.type = T::kPlacementFailed, .by_team = Team::kBlue, .value = 0.5});
}

TEST(RefereeGatewayGameEvents, UnsportingBehaviorMinor) {
  expect_event(R"(unsporting_behavior_minor { by_team: YELLOW reason: "too loud" })",
               {.type = T::kUnsportingBehaviorMinor, .by_team = Team::kYellow, .text = "too loud"});
}

TEST(RefereeGatewayGameEvents, UnsportingBehaviorMajor) {
  expect_event(R"(unsporting_behavior_major { by_team: BLUE reason: "robot thrown" })",
               {.type = T::kUnsportingBehaviorMajor, .by_team = Team::kBlue, .text = "robot thrown"});
}

TEST(RefereeGatewayGameEvents, KeeperHeldBall) {
  expect_event(
      "keeper_held_ball { by_team: YELLOW location { x: -5.75 y: 0 } duration: 5.5 }",
      {.type = T::kKeeperHeldBall, .by_team = Team::kYellow, .location = Vec2(-5.75, 0), .value = 5.5});
}

TEST(RefereeGatewayGameEvents, PlacementSucceeded) {
  expect_event("placement_succeeded { by_team: BLUE time_taken: 7.25 precision: 0.0625 distance: 1.5 }",
               {.type = T::kPlacementSucceeded, .by_team = Team::kBlue, .value = 7.25});
}

TEST(RefereeGatewayGameEvents, Prepared) {
  expect_event("prepared { time_taken: 2.5 }",
               {.type = T::kPrepared, .by_team = Team::kUnknown, .value = 2.5});
}

TEST(RefereeGatewayGameEvents, BotSubstitution) {
  expect_event("bot_substitution { by_team: YELLOW }",
               {.type = T::kBotSubstitution, .by_team = Team::kYellow});
}

TEST(RefereeGatewayGameEvents, ExcessiveBotSubstitution) {
  // oneof field 52, Type 48.
  expect_event("excessive_bot_substitution { by_team: BLUE }",
               {.type = T::kExcessiveBotSubstitution, .by_team = Team::kBlue});
}

TEST(RefereeGatewayGameEvents, ChallengeFlag) {
  // oneof field 46, Type 44.
  expect_event("challenge_flag { by_team: YELLOW }", {.type = T::kChallengeFlag, .by_team = Team::kYellow});
}

TEST(RefereeGatewayGameEvents, ChallengeFlagHandled) {
  // oneof field 48, Type 46.
  expect_event("challenge_flag_handled { by_team: BLUE accepted: true }",
               {.type = T::kChallengeFlagHandled, .by_team = Team::kBlue, .text = "accepted"});
  expect_event("challenge_flag_handled { by_team: BLUE accepted: false }",
               {.type = T::kChallengeFlagHandled, .by_team = Team::kBlue, .text = "rejected"});
}

TEST(RefereeGatewayGameEvents, EmergencyStop) {
  // oneof field 47, Type 45.
  expect_event("emergency_stop { by_team: YELLOW }", {.type = T::kEmergencyStop, .by_team = Team::kYellow});
}

TEST(RefereeGatewayGameEvents, TooManyRobots) {
  expect_event(
      "too_many_robots { by_team: BLUE num_robots_allowed: 6 num_robots_on_field: 7 "
      "ball_location { x: 0.5 y: 0.5 } }",
      {.type = T::kTooManyRobots,
       .by_team = Team::kBlue,
       .secondary_location = Vec2(0.5, 0.5),
       .text = "7 on field, 6 allowed"});
}

TEST(RefereeGatewayGameEvents, BoundaryCrossing) {
  // oneof field 43, Type 41.
  expect_event("boundary_crossing { by_team: BLUE location { x: 7 y: 0 } }",
               {.type = T::kBoundaryCrossing, .by_team = Team::kBlue, .location = Vec2(7, 0)});
}

TEST(RefereeGatewayGameEvents, PenaltyKickFailed) {
  // oneof field 45, Type 43.
  expect_event(R"(penalty_kick_failed { by_team: YELLOW location { x: 6 y: 0.5 } reason: "keeper saved" })",
               {.type = T::kPenaltyKickFailed,
                .by_team = Team::kYellow,
                .location = Vec2(6, 0.5),
                .text = "keeper saved"});
}

TEST(RefereeGatewayIdl, FromIdlInvertsToIdl) {
  RefereeState state;
  state.source = RefereeSource::kBuiltin;
  state.source_identifier = "builtin";
  state.match_type = MatchType::kFriendly;
  state.packet_referee = time::Timestamp::from_milliseconds(1'700'000'000'123);
  state.receive_wall = time::Timestamp::from_milliseconds(1'700'000'000'125);
  state.stage = Stage::kNormalSecondHalf;
  state.stage_time_left = std::chrono::milliseconds(-1500);
  state.command = Command::kBallPlacementBlue;
  state.command_counter = 42;
  state.command_referee = time::Timestamp::from_milliseconds(1'700'000'000'000);
  state.yellow.name = "Y";
  state.yellow.score = 3;
  state.yellow.yellow_card_times_left = {std::chrono::milliseconds(90'000)};
  state.yellow.hull_color = HullColor::kDark;
  state.blue.name = "B";
  state.blue.foul_counter = 2;
  state.blue.timeout_time_left = std::chrono::seconds(300);
  state.designated_position = Vec2(1.25, -2.5);
  state.blue_team_on_positive_half = true;
  state.next_command = Command::kDirectFreeBlue;
  state.game_events = {GameEvent{.id = "e1", .type = T::kBotCrashUnique, .by_team = Team::kYellow, .by_bot = 4u,
                                 .location = Vec2(0.5, 0.25), .value = 2.0}};
  state.game_event_proposals = {GameEventProposal{.id = "p", .events = state.game_events, .accepted = true}};
  state.current_action_time_remaining = std::chrono::milliseconds(2500);
  state.status_message = "placing";
  EXPECT_EQ(from_idl(to_idl(state)), state);

  const RefereeEvent event{.event = state.game_events.front(), .command = Command::kStop, .command_counter = 7,
                           .receive_wall = time::Timestamp::from_milliseconds(5)};
  EXPECT_EQ(from_idl(to_idl(event)), event);
}

TEST(RefereeGatewayIdl, EnumeratorsOutOfRangeBecomeTheFirst) {
  idl::referee::RefereeState state;
  state.command(static_cast<idl::referee::Command>(99));
  state.stage(static_cast<idl::referee::Stage>(-1));
  const RefereeState converted = from_idl(state);
  EXPECT_EQ(converted.command, Command::kHalt);
  EXPECT_EQ(converted.stage, Stage::kNormalFirstHalfPre);
}

}  // namespace
}  // namespace ssl::referee
