// The referee gateway core with scripted packets and an injected monotonic time: meaningful equality,
// heartbeat, game events once, source selection, command counter jumps, staleness.
#include "services/referee_gateway/core/gateway.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

namespace ssl::referee {
namespace {

using namespace std::chrono_literals;

const time::Timestamp kStart = time::Timestamp::from_seconds(1000.0);  // monotonic

RefereeState packet(Command command, std::uint32_t counter, const std::string& source = "gc-1") {
  RefereeState state;
  state.source_identifier = source;
  state.command = command;
  state.command_counter = counter;
  state.stage = Stage::kNormalFirstHalf;
  state.stage_time_left = 300s;
  state.yellow.name = "yellow";
  state.blue.name = "blue";
  return state;
}

GameEvent event(GameEventType type, const std::string& id, Team team = Team::kBlue) {
  GameEvent e;
  e.id = id;
  e.type = type;
  e.by_team = team;
  return e;
}

// ---------------------------------------------------------------------------------------------------------
// same_meaning

TEST(RefereeGatewayEquality, IgnoresGameEventsMatchTypeStatusMessageAndProposals) {
  const RefereeState a = packet(Command::kStop, 3);
  RefereeState b = a;
  b.status_message = "something else";
  b.match_type = MatchType::kFriendly;
  b.game_events.push_back(event(GameEventType::kGoal, "e1"));
  b.game_event_proposals.push_back({.id = "p", .events = {}, .accepted = true});
  EXPECT_TRUE(same_meaning(a, b));
  EXPECT_FALSE(a == b);
}

TEST(RefereeGatewayEquality, IgnoresTheClocksThatRunInEveryPacket) {
  RefereeState a = packet(Command::kDirectFreeBlue, 3);
  a.current_action_time_remaining = 10s;
  a.yellow.yellow_card_times_left = {100s};
  RefereeState b = a;
  b.packet_referee += 25ms;
  b.receive_wall += 25ms;
  b.stage_time_left = *a.stage_time_left - 25ms;
  b.current_action_time_remaining = 10s - 25ms;
  b.yellow.yellow_card_times_left = {100s - 25ms};
  b.yellow.timeout_time_left = 17s;
  b.blue.bot_substitution_time_left = 3s;
  EXPECT_TRUE(same_meaning(a, b));
}

TEST(RefereeGatewayEquality, EveryComparedFieldMakesADifference) {
  const std::vector<std::pair<std::string, std::function<void(RefereeState&)>>> changes = {
      {"source", [](RefereeState& s) { s.source = RefereeSource::kBuiltin; }},
      {"source_identifier", [](RefereeState& s) { s.source_identifier = "gc-2"; }},
      {"stage", [](RefereeState& s) { s.stage = Stage::kNormalHalfTime; }},
      {"command", [](RefereeState& s) { s.command = Command::kForceStart; }},
      {"command_counter", [](RefereeState& s) { s.command_counter += 1; }},
      {"command time", [](RefereeState& s) { s.command_referee += 1ms; }},
      {"next_command", [](RefereeState& s) { s.next_command = Command::kNormalStart; }},
      {"designated_position", [](RefereeState& s) { s.designated_position = Vec2(1.0, 2.0); }},
      {"blue_team_on_positive_half", [](RefereeState& s) { s.blue_team_on_positive_half = false; }},
      {"stage_time_left presence", [](RefereeState& s) { s.stage_time_left.reset(); }},
      {"current_action_time_remaining presence",
       [](RefereeState& s) { s.current_action_time_remaining = 5s; }},
      {"yellow.name", [](RefereeState& s) { s.yellow.name = "Tigers"; }},
      {"yellow.score", [](RefereeState& s) { s.yellow.score = 1; }},
      {"blue.red_cards", [](RefereeState& s) { s.blue.red_cards = 1; }},
      {"blue.active yellow cards", [](RefereeState& s) { s.blue.yellow_card_times_left = {120s}; }},
      {"blue.yellow_cards", [](RefereeState& s) { s.blue.yellow_cards = 1; }},
      {"yellow.timeouts", [](RefereeState& s) { s.yellow.timeouts = 3; }},
      {"yellow.goalkeeper", [](RefereeState& s) { s.yellow.goalkeeper = 5; }},
      {"blue.foul_counter", [](RefereeState& s) { s.blue.foul_counter = 2; }},
      {"blue.ball_placement_failures", [](RefereeState& s) { s.blue.ball_placement_failures = 1; }},
      {"blue.can_place_ball", [](RefereeState& s) { s.blue.can_place_ball = true; }},
      {"yellow.max_allowed_bots", [](RefereeState& s) { s.yellow.max_allowed_bots = 10; }},
      {"yellow.bot_substitution_intent", [](RefereeState& s) { s.yellow.bot_substitution_intent = true; }},
      {"yellow.ball_placement_failures_reached",
       [](RefereeState& s) { s.yellow.ball_placement_failures_reached = true; }},
      {"blue.bot_substitution_allowed", [](RefereeState& s) { s.blue.bot_substitution_allowed = true; }},
      {"blue.bot_substitutions_left", [](RefereeState& s) { s.blue.bot_substitutions_left = 4; }},
      {"blue.hull_color", [](RefereeState& s) { s.blue.hull_color = HullColor::kDark; }},
  };
  const RefereeState base = packet(Command::kStop, 3);
  for (const auto& [name, change] : changes) {
    RefereeState changed = base;
    change(changed);
    EXPECT_FALSE(same_meaning(base, changed)) << name;
  }
}

// ---------------------------------------------------------------------------------------------------------
// referee.state publication: change and heartbeat

TEST(RefereeGatewayHeartbeat, FirstPacketIsPublished) {
  RefereeGateway gateway({});
  const StepOutput out = gateway.on_packet(packet(Command::kHalt, 1), kStart);
  EXPECT_EQ(out.verdict, PacketVerdict::kAccepted);
  EXPECT_EQ(out.reason, PublishReason::kFirst);
  ASSERT_TRUE(out.state);
  EXPECT_EQ(out.state->command, Command::kHalt);
}

TEST(RefereeGatewayHeartbeat, StatusMessageChangeAloneWaitsForTheHeartbeat) {
  RefereeGateway gateway({.heartbeat_period = 1s});
  ASSERT_TRUE(gateway.on_packet(packet(Command::kStop, 1), kStart).state);
  RefereeState with_message = packet(Command::kStop, 1);
  with_message.status_message = "Ball left the field";
  for (auto t = 25ms; t < 1s; t += 25ms) {
    const StepOutput out = gateway.on_packet(with_message, kStart + t);
    EXPECT_FALSE(out.state) << "republished after " << time::to_string(t);
  }
  const StepOutput heartbeat = gateway.on_packet(with_message, kStart + 1s);
  EXPECT_EQ(heartbeat.reason, PublishReason::kHeartbeat);
  ASSERT_TRUE(heartbeat.state);
  EXPECT_EQ(heartbeat.state->status_message, "Ball left the field");
}

TEST(RefereeGatewayHeartbeat, CommandChangeIsPublishedAtOnce) {
  RefereeGateway gateway({.heartbeat_period = 1s});
  ASSERT_TRUE(gateway.on_packet(packet(Command::kStop, 1), kStart).state);
  EXPECT_FALSE(gateway.on_packet(packet(Command::kStop, 1), kStart + 25ms).state);
  const StepOutput out = gateway.on_packet(packet(Command::kForceStart, 2), kStart + 50ms);
  EXPECT_EQ(out.reason, PublishReason::kChange);
  ASSERT_TRUE(out.state);
  EXPECT_EQ(out.state->command, Command::kForceStart);
  EXPECT_EQ(out.state->command_counter, 2u);
}

TEST(RefereeGatewayHeartbeat, UnchangedStateIsRepublishedOncePerPeriodAt40Hz) {
  RefereeGateway gateway({.heartbeat_period = 1s});
  int published = 0;
  int heartbeats = 0;
  for (auto t = 0ms; t <= 3000ms; t += 25ms) {  // the Game Controller's rate
    RefereeState p = packet(Command::kStop, 1);
    p.stage_time_left = 300s - t;  // running clocks alone are no change
    const StepOutput out = gateway.on_packet(std::move(p), kStart + t);
    if (out.state) ++published;
    if (out.reason == PublishReason::kHeartbeat) ++heartbeats;
  }
  EXPECT_EQ(published, 4);  // the first packet, then at 1 s, 2 s, 3 s
  EXPECT_EQ(heartbeats, 3);
  EXPECT_EQ(gateway.counters().heartbeats, 3u);
  EXPECT_EQ(gateway.counters().states_published, 4u);
  EXPECT_EQ(gateway.counters().accepted, 121u);
}

TEST(RefereeGatewayHeartbeat, AChangeRestartsTheHeartbeatPeriod) {
  RefereeGateway gateway({.heartbeat_period = 1s});
  ASSERT_TRUE(gateway.on_packet(packet(Command::kStop, 1), kStart).state);
  ASSERT_TRUE(gateway.on_packet(packet(Command::kForceStart, 2), kStart + 600ms).state);
  EXPECT_FALSE(gateway.on_packet(packet(Command::kForceStart, 2), kStart + 1100ms).state);
  EXPECT_EQ(gateway.on_packet(packet(Command::kForceStart, 2), kStart + 1600ms).reason,
            PublishReason::kHeartbeat);
}

TEST(RefereeGatewayHeartbeat, PublishedStateIsTheLatestPacketInFull) {
  // Transient local keeps only the last sample: it must carry the current events and status message.
  RefereeGateway gateway({.heartbeat_period = 1s});
  ASSERT_TRUE(gateway.on_packet(packet(Command::kStop, 1), kStart).state);
  RefereeState latest = packet(Command::kStop, 1);
  latest.game_events = {event(GameEventType::kBallLeftFieldGoalLine, "e1")};
  latest.status_message = "goal line";
  latest.match_type = MatchType::kGroupPhase;
  latest.stage_time_left = 200s;
  EXPECT_FALSE(gateway.on_packet(latest, kStart + 500ms).state);
  const StepOutput out = gateway.on_packet(latest, kStart + 1s);
  ASSERT_TRUE(out.state);
  EXPECT_EQ(*out.state, latest);
  EXPECT_EQ(*gateway.last_published(), latest);
}

// ---------------------------------------------------------------------------------------------------------
// referee.event: each game event once

TEST(RefereeGatewayEvents, EventWithIdIsPublishedOnceWithTheCommandInForce) {
  RefereeGateway gateway({});
  RefereeState p = packet(Command::kStop, 4);
  p.receive_wall = time::Timestamp::from_seconds(1.7e9);
  p.game_events = {event(GameEventType::kBotTooFastInStop, "e-1", Team::kYellow)};
  const StepOutput first = gateway.on_packet(p, kStart);
  ASSERT_EQ(first.events.size(), 1u);
  EXPECT_EQ(first.events[0].event, p.game_events[0]);
  EXPECT_EQ(first.events[0].command, Command::kStop);
  EXPECT_EQ(first.events[0].command_counter, 4u);
  EXPECT_EQ(first.events[0].receive_wall, p.receive_wall);
  for (int i = 1; i <= 80; ++i) {
    EXPECT_TRUE(gateway.on_packet(p, kStart + i * 25ms).events.empty());
  }
  // The same event later, next to a new one: only the new one goes out.
  p.command = Command::kBallPlacementBlue;
  p.command_counter = 5;
  p.game_events.push_back(event(GameEventType::kPlacementSucceeded, "e-2"));
  const StepOutput second = gateway.on_packet(p, kStart + 3s);
  ASSERT_EQ(second.events.size(), 1u);
  EXPECT_EQ(second.events[0].event.id, "e-2");
  EXPECT_EQ(second.events[0].command, Command::kBallPlacementBlue);
  EXPECT_EQ(gateway.counters().events_published, 2u);
}

TEST(RefereeGatewayEvents, EventsWithoutIdArePublishedOnceByContent) {
  RefereeGateway gateway({});
  GameEvent a = event(GameEventType::kBotCrashDrawn, "", Team::kUnknown);
  a.by_bot = 3;
  a.other_bot = 5;
  a.location = Vec2(1.0, -2.0);
  a.value = 2.5;
  GameEvent b = a;
  b.location = Vec2(1.0, -2.5);  // another crash elsewhere
  RefereeState p = packet(Command::kStop, 1);
  p.game_events = {a};
  EXPECT_EQ(gateway.on_packet(p, kStart).events.size(), 1u);
  EXPECT_EQ(gateway.on_packet(p, kStart + 25ms).events.size(), 0u);
  p.game_events = {a, b};
  const StepOutput out = gateway.on_packet(p, kStart + 50ms);
  ASSERT_EQ(out.events.size(), 1u);
  EXPECT_EQ(out.events[0].event, b);
}

TEST(RefereeGatewayEvents, EventKeyPrefersTheIdAndOtherwiseSeesEveryField) {
  GameEvent a = event(GameEventType::kGoal, "id-1");
  GameEvent b = a;
  b.value = 0.1;
  EXPECT_EQ(event_key(a), event_key(b));  // same id: same event, whatever the content
  a.id.clear();
  b.id.clear();
  EXPECT_NE(event_key(a), event_key(b));
  b = a;
  b.text = "x";
  EXPECT_NE(event_key(a), event_key(b));
  b = a;
  b.origins = {"autoref"};
  EXPECT_NE(event_key(a), event_key(b));
  b = a;
  b.created_referee = time::Timestamp::from_seconds(5.0);
  EXPECT_NE(event_key(a), event_key(b));
  b = a;
  b.secondary_location = Vec2(0, 0);
  EXPECT_NE(event_key(a), event_key(b));
}

TEST(RefereeGatewayEvents, OnlyTheLastRememberedEventsAreKept) {
  RefereeGateway gateway({.remembered_events = 2});
  RefereeState p = packet(Command::kStop, 1);
  for (const char* id : {"a", "b", "c"}) {
    p.game_events = {event(GameEventType::kGoal, id)};
    EXPECT_EQ(gateway.on_packet(p, kStart).events.size(), 1u) << id;
  }
  p.game_events = {event(GameEventType::kGoal, "c")};
  EXPECT_TRUE(gateway.on_packet(p, kStart).events.empty());
  p.game_events = {event(GameEventType::kGoal, "a")};  // forgotten: published again
  EXPECT_EQ(gateway.on_packet(p, kStart).events.size(), 1u);
}

// ---------------------------------------------------------------------------------------------------------
// Source selection

TEST(RefereeGatewaySource, AutoFollowsTheFirstSourceAndCountsTheOthers) {
  RefereeGateway gateway({.source_switch_after = 2s});
  ASSERT_EQ(gateway.on_packet(packet(Command::kStop, 1, "gc-1"), kStart).verdict, PacketVerdict::kAccepted);
  RefereeState stray = packet(Command::kForceStart, 90, "stray");
  stray.game_events = {event(GameEventType::kGoal, "stray-goal")};
  for (int i = 1; i <= 10; ++i) {
    const StepOutput out = gateway.on_packet(stray, kStart + i * 25ms);
    EXPECT_EQ(out.verdict, PacketVerdict::kForeignSource);
    EXPECT_FALSE(out.state);
    EXPECT_TRUE(out.events.empty());
    EXPECT_TRUE(gateway.on_packet(packet(Command::kStop, 1, "gc-1"), kStart + i * 25ms).events.empty());
  }
  EXPECT_EQ(gateway.counters().foreign_source, 10u);
  EXPECT_EQ(gateway.counters().accepted, 11u);
  EXPECT_EQ(gateway.counters().packets, 21u);
  EXPECT_EQ(gateway.chosen_source(), "gc-1");
  EXPECT_EQ(gateway.last_foreign_source(), "stray");
  EXPECT_EQ(gateway.last_published()->command, Command::kStop);
}

TEST(RefereeGatewaySource, AutoSwitchesOnlyAfterTheChosenSourceWasSilent) {
  RefereeGateway gateway({.source_switch_after = 2s});
  ASSERT_TRUE(gateway.on_packet(packet(Command::kStop, 1, "gc-1"), kStart).state);
  EXPECT_EQ(gateway.on_packet(packet(Command::kHalt, 7, "gc-2"), kStart + 1999ms).verdict,
            PacketVerdict::kForeignSource);
  const StepOutput out = gateway.on_packet(packet(Command::kHalt, 7, "gc-2"), kStart + 2s);
  EXPECT_EQ(out.verdict, PacketVerdict::kAccepted);
  EXPECT_EQ(out.switched_from, "gc-1");
  EXPECT_FALSE(out.counter_jump);  // 1 -> 7 across sources is not a jump
  ASSERT_TRUE(out.state);
  EXPECT_EQ(out.state->source_identifier, "gc-2");
  EXPECT_EQ(gateway.chosen_source(), "gc-2");
  EXPECT_EQ(gateway.counters().source_switches, 1u);
  // The old one is now the foreign one.
  EXPECT_EQ(gateway.on_packet(packet(Command::kStop, 2, "gc-1"), kStart + 2100ms).verdict,
            PacketVerdict::kForeignSource);
}

TEST(RefereeGatewaySource, AFixedSourceIsTheOnlyOneEverAccepted) {
  RefereeGateway gateway({.source_identifier = std::string("gc-wanted"), .source_switch_after = 1s});
  EXPECT_EQ(gateway.chosen_source(), "gc-wanted");
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(gateway.on_packet(packet(Command::kStop, 1, "gc-other"), kStart + i * 10s).verdict,
              PacketVerdict::kForeignSource);
  }
  EXPECT_FALSE(gateway.last_published());
  EXPECT_TRUE(gateway.liveness(kStart + 40s).stale);
  EXPECT_EQ(gateway.on_packet(packet(Command::kStop, 1, "gc-wanted"), kStart + 41s).verdict,
            PacketVerdict::kAccepted);
  EXPECT_EQ(gateway.counters().foreign_source, 5u);
  EXPECT_EQ(gateway.counters().source_switches, 0u);
}

TEST(RefereeGatewaySource, PacketsWithoutIdentifierAreOneSourceOfTheirOwn) {
  RefereeGateway gateway({});
  EXPECT_EQ(gateway.on_packet(packet(Command::kStop, 1, ""), kStart).verdict, PacketVerdict::kAccepted);
  EXPECT_EQ(gateway.on_packet(packet(Command::kStop, 1, "gc-1"), kStart).verdict,
            PacketVerdict::kForeignSource);
  EXPECT_EQ(gateway.on_packet(packet(Command::kStop, 1, ""), kStart).verdict, PacketVerdict::kAccepted);
}

// ---------------------------------------------------------------------------------------------------------
// Command counter

TEST(RefereeGatewayCounter, RepeatsAndSingleStepsAreNotJumps) {
  RefereeGateway gateway({});
  for (std::uint32_t counter : {5u, 5u, 5u, 6u, 6u, 7u}) {
    EXPECT_FALSE(gateway.on_packet(packet(Command::kStop, counter), kStart).counter_jump) << counter;
  }
  EXPECT_EQ(gateway.counters().counter_jumps, 0u);
}

TEST(RefereeGatewayCounter, SkipsAndStepsBackAreCountedAndReported) {
  RefereeGateway gateway({});
  (void)gateway.on_packet(packet(Command::kStop, 5), kStart);
  const StepOutput skip = gateway.on_packet(packet(Command::kForceStart, 9), kStart + 25ms);
  ASSERT_TRUE(skip.counter_jump);
  EXPECT_EQ(*skip.counter_jump, (CounterJump{.from = 5, .to = 9}));
  EXPECT_TRUE(skip.state);  // still published: the new command is real
  const StepOutput back = gateway.on_packet(packet(Command::kStop, 2), kStart + 50ms);
  ASSERT_TRUE(back.counter_jump);
  EXPECT_EQ(*back.counter_jump, (CounterJump{.from = 9, .to = 2}));
  EXPECT_FALSE(gateway.on_packet(packet(Command::kStop, 3), kStart + 75ms).counter_jump);
  EXPECT_EQ(gateway.counters().counter_jumps, 2u);
}

TEST(RefereeGatewayCounter, WrapAroundIsASingleStep) {
  RefereeGateway gateway({});
  (void)gateway.on_packet(packet(Command::kStop, 0xFFFFFFFFu), kStart);
  EXPECT_FALSE(gateway.on_packet(packet(Command::kForceStart, 0), kStart).counter_jump);
  EXPECT_EQ(gateway.counters().counter_jumps, 0u);
}

// ---------------------------------------------------------------------------------------------------------
// Staleness

TEST(RefereeGatewayStale, StaleBeforeTheFirstPacketWithoutAnAge) {
  RefereeGateway gateway({.stale_after = 1s});
  const Liveness liveness = gateway.liveness(kStart);
  EXPECT_TRUE(liveness.stale);
  EXPECT_FALSE(liveness.age);
}

TEST(RefereeGatewayStale, StaleOnceNoPacketArrivedForStaleAfter) {
  RefereeGateway gateway({.stale_after = 1s});
  (void)gateway.on_packet(packet(Command::kStop, 1), kStart);
  EXPECT_FALSE(gateway.liveness(kStart + 500ms).stale);
  EXPECT_FALSE(gateway.liveness(kStart + 1s).stale);
  const Liveness late = gateway.liveness(kStart + 1500ms);
  EXPECT_TRUE(late.stale);
  ASSERT_TRUE(late.age);
  EXPECT_EQ(*late.age, 1500ms);
  (void)gateway.on_packet(packet(Command::kStop, 1), kStart + 1600ms);
  EXPECT_FALSE(gateway.liveness(kStart + 1700ms).stale);
}

TEST(RefereeGatewayStale, ForeignPacketsDoNotKeepTheRefereeAlive) {
  RefereeGateway gateway({.source_identifier = std::nullopt, .stale_after = 1s});
  (void)gateway.on_packet(packet(Command::kStop, 1, "gc-1"), kStart);
  for (auto t = 100ms; t < 1900ms; t += 100ms)
    (void)gateway.on_packet(packet(Command::kStop, 1, "x"), kStart + t);
  EXPECT_TRUE(gateway.liveness(kStart + 1900ms).stale);
}

// ---------------------------------------------------------------------------------------------------------
// Names

TEST(RefereeGatewayNames, LeagueNamesRoundTrip) {
  EXPECT_EQ(to_string(Command::kGoalBlue), "GOAL_BLUE");
  EXPECT_EQ(to_string(Stage::kPenaltyShootoutBreak), "PENALTY_SHOOTOUT_BREAK");
  EXPECT_EQ(to_string(static_cast<Command>(200)), "UNKNOWN");
  for (int i = 0; i < kGameEventTypeCount; ++i) {
    const auto type = static_cast<GameEventType>(i);
    EXPECT_EQ(parse_game_event_type(to_string(type)), type) << to_string(type);
  }
  EXPECT_EQ(parse_game_event_type("NO_SUCH_EVENT"), std::nullopt);
}

}  // namespace
}  // namespace ssl::referee

namespace ssl::referee {
namespace {

TEST(RefereeGameEventKinds, FoulsAreTheRulesFoulsAndNothingElse) {
  using T = GameEventType;
  for (T foul : {T::kBotCrashUnique, T::kBotTooFastInStop, T::kAttackerDoubleTouchedBall, T::kDefenderInDefenseArea,
                 T::kBotInterferedPlacement, T::kDefenderTooCloseToKickPoint, T::kBoundaryCrossing}) {
    EXPECT_TRUE(is_foul(foul)) << to_string(foul);
  }
  for (T other : {T::kUnknown, T::kGoal, T::kBallLeftFieldTouchLine, T::kPlacementSucceeded, T::kNoProgressInGame,
                  T::kMultipleFouls, T::kMultipleCards, T::kPossibleGoal, T::kAimlessKick}) {
    EXPECT_FALSE(is_foul(other)) << to_string(other);
  }
}

TEST(RefereeGameEventKinds, AvoidableFoulsAreFoulsATeamCommitsAlone) {
  using T = GameEventType;
  for (T avoidable : {T::kBotCrashUnique, T::kBotCrashDrawn, T::kBotTooFastInStop, T::kAttackerDoubleTouchedBall,
                      T::kDefenderInDefenseArea, T::kAttackerTooCloseToDefenseArea, T::kDefenderTooCloseToKickPoint}) {
    EXPECT_TRUE(is_avoidable_foul(avoidable)) << to_string(avoidable);
    EXPECT_TRUE(is_foul(avoidable)) << to_string(avoidable);
  }
  // Fouls of a contest (pushing, a keeper or dribbler pressed), leaving the field, the ball's measured speed,
  // and events that are no fouls are not counted as avoidable.
  for (T other : {T::kBotPushedBot, T::kKeeperHeldBall, T::kBotDribbledBallTooFar, T::kBoundaryCrossing,
                  T::kBotKickedBallTooFast, T::kGoal, T::kBallLeftFieldGoalLine, T::kUnknown}) {
    EXPECT_FALSE(is_avoidable_foul(other)) << to_string(other);
  }
}

}  // namespace
}  // namespace ssl::referee
