// The built-in referee driven by scripted observations at explicit times (no sleeps, no threads). Field:
// division B (9 x 6 m, goals 1 m wide, defense areas 2 x 1 m); blue defends the goal at +x unless a test
// says otherwise (kBlueOnPositive; a match starts with blue on the negative half), so yellow attacks +x.
#include "services/referee_gateway/builtin/builtin_referee.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace ssl::referee {
namespace {

using geom::Vec2;
using time::duration_from_seconds;
using time::Timestamp;

const Timestamp kStart = Timestamp::from_seconds(1'700'000'000.0);

Timestamp at(double seconds) { return kStart + duration_from_seconds(seconds); }

RefereeProfile builtin_profile(const char* name) {
  auto profile = load_referee_profile(name);
  EXPECT_TRUE(profile) << profile.error().message;
  return profile ? *profile : RefereeProfile{};
}

/// Blue defends +x (the default is the other half): the setup of most tests here.
const MatchSetup kBlueOnPositive{.blue_on_positive_half = true};

ObservedRobot yellow(std::uint32_t id, Vec2 position) { return {TeamColor::kYellow, id, position}; }
ObservedRobot blue(std::uint32_t id, Vec2 position) { return {TeamColor::kBlue, id, position}; }

Observation ball_at(Vec2 ball, std::vector<ObservedRobot> robots = {}) {
  return {.ball_position = ball, .ball_velocity = Vec2::Zero(), .robots = std::move(robots)};
}

/// As SSL-Vision sees it: no measured ball velocity, the referee differentiates the positions.
Observation seen(Vec2 ball, std::vector<ObservedRobot> robots) {
  return {.ball_position = ball, .ball_velocity = std::nullopt, .robots = std::move(robots)};
}

/// A referee in NORMAL_FIRST_HALF with the ball in play (FORCE_START at t = 0).
BuiltinReferee running_referee(RefereeProfile profile) {
  BuiltinReferee referee(std::move(profile), FieldGeometry::division_b(),
                         {.yellow = {"Yellow FC", 0}, .blue = {"Blue FC", 0}, .blue_on_positive_half = true});
  EXPECT_TRUE(referee.command(Command::kForceStart, at(0)));
  return referee;
}

const GameEvent* last_event(const BuiltinReferee& referee) {
  return referee.state().game_events.empty() ? nullptr : &referee.state().game_events.back();
}

void expect_near(const std::optional<Vec2>& actual, const Vec2& expected) {
  ASSERT_TRUE(actual.has_value());
  EXPECT_NEAR(actual->x(), expected.x(), 1e-9);
  EXPECT_NEAR(actual->y(), expected.y(), 1e-9);
}

// ---------------------------------------------------------------------------------------------------------
// Commands, counter, times, stages

TEST(BuiltinReferee, StartsHaltedBeforeTheFirstHalfWithTheKickoffPending) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_a(),
                         {.yellow = {"Yellow FC", 1}, .blue = {"Blue FC", 2}, .max_allowed_bots = 11});
  const RefereeState& state = referee.state();
  EXPECT_EQ(state.source, RefereeSource::kBuiltin);
  EXPECT_EQ(state.command, Command::kHalt);
  EXPECT_EQ(state.command_counter, 0u);
  EXPECT_EQ(state.stage, Stage::kNormalFirstHalfPre);
  EXPECT_EQ(state.next_command, Command::kPrepareKickoffYellow);
  EXPECT_EQ(state.yellow.name, "Yellow FC");
  EXPECT_EQ(state.blue.goalkeeper, 2u);
  EXPECT_TRUE(state.yellow.can_place_ball);
  EXPECT_EQ(state.blue.max_allowed_bots, 11u);
  EXPECT_EQ(state.yellow.timeouts, 4u);
  EXPECT_EQ(state.blue_team_on_positive_half, false) << "blue starts on the negative half, as with a GC";
}

TEST(BuiltinReferee, EveryCommandIncrementsTheCounterAndIsStampedWithItsTime) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  referee.step(ball_at({0, 0}), at(0));
  EXPECT_EQ(referee.state().command_referee, at(0)) << "the initial HALT is stamped by the first step";
  EXPECT_EQ(referee.state().packet_referee, at(0));

  ASSERT_TRUE(referee.command(Command::kStop, at(1)));
  EXPECT_EQ(referee.state().command_counter, 1u);
  EXPECT_EQ(referee.state().command_referee, at(1));
  referee.step(ball_at({0, 0}), at(1.5));
  EXPECT_EQ(referee.state().packet_referee, at(1.5));
  EXPECT_EQ(referee.state().command_referee, at(1)) << "steps do not restamp the command";
  ASSERT_TRUE(referee.command(Command::kStop, at(2)));
  EXPECT_EQ(referee.state().command_counter, 2u) << "a repeated command is a new command";
  EXPECT_EQ(referee.state().command_referee, at(2));
}

TEST(BuiltinReferee, OperatorCommandsSetNextCommandDesignatedPositionAndTimeouts) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kPrepareKickoffBlue, at(0)));
  EXPECT_EQ(referee.state().next_command, Command::kNormalStart);
  referee.step(ball_at({0, 0}), at(0.5));
  ASSERT_TRUE(referee.command(Command::kNormalStart, at(1)));
  EXPECT_EQ(referee.state().stage, Stage::kNormalFirstHalf);
  EXPECT_EQ(referee.state().stage_time_left, duration_from_seconds(300));
  EXPECT_FALSE(referee.game_running()) << "the kickoff is in play only once the ball moved";
  referee.step(ball_at({0.03, 0}), at(1.5));
  EXPECT_FALSE(referee.game_running());
  referee.step(ball_at({0.06, 0}), at(2));
  EXPECT_TRUE(referee.game_running());
  EXPECT_EQ(referee.state().command, Command::kNormalStart) << "in play changes no command";

  const std::uint32_t counter = referee.state().command_counter;
  EXPECT_FALSE(referee.command(Command::kBallPlacementYellow, at(3)));
  EXPECT_FALSE(referee.command(Command::kBallPlacementYellow, at(3), Vec2(std::nan(""), 0)));
  EXPECT_FALSE(referee.command(Command::kGoalBlue, at(3)));
  EXPECT_FALSE(referee.command(Command::kIndirectFreeYellow, at(3)));
  EXPECT_FALSE(referee.command(static_cast<Command>(42), at(3)));
  EXPECT_EQ(referee.counters().rejected_commands, 5u);
  EXPECT_EQ(referee.state().command_counter, counter);

  ASSERT_TRUE(referee.command(Command::kBallPlacementYellow, at(3), Vec2(1.0, -2.0)));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow);
  expect_near(referee.state().designated_position, {1.0, -2.0});
  EXPECT_EQ(referee.state().next_command, Command::kDirectFreeYellow);
  EXPECT_EQ(referee.state().current_action_time_remaining, duration_from_seconds(30));

  ASSERT_TRUE(referee.command(Command::kHalt, at(4)));
  EXPECT_FALSE(referee.state().designated_position);
  ASSERT_TRUE(referee.command(Command::kTimeoutYellow, at(5)));
  EXPECT_EQ(referee.state().yellow.timeouts, 3u);
  referee.step(ball_at({0, 0}), at(65));
  EXPECT_EQ(referee.state().yellow.timeout_time_left, duration_from_seconds(240));
  EXPECT_EQ(referee.state().blue.timeout_time_left, duration_from_seconds(300));
}

TEST(BuiltinReferee, StagesRunOnPlayingTimeThenHalfTimeThenTheSecondHalfKickoffOfTheOtherTeam) {
  RefereeProfile profile = builtin_profile("strict_ai");
  profile.game.half_duration = 10;
  profile.game.half_time = 5;
  profile.game.extra_time.enabled = false;
  BuiltinReferee referee(profile, FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kForceStart, at(0)));
  EXPECT_EQ(referee.state().stage, Stage::kNormalFirstHalf);
  referee.step(ball_at({0, 0}), at(4));
  EXPECT_EQ(referee.state().stage_time_left, duration_from_seconds(6));
  ASSERT_TRUE(referee.command(Command::kStop, at(4)));
  referee.step(ball_at({0, 0}), at(7));
  EXPECT_EQ(referee.state().stage_time_left, duration_from_seconds(6)) << "the clock stops in STOP";
  ASSERT_TRUE(referee.command(Command::kForceStart, at(7)));
  referee.step(ball_at({0, 0}), at(12.9));
  EXPECT_EQ(referee.state().stage, Stage::kNormalFirstHalf);
  referee.step(ball_at({0, 0}), at(13));
  EXPECT_EQ(referee.state().stage, Stage::kNormalHalfTime);
  EXPECT_EQ(referee.state().command, Command::kHalt);
  EXPECT_EQ(referee.state().stage_time_left, duration_from_seconds(5));
  referee.step(ball_at({0, 0}), at(16));
  EXPECT_EQ(referee.state().stage_time_left, duration_from_seconds(2)) << "half time runs in HALT";
  EXPECT_EQ(referee.state().blue_team_on_positive_half, true);
  referee.step(ball_at({0, 0}), at(18));
  EXPECT_EQ(referee.state().stage, Stage::kNormalSecondHalfPre);
  EXPECT_EQ(referee.state().blue_team_on_positive_half, false) << "the teams change sides at half time";
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_EQ(referee.state().next_command, Command::kPrepareKickoffBlue);
  EXPECT_FALSE(referee.state().stage_time_left);
  referee.step(ball_at({0, 0}), at(30));
  EXPECT_EQ(referee.state().command, Command::kStop) << "strict_ai waits for the operator's kickoff";

  ASSERT_TRUE(referee.command(Command::kPrepareKickoffBlue, at(31)));
  ASSERT_TRUE(referee.command(Command::kNormalStart, at(32)));
  EXPECT_EQ(referee.state().stage, Stage::kNormalSecondHalf);
  EXPECT_EQ(referee.state().stage_time_left, duration_from_seconds(10));
  ASSERT_TRUE(referee.next_stage(at(33)));
  EXPECT_EQ(referee.state().stage, Stage::kPostGame);
  EXPECT_EQ(referee.state().command, Command::kHalt);
  EXPECT_FALSE(referee.next_stage(at(34)));
}

TEST(BuiltinReferee, ArcadeRunsTheKickoffByItselfAfterOneStop) {
  BuiltinReferee referee(builtin_profile("arcade"), FieldGeometry::division_b(), kBlueOnPositive);
  referee.step(ball_at({0, 0}), at(0));
  ASSERT_TRUE(referee.command(Command::kStop, at(1)));
  referee.step(ball_at({0, 0}), at(2.9));
  EXPECT_EQ(referee.state().command, Command::kStop);
  referee.step(ball_at({0, 0}), at(3));
  EXPECT_EQ(referee.state().command, Command::kPrepareKickoffYellow);
  referee.step(ball_at({0, 0}), at(5));
  EXPECT_EQ(referee.state().command, Command::kNormalStart);
  EXPECT_EQ(referee.state().stage, Stage::kNormalFirstHalf);
  EXPECT_EQ(referee.state().command_counter, 3u);
}

// ---------------------------------------------------------------------------------------------------------
// Resuming after a restart (the service's state file)

/// A match in its first half, 2 : 1, a yellow card on blue, with the ball in play since t = 10.
RefereeState state_in_play() {
  BuiltinReferee referee(builtin_profile("arcade"), FieldGeometry::division_b(), kBlueOnPositive);
  EXPECT_TRUE(referee.command(Command::kPrepareKickoffYellow, at(0)));
  EXPECT_TRUE(referee.command(Command::kNormalStart, at(1)));
  EXPECT_TRUE(referee.command(Command::kForceStart, at(10)));
  referee.step(ball_at({1, 1}), at(40));
  RefereeState state = referee.state();
  state.yellow.score = 2;
  state.blue.score = 1;
  state.blue.yellow_cards = 1;
  state.blue.yellow_card_times_left = {duration_from_seconds(60)};
  state.blue.foul_counter = 3;
  return state;
}

TEST(BuiltinRefereeResume, AMatchInPlayGoesOnWithItsScoreStageAndClocksAfterAStopAndAForceStart) {
  const RefereeState saved = state_in_play();
  ASSERT_EQ(saved.stage, Stage::kNormalFirstHalf);
  BuiltinReferee resumed(builtin_profile("arcade"), FieldGeometry::division_b(), kBlueOnPositive);
  resumed.resume(saved, at(42));
  const RefereeState& state = resumed.state();
  EXPECT_EQ(state.stage, Stage::kNormalFirstHalf);
  EXPECT_EQ(state.stage_time_left, saved.stage_time_left);
  EXPECT_EQ(state.yellow.score, 2u);
  EXPECT_EQ(state.blue.score, 1u);
  EXPECT_EQ(state.blue.yellow_card_times_left, saved.blue.yellow_card_times_left);
  EXPECT_EQ(state.blue.foul_counter, 3u);
  EXPECT_EQ(state.blue_team_on_positive_half, saved.blue_team_on_positive_half);
  EXPECT_EQ(state.command, Command::kStop);
  EXPECT_EQ(state.command_counter, saved.command_counter + 1) << "consumers see one new command";
  EXPECT_EQ(state.next_command, Command::kForceStart);
  EXPECT_EQ(state.status_message, "resumed after a restart of the referee");

  resumed.step(ball_at({1, 1}), at(43.9));
  EXPECT_EQ(resumed.state().command, Command::kStop);
  resumed.step(ball_at({1, 1}), at(44));
  EXPECT_EQ(resumed.state().command, Command::kForceStart) << "arcade continues by itself after stop_duration";
  resumed.step(ball_at({1, 1}), at(54));
  EXPECT_EQ(resumed.state().stage_time_left, *saved.stage_time_left - duration_from_seconds(10))
      << "the half's clock runs on from where it stood";
}

TEST(BuiltinRefereeResume, HaltAndATimeoutStayAsTheyWereWithTheirPendingRestart) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kTimeoutBlue, at(0)));
  BuiltinReferee from_timeout(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  from_timeout.resume(referee.state(), at(5));
  EXPECT_EQ(from_timeout.state().command, Command::kTimeoutBlue);
  EXPECT_EQ(from_timeout.state().blue.timeouts, 3u) << "the timeout was counted before the restart";
  EXPECT_EQ(from_timeout.state().next_command, Command::kPrepareKickoffYellow);

  BuiltinReferee fresh(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  BuiltinReferee from_halt(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  from_halt.resume(fresh.state(), at(5));
  EXPECT_EQ(from_halt.state().command, Command::kHalt);
  EXPECT_EQ(from_halt.state().stage, Stage::kNormalFirstHalfPre);
  EXPECT_EQ(from_halt.state().next_command, Command::kPrepareKickoffYellow);
  from_halt.step(ball_at({0, 0}), at(60));
  EXPECT_EQ(from_halt.state().command, Command::kHalt) << "nothing automatic in HALT";
}

TEST(BuiltinRefereeResume, APreparationIsPreparedAgainAndAStoppageKeepsItsRestart) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kPreparePenaltyBlue, at(0)));
  BuiltinReferee from_preparation(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  from_preparation.resume(referee.state(), at(1));
  EXPECT_EQ(from_preparation.state().command, Command::kStop);
  EXPECT_EQ(from_preparation.state().next_command, Command::kPreparePenaltyBlue);

  BuiltinReferee placing(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(placing.command(Command::kBallPlacementYellow, at(0), Vec2(0.0, 0.0)));
  ASSERT_EQ(placing.state().next_command, Command::kPrepareKickoffYellow);
  BuiltinReferee from_placement(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  from_placement.resume(placing.state(), at(3));
  EXPECT_EQ(from_placement.state().command, Command::kStop);
  EXPECT_EQ(from_placement.state().next_command, Command::kPrepareKickoffYellow) << "the placement's restart";
}

TEST(BuiltinRefereeResume, AMatchThatIsOverStaysOver) {
  RefereeState saved = state_in_play();
  saved.stage = Stage::kPostGame;
  BuiltinReferee resumed(builtin_profile("arcade"), FieldGeometry::division_b(), kBlueOnPositive);
  resumed.resume(saved, at(42));
  EXPECT_EQ(resumed.state().command, Command::kHalt);
  EXPECT_EQ(resumed.state().stage, Stage::kPostGame);
  EXPECT_EQ(resumed.state().yellow.score, 2u);
  resumed.step(ball_at({0, 0}), at(100));
  EXPECT_EQ(resumed.state().command, Command::kHalt);
}

// ---------------------------------------------------------------------------------------------------------
// Goals

struct GoalCase {
  bool blue_on_positive_half;
  double goal_x_sign;  // which goal the ball goes into
  Team scorer;
  Command kickoff;  // for the team that conceded
};

void PrintTo(const GoalCase& c, std::ostream* out) {
  *out << (c.blue_on_positive_half ? "blue on +x" : "blue on -x") << ", goal at "
       << (c.goal_x_sign > 0 ? "+x" : "-x");
}

std::string goal_case_name(const ::testing::TestParamInfo<GoalCase>& info) {
  return std::string(info.param.blue_on_positive_half ? "BlueOnPositiveHalf" : "BlueOnNegativeHalf") +
         (info.param.goal_x_sign > 0 ? "GoalAtPlusX" : "GoalAtMinusX");
}

class GoalTest : public ::testing::TestWithParam<GoalCase> {};

TEST_P(GoalTest, ScoresForTheAttackersStopsAndNamesTheKickoffOfTheTeamThatConceded) {
  const GoalCase c = GetParam();
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  referee.set_blue_on_positive_half(c.blue_on_positive_half);
  const std::uint32_t counter = referee.state().command_counter;
  const ObservedRobot kicker = c.scorer == Team::kYellow ? yellow(3, {c.goal_x_sign * 3.18, 0.1})
                                                         : blue(3, {c.goal_x_sign * 3.18, 0.1});
  referee.step(ball_at({c.goal_x_sign * 3.3, 0.1}, {kicker}), at(1));
  referee.step(ball_at({c.goal_x_sign * 4.6, 0.1}), at(1.1));

  const RefereeState& state = referee.state();
  EXPECT_EQ(state.yellow.score, c.scorer == Team::kYellow ? 1u : 0u);
  EXPECT_EQ(state.blue.score, c.scorer == Team::kBlue ? 1u : 0u);
  EXPECT_EQ(state.command, Command::kStop);
  EXPECT_EQ(state.command_counter, counter + 1);
  EXPECT_EQ(state.next_command, c.kickoff);
  const GameEvent* goal = last_event(referee);
  ASSERT_NE(goal, nullptr);
  EXPECT_EQ(goal->type, GameEventType::kGoal);
  EXPECT_EQ(goal->by_team, c.scorer);
  EXPECT_EQ(goal->by_bot, 3u);
  ASSERT_TRUE(goal->location);
  EXPECT_NEAR(goal->location->x(), c.goal_x_sign * (4.5 + 0.0215), 1e-9);

  // After stop_duration the team that kicks off places the ball on the centre mark (the restart stays).
  referee.step(ball_at({c.goal_x_sign * 4.6, 0.1}), at(3.09));
  EXPECT_EQ(referee.state().command, Command::kStop);
  referee.step(ball_at({c.goal_x_sign * 4.6, 0.1}), at(3.11));
  const Command placement =
      c.kickoff == Command::kPrepareKickoffBlue ? Command::kBallPlacementBlue : Command::kBallPlacementYellow;
  EXPECT_EQ(referee.state().command, placement);
  expect_near(referee.state().designated_position, {0, 0});
  EXPECT_EQ(referee.state().next_command, c.kickoff);
  referee.step(ball_at({0.05, 0}), at(5));
  referee.step(ball_at({0.05, 0}), at(5.5));
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_EQ(referee.state().next_command, c.kickoff);
  referee.step(ball_at({0.05, 0}), at(20));
  EXPECT_EQ(referee.state().command, Command::kStop) << "strict_ai waits for the operator's kickoff";
  EXPECT_EQ(referee.state().command_counter, counter + 3);
}

INSTANTIATE_TEST_SUITE_P(BothGoalsBothTeams, GoalTest,
                         ::testing::Values(GoalCase{true, +1, Team::kYellow, Command::kPrepareKickoffBlue},
                                           GoalCase{true, -1, Team::kBlue, Command::kPrepareKickoffYellow},
                                           GoalCase{false, +1, Team::kBlue, Command::kPrepareKickoffYellow},
                                           GoalCase{false, -1, Team::kYellow, Command::kPrepareKickoffBlue}),
                         goal_case_name);

TEST(BuiltinReferee, AnOwnGoalCountsForTheOpponentWithoutAKicker) {
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  referee.step(ball_at({4.0, 0.0}, {blue(5, {3.88, 0.0})}), at(1));
  referee.step(ball_at({4.6, 0.0}), at(1.1));
  EXPECT_EQ(referee.state().yellow.score, 1u);
  ASSERT_NE(last_event(referee), nullptr);
  EXPECT_FALSE(last_event(referee)->by_bot);
}

TEST(BuiltinReferee, ABallBesideThePostIsNoGoal) {
  BuiltinReferee referee = running_referee(builtin_profile("arcade"));
  referee.step(ball_at({4.0, 0.7}), at(1));
  referee.step(ball_at({4.6, 0.7}), at(1.1));
  EXPECT_EQ(referee.state().yellow.score, 0u);
  EXPECT_EQ(referee.state().command, Command::kForceStart);
}

TEST(BuiltinReferee, ArcadePlacesTheBallOnTheCentreMarkAfterAGoalThenForceStarts) {
  BuiltinReferee referee = running_referee(builtin_profile("arcade"));
  referee.step(ball_at({4.0, 0.0}), at(1));
  referee.step(ball_at({4.6, 0.0}), at(1.1));
  EXPECT_EQ(referee.state().yellow.score, 1u);
  EXPECT_EQ(referee.state().command, Command::kBallPlacementBlue) << "the conceding team places";
  expect_near(referee.state().designated_position, {0, 0});
  EXPECT_EQ(referee.state().next_command, Command::kForceStart);
  referee.step(ball_at({4.6, 0.0}), at(10));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementBlue) << "never FORCE_START a ball in the goal";
  referee.step(ball_at({0.0, 0.1}), at(11));
  referee.step(ball_at({0.0, 0.1}), at(11.5));
  EXPECT_EQ(referee.state().command, Command::kStop);
  referee.step(ball_at({0.0, 0.1}), at(13.45));
  EXPECT_EQ(referee.state().command, Command::kStop);
  referee.step(ball_at({0.0, 0.1}), at(13.55));
  EXPECT_EQ(referee.state().command, Command::kForceStart) << "after stop_duration";
  EXPECT_TRUE(referee.game_running());
  EXPECT_TRUE(referee.state().game_events.empty()) << "game events are cleared when play resumes";
  EXPECT_EQ(referee.state().yellow.score, 1u);
}

TEST(BuiltinReferee, GoalsWithinTheCooldownAreIgnored) {
  RefereeProfile profile = builtin_profile("arcade");
  profile.rules.goal_detection.cooldown = 5;
  profile.game.stop_duration = 0.5;
  BuiltinReferee referee = running_referee(profile);
  referee.step(ball_at({4.0, 0.0}), at(1));
  referee.step(ball_at({4.6, 0.0}), at(1.1));
  referee.step(ball_at({0.0, 0.0}), at(1.15));  // placed on the centre mark ...
  referee.step(ball_at({0.0, 0.0}), at(1.65));  // ... and held: STOP
  referee.step(ball_at({0.0, 0.0}), at(2.15));  // automatic FORCE_START
  EXPECT_EQ(referee.state().command, Command::kForceStart);
  referee.step(ball_at({-4.0, 0.0}), at(2.5));
  referee.step(ball_at({-4.6, 0.0}), at(3));  // 1.9 s after the first goal
  EXPECT_EQ(referee.state().blue.score, 0u);
  EXPECT_EQ(referee.state().command, Command::kForceStart);
  referee.step(ball_at({-4.0, 0.0}), at(6.5));
  referee.step(ball_at({-4.6, 0.0}), at(7));
  EXPECT_EQ(referee.state().blue.score, 1u);
  EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow);
}

TEST(BuiltinReferee, NoGoalIsJudgedWhileStopped) {
  BuiltinReferee referee(builtin_profile("arcade"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kStop, at(0)));
  referee.step(ball_at({4.0, 0.0}), at(1));
  referee.step(ball_at({4.6, 0.0}), at(1.1));
  EXPECT_EQ(referee.state().yellow.score, 0u);
  ASSERT_TRUE(referee.command(Command::kHalt, at(1.2)));
  referee.step(ball_at({4.6, 0.0}), at(9));
  EXPECT_EQ(referee.state().command, Command::kHalt) << "nothing automatic during HALT";
}

// ---------------------------------------------------------------------------------------------------------
// Out of bounds and ball placement

TEST(BuiltinReferee, TouchLineGivesPlacementAndFreeKickToTheTeamThatDidNotTouchLast) {
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  referee.step(ball_at({1.0, 2.8}, {blue(2, {1.0, 2.68}), yellow(1, {0.0, 0.0})}), at(1));
  referee.step(ball_at({1.2, 3.1}), at(1.1));
  const RefereeState& state = referee.state();
  EXPECT_EQ(state.command, Command::kBallPlacementYellow);
  EXPECT_EQ(state.next_command, Command::kDirectFreeYellow);
  const double exit_x = 1.0 + 0.2 * (3.0215 - 2.8) / 0.3;
  expect_near(state.designated_position, {exit_x, 2.8});
  const GameEvent* left = last_event(referee);
  ASSERT_NE(left, nullptr);
  EXPECT_EQ(left->type, GameEventType::kBallLeftFieldTouchLine);
  EXPECT_EQ(left->by_team, Team::kBlue);
  EXPECT_EQ(left->by_bot, 2u);
  expect_near(left->location, {exit_x, 3.0215});
}

TEST(BuiltinReferee, TouchLinePlacementStaysAwayFromTheGoalLines) {
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  referee.step(ball_at({-4.45, -2.9}, {yellow(4, {-4.45, -2.78})}), at(1));
  referee.step(ball_at({-4.45, -3.2}), at(1.1));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementBlue);
  expect_near(referee.state().designated_position, {-4.3, -2.8});
}

TEST(BuiltinReferee, GoalLineByTheAttackersIsAGoalKickAndByTheDefendersACorner) {
  {
    BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
    referee.step(ball_at({4.4, 1.5}, {yellow(7, {4.28, 1.5})}), at(1));
    referee.step(ball_at({4.7, 1.5}), at(1.1));
    EXPECT_EQ(referee.state().command, Command::kBallPlacementBlue);
    EXPECT_EQ(referee.state().next_command, Command::kDirectFreeBlue);
    expect_near(referee.state().designated_position, {3.5, 2.8});
    ASSERT_NE(last_event(referee), nullptr);
    EXPECT_EQ(last_event(referee)->type, GameEventType::kBallLeftFieldGoalLine);
    EXPECT_EQ(last_event(referee)->by_team, Team::kYellow);
  }
  {
    BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
    referee.step(ball_at({4.4, -1.5}, {blue(1, {4.28, -1.5})}), at(1));
    referee.step(ball_at({4.7, -1.5}), at(1.1));
    EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow);
    expect_near(referee.state().designated_position, {4.3, -2.8});
  }
}

TEST(BuiltinReferee, WithoutBallPlacementOutOfBoundsStopsAndWaitsForTheOperator) {
  RefereeProfile profile = builtin_profile("strict_ai");
  profile.rules.out_of_bounds.ball_placement = false;
  BuiltinReferee referee = running_referee(profile);
  referee.step(ball_at({1.0, 2.8}, {blue(2, {1.0, 2.68})}), at(1));
  referee.step(ball_at({1.2, 3.1}), at(1.1));
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_EQ(referee.state().next_command, Command::kDirectFreeYellow);
  referee.step(ball_at({1.2, 3.1}), at(10));
  EXPECT_EQ(referee.state().command, Command::kStop);
}

/// strict_ai after blue kicked the ball over the touch line at t = 1.1: yellow places the ball.
BuiltinReferee referee_with_yellow_placing() {
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  referee.step(ball_at({1.0, 2.8}, {blue(2, {1.0, 2.68})}), at(1));
  referee.step(ball_at({1.0, 3.1}), at(1.1));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow);
  return referee;
}

TEST(BuiltinReferee, ASuccessfulPlacementIsFollowedByTheFreeKickAfterStopDuration) {
  BuiltinReferee referee = referee_with_yellow_placing();
  const Vec2 target = *referee.state().designated_position;
  referee.step(ball_at(target + Vec2(0.1, 0.0)), at(5));
  referee.step(ball_at(target + Vec2(0.1, 0.0)), at(5.49));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow) << "placed, but not held 0.5 s yet";
  referee.step(ball_at(target + Vec2(0.1, 0.0)), at(5.5));
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_EQ(referee.state().next_command, Command::kDirectFreeYellow);
  EXPECT_FALSE(referee.state().designated_position);
  ASSERT_NE(last_event(referee), nullptr);
  EXPECT_EQ(last_event(referee)->type, GameEventType::kPlacementSucceeded);
  EXPECT_EQ(last_event(referee)->by_team, Team::kYellow);
  EXPECT_NEAR(*last_event(referee)->value, 0.1, 1e-9);

  referee.step(ball_at(target), at(7.5));
  EXPECT_EQ(referee.state().command, Command::kDirectFreeYellow);
  EXPECT_FALSE(referee.game_running());
  referee.step(ball_at(target + Vec2(0.06, 0.0)), at(8));
  EXPECT_TRUE(referee.game_running());
}

TEST(BuiltinReferee, AMovingBallIsNotPlaced) {
  BuiltinReferee referee = referee_with_yellow_placing();
  const Vec2 target = *referee.state().designated_position;
  for (double t = 5; t < 7; t += 0.1) {
    referee.step({.ball_position = target, .ball_velocity = Vec2(0.5, 0.0)}, at(t));
  }
  EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow);
  // Without a measured velocity the speed is estimated from successive positions.
  referee.step({.ball_position = target}, at(7.0));
  referee.step({.ball_position = target + Vec2(0.05, 0)}, at(7.1));
  referee.step({.ball_position = target}, at(7.7));  // 0.08 m/s: at rest from here
  EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow);
  referee.step({.ball_position = target}, at(8.3));
  EXPECT_EQ(referee.state().command, Command::kStop);
}

TEST(BuiltinReferee, APlacementTimeoutHandsThePlacementToTheOtherTeamThenToTheOperator) {
  BuiltinReferee referee = referee_with_yellow_placing();
  const Vec2 target = *referee.state().designated_position;
  referee.step(ball_at({1.0, 3.1}), at(31.05));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow);
  referee.step(ball_at({1.0, 3.1}), at(31.1));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementBlue);
  EXPECT_EQ(referee.state().next_command, Command::kDirectFreeBlue);
  expect_near(referee.state().designated_position, target);
  EXPECT_EQ(referee.state().yellow.ball_placement_failures, 1u);
  ASSERT_NE(last_event(referee), nullptr);
  EXPECT_EQ(last_event(referee)->type, GameEventType::kPlacementFailed);
  EXPECT_EQ(last_event(referee)->by_team, Team::kYellow);

  referee.step(ball_at({1.0, 3.1}), at(61.1));
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_EQ(referee.state().next_command, Command::kDirectFreeYellow);
  EXPECT_EQ(referee.state().blue.ball_placement_failures, 1u);
  referee.step(ball_at({1.0, 3.1}), at(80));
  EXPECT_EQ(referee.state().command, Command::kStop) << "the ball must be placed by hand";
}

TEST(BuiltinReferee, FiveFailedPlacementsTakeAwayTheRightToPlace) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  double t = 0;
  for (int failure = 0; failure < 5; ++failure) {
    ASSERT_TRUE(referee.command(Command::kBallPlacementBlue, at(t), Vec2(0, 0)));
    t += 31;
    referee.step(ball_at({2, 2}), at(t));
  }
  EXPECT_EQ(referee.state().blue.ball_placement_failures, 5u);
  EXPECT_TRUE(referee.state().blue.ball_placement_failures_reached);
  EXPECT_FALSE(referee.state().blue.can_place_ball);
  EXPECT_TRUE(referee.state().yellow.can_place_ball);
}

// ---------------------------------------------------------------------------------------------------------
// Defense areas (blue's own area at +x: x in [3.5, 4.5], y in [-1, 1])

TEST(BuiltinReferee, TooManyDefendersInTheirAreaGiveThePenaltyToTheOtherTeam) {
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  referee.step(ball_at({0, 0}, {blue(0, {4.3, 0.0}), blue(4, {3.45, 0.2})}), at(1));
  EXPECT_EQ(referee.state().command, Command::kForceStart) << "keeper inside, defender only partly inside";
  referee.step(ball_at({0, 0}, {blue(0, {4.3, 0.0}), blue(4, {3.7, 0.2}), blue(6, {3.6, -0.5})}), at(2));
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_EQ(referee.state().next_command, Command::kPreparePenaltyYellow);
  const GameEvent* foul = last_event(referee);
  ASSERT_NE(foul, nullptr);
  EXPECT_EQ(foul->type, GameEventType::kDefenderInDefenseArea);
  EXPECT_EQ(foul->by_team, Team::kBlue);
  EXPECT_EQ(foul->by_bot, 4u) << "the deepest robot that is not the goalkeeper";
  EXPECT_NEAR(*foul->value, 0.2, 1e-9);
  // The ball goes to the mark 6 m from blue's goal (+4.5) first, then the penalty is prepared.
  referee.step(ball_at({0, 0}), at(5));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow);
  ASSERT_TRUE(referee.state().designated_position);
  expect_near(*referee.state().designated_position, {-1.5, 0});
  for (double t = 5.5; t <= 30; t += 0.5) referee.step(ball_at({-1.5, 0}), at(t));
  EXPECT_EQ(referee.state().command, Command::kPreparePenaltyYellow) << "strict_ai: operator's NORMAL_START";
}

TEST(BuiltinReferee, AnAttackerInTheOpponentsAreaGivesAFreeKickToTheDefenders) {
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  referee.step(ball_at({0, 0}, {yellow(5, {3.45, -0.5})}), at(1));
  EXPECT_EQ(referee.state().command, Command::kForceStart) << "partly inside, away from the ball";
  referee.step(ball_at({0, 0}, {yellow(5, {4.0, -0.5})}), at(2));
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_EQ(referee.state().next_command, Command::kDirectFreeBlue);
  const GameEvent* foul = last_event(referee);
  ASSERT_NE(foul, nullptr);
  EXPECT_EQ(foul->type, GameEventType::kAttackerTooCloseToDefenseArea);
  EXPECT_EQ(foul->by_team, Team::kYellow);
  EXPECT_EQ(foul->by_bot, 5u);
  EXPECT_EQ(referee.state().yellow.foul_counter, 1u);
  referee.step(ball_at({0, 0}), at(4));
  EXPECT_EQ(referee.state().command, Command::kDirectFreeBlue)
      << "free kicks after fouls follow by themselves";
}

TEST(BuiltinReferee, AFreeKickBallThatRolledIntoADefenseAreaDuringStopIsPlacedFirst) {
  // The same foul at the centre; during STOP the ball rolls on into blue's defense area (blue defends +x),
  // where no blue field player may take the kick: it is placed at the nearest legal spot first.
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  referee.step(ball_at({0, 0}, {yellow(5, {4.0, -0.5})}), at(2));
  ASSERT_EQ(referee.state().next_command, Command::kDirectFreeBlue);
  referee.step(ball_at({4.2, 0.1}), at(4));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementBlue);
  EXPECT_EQ(referee.state().next_command, Command::kDirectFreeBlue);
  ASSERT_TRUE(referee.state().designated_position);
  const FieldGeometry field = FieldGeometry::division_b();
  EXPECT_NEAR(referee.state().designated_position->x(),
              field.field_length / 2 - field.penalty_area_depth - BuiltinReferee::kRestartDefenseAreaDistance, 1e-9)
      << "1 m in front of the area";
}

TEST(BuiltinReferee, AnAttackerTouchingTheBallPartlyInsideTheAreaIsAFoul) {
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  referee.step(ball_at({3.56, 0.0}, {yellow(8, {3.45, 0.0})}), at(1));
  ASSERT_NE(last_event(referee), nullptr);
  EXPECT_EQ(last_event(referee)->type, GameEventType::kAttackerTouchedBallInDefenseArea);
  EXPECT_EQ(referee.state().next_command, Command::kDirectFreeBlue);
}

// ---------------------------------------------------------------------------------------------------------
// Keep-out

TEST(BuiltinReferee, ARobotTooCloseDuringStopFoulsOnceAfterThePersistence) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kStop, at(0)));
  const std::uint32_t counter = referee.state().command_counter;
  const Observation close = ball_at({0, 0}, {yellow(1, {0.3, 0.0}), blue(2, {0.8, 0.0})});
  referee.step(close, at(0.5));
  referee.step(close, at(2.4));
  EXPECT_TRUE(referee.state().game_events.empty());
  referee.step(close, at(2.5));
  ASSERT_EQ(referee.state().game_events.size(), 1u);
  const GameEvent& foul = referee.state().game_events[0];
  EXPECT_EQ(foul.type, GameEventType::kDefenderTooCloseToKickPoint);
  EXPECT_EQ(foul.by_team, Team::kYellow);
  EXPECT_EQ(foul.by_bot, 1u);
  EXPECT_NEAR(*foul.value, 0.21, 1e-9);
  EXPECT_EQ(referee.state().yellow.foul_counter, 1u);
  EXPECT_EQ(referee.state().blue.foul_counter, 0u);
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_EQ(referee.state().command_counter, counter) << "a keep-out foul changes no command";
  referee.step(close, at(6));
  EXPECT_EQ(referee.state().game_events.size(), 1u) << "one foul per stay";
  referee.step(ball_at({0, 0}, {yellow(1, {1.0, 0.0})}), at(6.5));
  referee.step(close, at(7));
  referee.step(close, at(9));
  EXPECT_EQ(referee.state().yellow.foul_counter, 2u) << "leaving and coming back is a new stay";
}

TEST(BuiltinReferee, DuringAFreeKickOnlyTheOtherTeamMustKeepOut) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kDirectFreeYellow, at(0)));
  const Observation close = ball_at({0, 0}, {yellow(1, {0.12, 0.0}), blue(2, {-0.3, 0.0})});
  referee.step(close, at(0.1));
  referee.step(close, at(3));
  ASSERT_EQ(referee.state().game_events.size(), 1u);
  EXPECT_EQ(referee.state().game_events[0].by_team, Team::kBlue);
  EXPECT_EQ(referee.state().command, Command::kDirectFreeYellow);
}

TEST(BuiltinReferee, DuringPlacementThePathToTheTargetIsKeptClear) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kBallPlacementBlue, at(0), Vec2(2.0, 0.0)));
  const Observation near_path = ball_at({0, 0}, {yellow(3, {1.0, 0.3}), blue(2, {0.1, 0.0})});
  referee.step(near_path, at(0.1));
  referee.step(near_path, at(2.2));
  ASSERT_EQ(referee.state().game_events.size(), 1u);
  EXPECT_EQ(referee.state().game_events[0].type, GameEventType::kBotInterferedPlacement);
  EXPECT_EQ(referee.state().game_events[0].by_bot, 3u);
  EXPECT_EQ(referee.state().command, Command::kBallPlacementBlue);
}

// ---------------------------------------------------------------------------------------------------------
// Disabled rules, bad input, determinism

TEST(BuiltinReferee, DisabledRulesDoNothing) {
  BuiltinReferee referee = running_referee(builtin_profile("arcade"));
  const std::uint32_t counter = referee.state().command_counter;
  referee.step(ball_at({1.0, 2.8}, {blue(2, {1.0, 2.68})}), at(1));
  referee.step(ball_at({1.2, 3.1}), at(1.1));  // over the touch line
  referee.step(ball_at({0, 0}, {blue(0, {4.3, 0}), blue(4, {3.7, 0.2}), yellow(5, {-4.0, 0})}), at(2));
  EXPECT_EQ(referee.state().command_counter, counter);
  EXPECT_TRUE(referee.state().game_events.empty());
  ASSERT_TRUE(referee.command(Command::kStop, at(3)));
  referee.step(ball_at({0, 0}, {yellow(1, {0.1, 0.0})}), at(3.1));
  referee.step(ball_at({0, 0}, {yellow(1, {0.1, 0.0})}), at(4.9));
  EXPECT_TRUE(referee.state().game_events.empty());
  EXPECT_EQ(referee.state().yellow.foul_counter, 0u);

  RefereeProfile no_goals = builtin_profile("strict_ai");
  no_goals.rules.goal_detection.enabled = false;
  BuiltinReferee without_goals = running_referee(no_goals);
  without_goals.step(ball_at({4.0, 0.0}), at(1));
  without_goals.step(ball_at({4.6, 0.0}), at(1.1));
  EXPECT_EQ(without_goals.state().yellow.score, 0u);
  EXPECT_EQ(without_goals.state().command, Command::kForceStart) << "a goal is not a goal-line out";
}

TEST(BuiltinReferee, BadInputIsIgnoredAndCounted) {
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  referee.step(ball_at({4.0, 0.0}), at(1));
  const RefereeState before = referee.state();
  referee.step({.ball_position = Vec2(nan, 0.0)}, at(1.1));
  referee.step({.ball_position = Vec2(4.0, 0.0), .ball_velocity = Vec2(nan, nan)}, at(1.2));
  referee.step({.robots = {blue(1, {nan, 0.0}), blue(16, {4.0, 0.0}), blue(2, {0, 0}), blue(2, {1, 1})}},
               at(1.3));
  referee.step(ball_at({4.6, 0.0}), at(0.5));  // time went backwards: ignored
  EXPECT_EQ(referee.counters().invalid_ball, 2u);
  EXPECT_EQ(referee.counters().missing_ball, 1u);
  EXPECT_EQ(referee.counters().invalid_robot, 1u);
  EXPECT_EQ(referee.counters().unknown_robot_id, 1u);
  EXPECT_EQ(referee.counters().duplicate_robot, 1u);
  EXPECT_EQ(referee.counters().time_went_backwards, 1u);
  EXPECT_EQ(referee.counters().observations, 4u);
  EXPECT_EQ(referee.state().command, before.command);
  EXPECT_EQ(referee.state().yellow.score, 0u);
  EXPECT_EQ(referee.state().packet_referee, at(1.3));

  // A robot with an unknown id next to the ball is no last toucher.
  referee.step(ball_at({1.0, 2.8}, {blue(2, {1.0, 2.68}), yellow(20, {1.0, 2.9})}), at(2));
  referee.step(ball_at({1.0, 3.1}), at(2.1));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow);
}

TEST(BuiltinReferee, TheSameInputsGiveTheSameStates) {
  BuiltinReferee first(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  BuiltinReferee second(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  std::uint64_t seed = 12345;
  const auto uniform = [&seed](double low, double high) {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return low + (high - low) * static_cast<double>(seed >> 11) / static_cast<double>(1ULL << 53);
  };
  Vec2 ball(0, 0);
  for (int frame = 0; frame < 6000; ++frame) {
    const Timestamp now = at(frame / 60.0);
    if (frame % 600 == 0) {
      const Command command = frame % 1200 == 0 ? Command::kForceStart : Command::kStop;
      ASSERT_EQ(first.command(command, now).ok(), second.command(command, now).ok());
    }
    ball += Vec2(uniform(-0.08, 0.08), uniform(-0.08, 0.08));
    if (std::abs(ball.x()) > 5.0 || std::abs(ball.y()) > 3.5) ball = Vec2(0, 0);
    Observation observation = ball_at(ball);
    for (std::uint32_t id = 0; id < 6; ++id) {
      observation.robots.push_back(yellow(id, {uniform(-4.5, 4.5), uniform(-3, 3)}));
      observation.robots.push_back(blue(id, {uniform(-4.5, 4.5), uniform(-3, 3)}));
    }
    first.step(observation, now);
    second.step(observation, now);
    ASSERT_EQ(first.state(), second.state()) << "frame " << frame;
  }
  EXPECT_GT(first.state().command_counter, 10u) << "the script should exercise the rules";
}

TEST(BuiltinReferee, ARestingBallSeenWithDetectionNoiseAndNoVelocityIsPlaced) {
  // Vision gives positions only, each with a few millimetres of noise; 10 ms apart that alone looks like
  // 0.4 m/s. The speed is estimated over 0.1 s, so the ball at the target is at rest.
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kBallPlacementYellow, at(0), Vec2(1.0, -2.0)));
  for (int i = 0; i <= 200; ++i) {
    const double noise = (i % 2 == 0 ? 0.003 : -0.003) * ((i % 3) + 1) / 3.0;
    referee.step({.ball_position = Vec2(1.0 + noise, -2.0 - noise)}, at(0.01 * i));
  }
  EXPECT_EQ(referee.state().command, Command::kStop);
  ASSERT_NE(last_event(referee), nullptr);
  EXPECT_EQ(last_event(referee)->type, GameEventType::kPlacementSucceeded);
}

// ---------------------------------------------------------------------------------------------------------
// No progress

TEST(BuiltinReferee, ABallThatRestsTenSecondsWhileRunningIsRestartedWithForceStart) {
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  // Creeping 0.06 m every 5 s is progress; then it rests.
  for (double t = 0; t <= 12.0; t += 0.01) referee.step(ball_at({0.06 * std::floor(t / 5.0), 1.0}), at(t));
  EXPECT_EQ(referee.state().command, Command::kForceStart) << "the ball moved 0.06 m at 5 s and 10 s";
  double stopped_at = -1;
  for (double t = 12.01; t <= 25.0 && stopped_at < 0; t += 0.01) {
    referee.step(ball_at({0.12, 1.0}), at(t));
    if (referee.state().command == Command::kStop) stopped_at = t;
  }
  EXPECT_NEAR(stopped_at, 20.0, 0.02) << "10 s after the last movement (at 10 s)";
  ASSERT_NE(last_event(referee), nullptr);
  EXPECT_EQ(last_event(referee)->type, GameEventType::kNoProgressInGame);
  expect_near(last_event(referee)->location, Vec2(0.12, 1.0));
  EXPECT_EQ(referee.state().next_command, Command::kForceStart);
  for (double t = stopped_at; t <= stopped_at + 2.05; t += 0.01) referee.step(ball_at({0.12, 1.0}), at(t));
  EXPECT_EQ(referee.state().command, Command::kForceStart) << "FORCE_START after stop_duration (2 s)";
}

// ---------------------------------------------------------------------------------------------------------
// Restart timeouts (rules 5.3): the ball is in play after them, kicked or not; a penalty fails.

struct RestartTimeoutCase {
  Division division;
  bool kickoff;    // else a free kick
  double timeout;  // s the rules give
};

std::string restart_timeout_case_name(const ::testing::TestParamInfo<RestartTimeoutCase>& param_info) {
  return std::string(param_info.param.kickoff ? "Kickoff" : "FreeKick") + "Division" +
         (param_info.param.division == Division::kA ? "A" : "B");
}

class RestartTimeoutTest : public ::testing::TestWithParam<RestartTimeoutCase> {};

TEST_P(RestartTimeoutTest, TheBallIsInPlayAtTheTimeoutWithoutACommand) {
  const RestartTimeoutCase c = GetParam();
  MatchSetup setup = kBlueOnPositive;
  setup.division = c.division;
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), setup);
  ASSERT_TRUE(referee.command(Command::kStop, at(0)));
  if (c.kickoff) {
    ASSERT_TRUE(referee.command(Command::kPrepareKickoffBlue, at(0.5)));
    ASSERT_TRUE(referee.command(Command::kNormalStart, at(1)));
  } else {
    ASSERT_TRUE(referee.command(Command::kDirectFreeBlue, at(1)));
  }
  const Command command = referee.state().command;
  referee.step(ball_at({0.0, 0.0}), at(1.5));
  EXPECT_NEAR(time::to_seconds(*referee.state().current_action_time_remaining), c.timeout - 0.5, 1e-9);
  referee.step(ball_at({0.0, 0.0}), at(1 + c.timeout - 0.01));
  EXPECT_FALSE(referee.game_running()) << "just inside the timeout";
  referee.step(ball_at({0.0, 0.0}), at(1 + c.timeout + 0.01));
  EXPECT_TRUE(referee.game_running()) << "just past the timeout";
  EXPECT_EQ(referee.state().command, command) << "no command changes";
  EXPECT_EQ(last_event(referee), nullptr) << "KICK_TIMEOUT is deprecated; nothing is raised";
}

INSTANTIATE_TEST_SUITE_P(BuiltinReferee, RestartTimeoutTest,
                         ::testing::Values(RestartTimeoutCase{Division::kB, true, 10.0},
                                           RestartTimeoutCase{Division::kA, true, 10.0},
                                           RestartTimeoutCase{Division::kB, false, 10.0},
                                           RestartTimeoutCase{Division::kA, false, 5.0}),
                         restart_timeout_case_name);

TEST(BuiltinReferee, APenaltyUndecidedAfterTenSecondsFailsAndGivesTheDefendersAGoalKick) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kPreparePenaltyYellow, at(0)));
  ASSERT_TRUE(referee.command(Command::kNormalStart, at(1)));
  // Yellow attacks +x: the mark is 6 m from blue's goal at +4.5.
  referee.step(ball_at({-1.5, 0.0}), at(1.5));
  referee.step(ball_at({-1.3, 0.0}), at(2));  // kicked softly: in play, rolling, then resting short
  EXPECT_TRUE(referee.game_running());
  referee.step(ball_at({-1.0, 0.0}), at(10.99));
  EXPECT_EQ(referee.state().command, Command::kNormalStart) << "just inside 10 s";
  referee.step(ball_at({-1.0, 0.0}), at(11.01));
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_EQ(referee.state().next_command, Command::kDirectFreeBlue);
  ASSERT_NE(last_event(referee), nullptr);
  EXPECT_EQ(last_event(referee)->type, GameEventType::kPenaltyKickFailed);
  EXPECT_EQ(last_event(referee)->by_team, Team::kYellow);
}

// ---------------------------------------------------------------------------------------------------------
// Restarts always restart: the ball is placed where the restart needs it

TEST(BuiltinReferee, TheSimulationProfileRunsAGoalThroughPlacementAndKickoffBackToPlay) {
  BuiltinReferee referee = running_referee(builtin_profile("simulation"));
  referee.step(ball_at({4.0, 0.0}, {yellow(2, {3.88, 0.0})}), at(1));
  referee.step(ball_at({4.6, 0.0}), at(1.1));
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_EQ(referee.state().next_command, Command::kPrepareKickoffBlue);
  referee.step(ball_at({4.6, 0.0}), at(3.11));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementBlue);
  referee.step(ball_at({0.0, 0.0}), at(3.2));  // the simulator puts it there
  referee.step(ball_at({0.0, 0.0}), at(3.7));
  EXPECT_EQ(referee.state().command, Command::kStop);
  referee.step(ball_at({0.0, 0.0}), at(5.71));
  EXPECT_EQ(referee.state().command, Command::kPrepareKickoffBlue);
  // A yellow robot inside the centre circle: no NORMAL_START until it leaves.
  referee.step(ball_at({0.0, 0.0}, {yellow(1, {-0.4, 0.0}), blue(0, {0.2, 0.0})}), at(8));
  EXPECT_EQ(referee.state().command, Command::kPrepareKickoffBlue);
  referee.step(ball_at({0.0, 0.0}, {yellow(1, {-0.7, 0.0}), blue(0, {0.2, 0.0})}), at(8.1));
  EXPECT_EQ(referee.state().command, Command::kNormalStart) << "everybody in position";
  referee.step(ball_at({-0.1, 0.0}), at(8.5));
  EXPECT_TRUE(referee.game_running());
}

TEST(BuiltinReferee, AKickoffGetsItsNormalStartAtThePrepareTimeoutEvenIfRobotsAreOutOfPosition) {
  BuiltinReferee referee(builtin_profile("simulation"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kPrepareKickoffYellow, at(0)));
  const Observation blocked = ball_at({0, 0}, {blue(1, {0.3, 0.0})});  // blue in the circle
  referee.step(blocked, at(9.99));
  EXPECT_EQ(referee.state().command, Command::kPrepareKickoffYellow);
  referee.step(blocked, at(10.01));
  EXPECT_EQ(referee.state().command, Command::kNormalStart);
}

TEST(BuiltinReferee, NoProgressWithTheBallBeyondTheLinesPlacesItBeforeTheForceStart) {
  RefereeProfile profile = builtin_profile("simulation");
  profile.rules.out_of_bounds.enabled = false;  // the ball may lie out there while running
  profile.rules.goal_detection.enabled = false;
  for (const auto& [ball, target] : {std::pair{Vec2(1.0, 3.2), Vec2(1.0, 2.8)},     // in the boundary
                                     std::pair{Vec2(4.6, 0.1), Vec2(2.5, 0.1)},     // in blue's goal
                                     std::pair{Vec2(-4.7, -1.6), Vec2(-4.3, -2.0)}}) {  // beside a goal
    BuiltinReferee referee = running_referee(profile);
    referee.step(ball_at(ball, {blue(3, ball + Vec2(0.0, 0.11))}), at(0.5));
    for (double t = 1; t <= 10.6; t += 0.1) referee.step(ball_at(ball), at(t));
    ASSERT_EQ(referee.state().command, Command::kStop) << "no progress at " << ball.transpose();
    EXPECT_EQ(referee.state().next_command, Command::kForceStart);
    referee.step(ball_at(ball), at(12.7));
    EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow)
        << "placed first, by the team that did not touch it last";
    expect_near(referee.state().designated_position, target);
    EXPECT_EQ(referee.state().next_command, Command::kForceStart);
    referee.step(ball_at(target), at(13));
    referee.step(ball_at(target), at(13.5));
    referee.step(ball_at(target), at(15.6));
    EXPECT_EQ(referee.state().command, Command::kForceStart);
  }
}

TEST(BuiltinReferee, NoProgressBeforeADefenseAreaPlacesTheBallOneMetreFromItBeforeTheForceStart) {
  // Stuck where neither team can play it (by the area's edge, its own robots kept out of it): placed out of
  // the area's reach first, along x or along y, whichever is nearer, as the Game Controller does. A ball
  // anywhere else stays where it rests. Blue touched it last, from outside both areas.
  struct Case {
    Vec2 ball, target, toucher;
  };
  for (const Case& c : {Case{{3.5, 0.09}, {2.5, 0.09}, {3.39, 0.09}},      // before blue's area
                        Case{{3.93, 1.05}, {3.93, 2.0}, {3.93, 1.16}},     // beside it
                        Case{{-3.45, -0.4}, {-2.5, -0.4}, {-3.34, -0.4}},  // before yellow's
                        Case{{2.4, 0.5}, {2.4, 0.5}, {2.29, 0.5}},         // 1.1 m out: stays
                        Case{{3.8, 2.1}, {3.8, 2.1}, {3.8, 2.21}}}) {      // 1.1 m aside: stays
    BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
    referee.step(ball_at(c.ball, {blue(3, c.toucher)}), at(0.5));
    for (double t = 1; t <= 10.6; t += 0.1) referee.step(ball_at(c.ball), at(t));
    ASSERT_EQ(referee.state().command, Command::kStop) << "no progress at " << c.ball.transpose();
    EXPECT_EQ(referee.state().next_command, Command::kForceStart);
    referee.step(ball_at(c.ball), at(12.7));
    if (c.target == c.ball) {
      EXPECT_EQ(referee.state().command, Command::kForceStart) << "at " << c.ball.transpose();
      continue;
    }
    EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow) << "at " << c.ball.transpose();
    expect_near(referee.state().designated_position, c.target);
    EXPECT_EQ(referee.state().next_command, Command::kForceStart);
    referee.step(ball_at(c.target), at(13));
    referee.step(ball_at(c.target), at(13.5));
    referee.step(ball_at(c.target), at(15.6));
    EXPECT_EQ(referee.state().command, Command::kForceStart);
  }
}

TEST(BuiltinReferee, WithoutBallPlacementTheKickoffWaitsUntilTheBallIsOnTheCentreMarkByHand) {
  RefereeProfile profile = builtin_profile("simulation");
  profile.game.ball_placement = false;
  BuiltinReferee referee = running_referee(profile);
  referee.step(ball_at({4.0, 0.0}), at(1));
  referee.step(ball_at({4.6, 0.0}), at(1.1));
  referee.step(ball_at({4.6, 0.0}), at(3.2));
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_NE(referee.state().status_message.find("by hand"), std::string::npos) << referee.state().status_message;
  referee.step(ball_at({4.6, 0.0}), at(30));
  EXPECT_EQ(referee.state().command, Command::kStop) << "never a kickoff with the ball in the goal";
  referee.step(ball_at({0.1, 0.0}), at(31));
  EXPECT_EQ(referee.state().command, Command::kPrepareKickoffBlue) << "placed by hand: the kickoff follows";
}

TEST(BuiltinReferee, AFailedPlacementBeforeAKickoffKeepsTheKickoff) {
  BuiltinReferee referee = running_referee(builtin_profile("simulation"));
  referee.step(ball_at({4.0, 0.0}), at(1));
  referee.step(ball_at({4.6, 0.0}), at(1.1));
  referee.step(ball_at({4.6, 0.0}), at(3.2));
  ASSERT_EQ(referee.state().command, Command::kBallPlacementBlue);
  referee.step(ball_at({4.6, 0.0}), at(33.3));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow) << "the other team tries";
  EXPECT_EQ(referee.state().next_command, Command::kPrepareKickoffBlue);
  referee.step(ball_at({4.6, 0.0}), at(63.4));
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_EQ(referee.state().next_command, Command::kPrepareKickoffBlue);
  referee.step(ball_at({4.6, 0.0}), at(70));
  EXPECT_EQ(referee.state().command, Command::kStop) << "by hand now";
}

// ---------------------------------------------------------------------------------------------------------
// Extra time, shoot-out, early end

TEST(BuiltinReferee, ADrawGoesToExtraTimeWithSidesChangedEachHalfThenToTheShootout) {
  RefereeProfile profile = builtin_profile("strict_ai");
  profile.game.half_duration = 10;
  profile.game.half_time = 1;
  profile.game.extra_time = {.enabled = true, .break_duration = 2, .half_duration = 5, .half_time = 1,
                             .shootout_break = 3, .shootout_penalties = 5};
  BuiltinReferee referee(profile, FieldGeometry::division_b());
  std::vector<std::pair<Stage, bool>> seen;  // stage, blue on the positive half
  double t = 0;
  const auto play = [&](double seconds) {
    for (const double end = t + seconds; t < end; t += 0.5) {
      referee.step(ball_at({0, 0}), at(t));
      if (referee.state().command == Command::kStop) {
        ASSERT_TRUE(referee.command(Command::kForceStart, at(t)));
      }
      const std::pair<Stage, bool> now{referee.state().stage, *referee.state().blue_team_on_positive_half};
      if (seen.empty() || seen.back() != now) seen.push_back(now);
    }
  };
  ASSERT_TRUE(referee.command(Command::kForceStart, at(0)));
  play(60);
  const std::vector<std::pair<Stage, bool>> expected = {
      {Stage::kNormalFirstHalf, false},       {Stage::kNormalHalfTime, false},
      {Stage::kNormalSecondHalf, true},        {Stage::kExtraTimeBreak, true},
      {Stage::kExtraFirstHalf, false},         {Stage::kExtraHalfTime, false},
      {Stage::kExtraSecondHalf, true},         {Stage::kPenaltyShootoutBreak, true},
      {Stage::kPenaltyShootout, true}};
  ASSERT_EQ(seen.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(seen[i].first, expected[i].first) << i << ": " << to_string(seen[i].first);
    EXPECT_EQ(seen[i].second, expected[i].second) << i << ": " << to_string(seen[i].first);
  }
}

TEST(BuiltinReferee, AWinnerAfterTheSecondHalfEndsTheMatchWithoutExtraTime) {
  RefereeProfile profile = builtin_profile("strict_ai");
  profile.game.half_duration = 10;
  profile.game.half_time = 1;
  BuiltinReferee referee(profile, FieldGeometry::division_b());
  ASSERT_TRUE(referee.command(Command::kForceStart, at(0)));
  referee.step(ball_at({-4.0, 0.0}), at(1));  // blue defends -x in the first half: yellow scores
  referee.step(ball_at({-4.6, 0.0}), at(1.1));
  ASSERT_EQ(referee.state().yellow.score, 1u);
  ASSERT_TRUE(referee.command(Command::kForceStart, at(2)));
  referee.step(ball_at({0.0, 0.0}), at(12));
  ASSERT_EQ(referee.state().stage, Stage::kNormalHalfTime);
  referee.step(ball_at({0.0, 0.0}), at(13.5));
  ASSERT_TRUE(referee.command(Command::kForceStart, at(14)));
  referee.step(ball_at({0.0, 0.0}), at(24.1));
  EXPECT_EQ(referee.state().stage, Stage::kPostGame) << "the final whistle";
  EXPECT_EQ(referee.state().command, Command::kHalt);
}

/// A referee at the start of the shoot-out (strict_ai with auto_continue, blue defending +x).
BuiltinReferee shootout_referee() {
  RefereeProfile profile = builtin_profile("strict_ai");
  profile.game.auto_continue = true;
  profile.game.ball_placement = false;
  BuiltinReferee referee(profile, FieldGeometry::division_b());
  for (int stage = 0; stage < 12 && referee.state().stage != Stage::kPenaltyShootout; ++stage) {
    EXPECT_TRUE(referee.next_stage(at(0)));
  }
  return referee;
}

/// Plays one penalty of the shoot-out from its STOP at `t`: a goal or a miss.
void take_penalty(BuiltinReferee& referee, double& t, bool goal) {
  const Command penalty = *referee.state().next_command;
  const bool yellow_kicks = penalty == Command::kPreparePenaltyYellow;
  const double goal_x = (yellow_kicks == referee.state().blue_team_on_positive_half.value()) ? 4.5 : -4.5;
  const Vec2 mark(goal_x - (goal_x > 0 ? 6.0 : -6.0), 0.0);
  for (int i = 0; i < 20 && referee.state().command != Command::kNormalStart; ++i, t += 0.5) {
    referee.step(ball_at(mark), at(t));
  }
  ASSERT_EQ(referee.state().command, Command::kNormalStart);
  const Vec2 end(goal_x + (goal_x > 0 ? 0.1 : -0.1), goal ? 0.0 : 0.8);
  referee.step(ball_at(mark + 0.9 * (end - mark)), at(t += 0.1));
  referee.step(ball_at(end), at(t += 0.1));
  t += 0.5;
}

TEST(BuiltinReferee, TheShootoutEndsWhenOneTeamCanNoLongerBeCaught) {
  BuiltinReferee referee = shootout_referee();
  EXPECT_EQ(referee.state().next_command, Command::kPreparePenaltyYellow);
  double t = 1;
  for (int round = 0; round < 3; ++round) {
    take_penalty(referee, t, /*goal=*/true);   // yellow scores
    EXPECT_EQ(referee.state().next_command, Command::kPreparePenaltyBlue);
    take_penalty(referee, t, /*goal=*/false);  // blue misses
  }
  EXPECT_EQ(referee.state().yellow.score, 3u);
  EXPECT_EQ(referee.state().blue.score, 0u);
  EXPECT_EQ(referee.state().stage, Stage::kPostGame) << "3 : 0 with two kicks each left";
}

TEST(BuiltinReferee, TheShootoutGoesToSuddenDeathAfterFivePenaltiesEach) {
  BuiltinReferee referee = shootout_referee();
  double t = 1;
  for (int round = 0; round < 5; ++round) {
    take_penalty(referee, t, true);
    take_penalty(referee, t, true);
  }
  EXPECT_EQ(referee.state().stage, Stage::kPenaltyShootout) << "5 : 5";
  take_penalty(referee, t, true);
  EXPECT_EQ(referee.state().stage, Stage::kPenaltyShootout) << "blue still kicks";
  take_penalty(referee, t, false);
  EXPECT_EQ(referee.state().stage, Stage::kPostGame);
  EXPECT_EQ(referee.state().yellow.score, 6u);
  EXPECT_EQ(referee.state().blue.score, 5u);
}

TEST(BuiltinReferee, TenGoalsWithALeadOfTwoEndTheMatchEarly) {
  RefereeProfile profile = builtin_profile("arcade");
  profile.rules.goal_detection.cooldown = 0;
  profile.game.early_end_goals = 10;  // arcade plays on whatever the score
  BuiltinReferee referee = running_referee(profile);
  double t = 1;
  for (int goal = 0; goal < 10; ++goal) {
    ASSERT_TRUE(referee.command(Command::kForceStart, at(t)));
    referee.step(ball_at({4.0, 0.0}), at(t += 0.1));
    referee.step(ball_at({4.6, 0.0}), at(t += 0.1));
    if (goal < 9) {
      EXPECT_NE(referee.state().stage, Stage::kPostGame) << goal;
    }
  }
  EXPECT_EQ(referee.state().yellow.score, 10u);
  EXPECT_EQ(referee.state().stage, Stage::kPostGame);
}

TEST(BuiltinReferee, WithoutTheNoProgressRuleARestingBallIsLeftAlone) {
  BuiltinReferee referee = running_referee(builtin_profile("arcade"));
  for (double t = 0; t <= 30.0; t += 0.01) referee.step(ball_at({1.0, 1.0}), at(t));
  EXPECT_EQ(referee.state().command, Command::kForceStart);
  EXPECT_EQ(last_event(referee), nullptr);
}


// ---------------------------------------------------------------------------------------------------------
// Fouls (strict_ai has every rule on; blue defends +x: blue's area x in [3.5, 4.5], |y| <= 1)

ObservedRobot moving(ObservedRobot robot, Vec2 velocity) {
  robot.velocity = velocity;
  return robot;
}

std::size_t count_events(const BuiltinReferee& referee, GameEventType type) {
  return static_cast<std::size_t>(std::count_if(referee.state().game_events.begin(), referee.state().game_events.end(),
                                                [&](const GameEvent& e) { return e.type == type; }));
}

struct CrashCase {
  const char* name;
  double yellow_speed;  // m/s towards blue (+x)
  double blue_speed;    // m/s towards yellow (-x)
  std::optional<GameEventType> expected;
  Team by_team;
};

class CrashTest : public ::testing::TestWithParam<CrashCase> {};

TEST_P(CrashTest, ARelativeSpeedAboveOnePointFiveIsACrashOfTheFasterOrOfBoth) {
  const CrashCase c = GetParam();
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  referee.step(ball_at({2, 2}, {moving(yellow(1, {0, 0}), {c.yellow_speed, 0}),
                                moving(blue(2, {0.185, 0}), {-c.blue_speed, 0})}),
               at(1));
  if (!c.expected) {
    EXPECT_EQ(count_events(referee, GameEventType::kBotCrashUnique) + count_events(referee, GameEventType::kBotCrashDrawn),
              0u);
    return;
  }
  const GameEvent* crash = last_event(referee);
  ASSERT_NE(crash, nullptr);
  EXPECT_EQ(crash->type, *c.expected);
  EXPECT_NEAR(*crash->value, c.yellow_speed + c.blue_speed, 1e-9);
  expect_near(crash->location, {0.0925, 0});
  EXPECT_EQ(referee.state().command, Command::kForceStart) << "non-stopping";
  if (*c.expected == GameEventType::kBotCrashDrawn) {
    EXPECT_EQ(crash->by_bot, 1u) << "the yellow robot";
    EXPECT_EQ(crash->other_bot, 2u) << "the blue robot";
    EXPECT_EQ(referee.state().yellow.foul_counter, 1u);
    EXPECT_EQ(referee.state().blue.foul_counter, 1u);
  } else {
    EXPECT_EQ(crash->by_team, c.by_team);
    EXPECT_EQ(crash->by_bot, c.by_team == Team::kYellow ? 1u : 2u);
    EXPECT_EQ(crash->other_bot, c.by_team == Team::kYellow ? 2u : 1u);
    EXPECT_EQ(c.by_team == Team::kYellow ? referee.state().yellow.foul_counter : referee.state().blue.foul_counter, 1u);
  }
}

INSTANTIATE_TEST_SUITE_P(
    BuiltinReferee, CrashTest,
    ::testing::Values(CrashCase{"JustBelowTheSpeed", 1.49, 0.0, std::nullopt, Team::kUnknown},
                      CrashCase{"JustAboveTheSpeed", 1.51, 0.0, GameEventType::kBotCrashUnique, Team::kYellow},
                      CrashCase{"BlueFaster", 0.2, 1.4, GameEventType::kBotCrashUnique, Team::kBlue},
                      CrashCase{"DifferenceJustBelowDrawn", 0.94, 0.66, GameEventType::kBotCrashDrawn, Team::kUnknown},
                      CrashCase{"DifferenceJustAboveDrawn", 0.96, 0.64, GameEventType::kBotCrashUnique, Team::kYellow}),
    [](const ::testing::TestParamInfo<CrashCase>& param_info) { return std::string(param_info.param.name); });

TEST(BuiltinReferee, ACrashIsRaisedAgainOnlyAfterTwoSeconds) {
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
  const Observation crash = ball_at({2, 2}, {moving(yellow(1, {0, 0}), {2, 0}), blue(2, {0.185, 0})});
  referee.step(crash, at(1));
  referee.step(crash, at(2.9));
  EXPECT_EQ(referee.state().yellow.foul_counter, 1u);
  referee.step(crash, at(3.1));
  EXPECT_EQ(referee.state().yellow.foul_counter, 2u);
}

TEST(BuiltinReferee, TooFastInStopAfterTheGraceOncePerRobot) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kStop, at(0)));
  referee.step(ball_at({0, 0}, {moving(yellow(1, {-2, 0}), {3, 0})}), at(1.9));
  EXPECT_EQ(referee.state().yellow.foul_counter, 0u) << "within the 2 s grace";
  referee.step(ball_at({0, 0}, {moving(yellow(1, {-2, 0}), {1.49, 0}), moving(blue(3, {2, 0}), {0, 1.49})}), at(2.1));
  EXPECT_EQ(referee.state().yellow.foul_counter + referee.state().blue.foul_counter, 0u) << "1.49 m/s";
  referee.step(ball_at({0, 0}, {moving(yellow(1, {-2, 0}), {1.51, 0})}), at(2.2));
  const GameEvent* fast = last_event(referee);
  ASSERT_NE(fast, nullptr);
  EXPECT_EQ(fast->type, GameEventType::kBotTooFastInStop);
  EXPECT_EQ(fast->by_team, Team::kYellow);
  EXPECT_EQ(fast->by_bot, 1u);
  EXPECT_NEAR(*fast->value, 1.51, 1e-9);
  expect_near(fast->location, {-2, 0});
  referee.step(ball_at({0, 0}, {moving(yellow(1, {-2, 0}), {2, 0})}), at(3));
  EXPECT_EQ(referee.state().yellow.foul_counter, 1u) << "once per robot and STOP";
  EXPECT_EQ(referee.state().command, Command::kStop);
}

TEST(BuiltinReferee, RobotSpeedsAreEstimatedFromPositionsWhenNotGiven) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kStop, at(0)));
  for (int i = 0; i <= 30; ++i) {  // 1.0 m/s with 3 mm of noise: never too fast
    const double noise = (i % 2 == 0 ? 0.003 : -0.003);
    referee.step(ball_at({0, 0}, {yellow(1, {-2 + 0.01 * i + noise, 1})}), at(2.0 + 0.01 * i));
  }
  EXPECT_EQ(referee.state().yellow.foul_counter, 0u);
  for (int i = 0; i <= 30; ++i) referee.step(ball_at({0, 0}, {yellow(1, {-1 + 0.02 * i, 1})}), at(3.0 + 0.01 * i));
  EXPECT_EQ(referee.state().yellow.foul_counter, 1u) << "2 m/s";
}

/// A free kick for yellow from (0, 0): yellow 2 kicks it to +x (in play at t = 1.1).
BuiltinReferee referee_after_free_kick() {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  EXPECT_TRUE(referee.command(Command::kDirectFreeYellow, at(0)));
  referee.step(ball_at({0, 0}, {yellow(2, {-0.11, 0})}), at(1));
  referee.step(ball_at({0.06, 0}, {yellow(2, {-0.11, 0})}), at(1.1));
  EXPECT_TRUE(referee.game_running());
  return referee;
}

TEST(BuiltinReferee, TheKickerTouchingAgainFirstIsADoubleTouch) {
  BuiltinReferee referee = referee_after_free_kick();
  referee.step(ball_at({0.5, 0}, {yellow(2, {-0.11, 0})}), at(1.2));  // released
  referee.step(ball_at({0.6, 0}, {yellow(2, {0.49, 0})}), at(1.5));   // touches again
  EXPECT_EQ(referee.state().command, Command::kStop);
  EXPECT_EQ(referee.state().next_command, Command::kDirectFreeBlue);
  const GameEvent* touch = nullptr;
  for (const GameEvent& e : referee.state().game_events) {
    if (e.type == GameEventType::kAttackerDoubleTouchedBall) touch = &e;
  }
  ASSERT_NE(touch, nullptr);
  EXPECT_EQ(touch->by_team, Team::kYellow);
  EXPECT_EQ(touch->by_bot, 2u);
  expect_near(touch->location, {0.6, 0});
  EXPECT_EQ(referee.state().yellow.foul_counter, 1u);
}

TEST(BuiltinReferee, APenaltysAttackerMayPlayTheBallAgain) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kPreparePenaltyYellow, at(0)));
  ASSERT_TRUE(referee.command(Command::kNormalStart, at(1)));
  // Yellow attacks +x from the mark at -1.5: pushed on, released, then touched again by the same robot.
  referee.step(ball_at({-1.5, 0}, {yellow(2, {-1.61, 0})}), at(1.5));
  referee.step(ball_at({-1.4, 0}, {yellow(2, {-1.61, 0})}), at(1.6));
  ASSERT_TRUE(referee.game_running());
  referee.step(ball_at({0.5, 0}, {yellow(2, {-1.0, 0})}), at(2.5));
  referee.step(ball_at({1.0, 0}, {yellow(2, {0.89, 0})}), at(3.5));
  EXPECT_EQ(referee.state().command, Command::kNormalStart);
  EXPECT_EQ(count_events(referee, GameEventType::kAttackerDoubleTouchedBall), 0u);
}

TEST(BuiltinReferee, AnotherRobotsTouchClearsTheKicker) {
  BuiltinReferee referee = referee_after_free_kick();
  referee.step(ball_at({0.5, 0}, {yellow(2, {-0.11, 0}), blue(4, {0.61, 0})}), at(1.2));
  referee.step(ball_at({0.6, 0}, {yellow(2, {0.49, 0})}), at(1.5));
  EXPECT_EQ(referee.state().command, Command::kDirectFreeYellow);
  EXPECT_EQ(referee.state().yellow.foul_counter, 0u);
}

TEST(BuiltinReferee, ABallBouncingOffARobotBetweenTwoObservationsIsThatRobotsTouch) {
  // Yellow 2's free kick runs at 5 m/s into blue 4 (centre at x = 0.8) and bounces back between two
  // observations 10 ms apart: seen 0.15 m and then 0.14 m from blue 4's centre, never within its reach
  // (0.13 m), but its velocity turned. Then yellow 2 plays it again: no double touch, blue 4 touched it.
  // No measured ball velocity (as from SSL-Vision): the referee differentiates the positions.
  for (const bool bounced : {true, false}) {
    BuiltinReferee referee = referee_after_free_kick();
    // Without the bounce blue 4 stands 0.2 m off the ball's line and the ball rolls on past it.
    const Vec2 blue_at = bounced ? Vec2(0.8, 0) : Vec2(0.8, 0.2);
    for (int i = 0; i < 3; ++i) {
      referee.step(seen({0.55 + 0.05 * i, 0}, {yellow(2, {-0.11, 0}), blue(4, blue_at)}), at(1.2 + 0.01 * i));
    }
    const Vec2 after = bounced ? Vec2(0.66, 0) : Vec2(0.70, 0);
    referee.step(seen(after, {yellow(2, {-0.11, 0}), blue(4, blue_at)}), at(1.23));
    referee.step(seen({0.4, 0}, {yellow(2, {0.29, 0})}), at(1.5));  // yellow 2 plays it again
    EXPECT_EQ(referee.state().yellow.foul_counter, bounced ? 0u : 1u)
        << (bounced ? "the bounce off blue 4 is its touch" : "no touch by blue 4: a double touch");
  }
}

TEST(BuiltinReferee, AVelocityJumpBesideTheKickerBehindItsBallIsNoDoubleTouch) {
  // Yellow 2's free kick runs away from it at 2.5 m/s along +x (in play at 0.06 m), yellow 2 following 0.2 m
  // behind: released. One noisy observation puts the ball 4 cm back; from there the velocity differentiated
  // from the positions runs back towards yellow 2, so the next change of velocity (8 m/s) has a path within
  // its reach. Yellow 2 never reached the ball: no double touch. When it then drives into the ball, it is one.
  for (const bool reaches : {false, true}) {
    BuiltinReferee referee = referee_after_free_kick();
    const double observed[] = {0.085, 0.11, 0.095, 0.16, 0.185};  // truly 0.085 + 0.025 i
    for (int i = 0; i < 5; ++i) {
      const double truth = 0.085 + 0.025 * i;
      referee.step(seen({observed[i], 0}, {yellow(2, {truth - 0.2, 0})}), at(1.11 + 0.01 * i));
    }
    EXPECT_EQ(referee.state().yellow.foul_counter, 0u) << "the ball's path drawn back by noise";
    if (reaches) referee.step(seen({0.3, 0}, {yellow(2, {0.19, 0})}), at(1.2));
    EXPECT_EQ(referee.state().yellow.foul_counter, reaches ? 1u : 0u);
  }
}

TEST(BuiltinReferee, TheKickerStayingInContactCountsOnlyBeyondTheDistance) {
  for (const auto& [travel, foul] : {std::pair{0.04, false}, std::pair{0.06, true}}) {
    // Yellow 2 pushes the ball from (0, 0) without letting go: in play at 0.06 m, then `travel` further.
    BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
    ASSERT_TRUE(referee.command(Command::kDirectFreeYellow, at(0)));
    referee.step(ball_at({0, 0}, {yellow(2, {-0.11, 0})}), at(1));
    referee.step(ball_at({0.06, 0}, {yellow(2, {-0.05, 0})}), at(1.1));
    ASSERT_TRUE(referee.game_running());
    referee.step(ball_at({0.06 + travel, 0}, {yellow(2, {travel - 0.05, 0})}), at(1.2));
    EXPECT_EQ(referee.state().yellow.foul_counter, foul ? 1u : 0u) << travel << " m in contact";
  }
}

TEST(BuiltinReferee, AKickFasterThanSixPointFiveIsAFoulOncePerKick) {
  for (const auto& [speed, foul] : {std::pair{6.49, false}, std::pair{6.51, true}}) {
    BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
    referee.step(ball_at({0, 0}, {yellow(1, {-0.11, 0})}), at(1));
    referee.step({.ball_position = Vec2(0.1, 0), .ball_velocity = Vec2(speed, 0)}, at(1.02));
    referee.step({.ball_position = Vec2(0.2, 0), .ball_velocity = Vec2(speed, 0)}, at(1.04));
    EXPECT_EQ(count_events(referee, GameEventType::kBotKickedBallTooFast), foul ? 1u : 0u) << speed;
    if (!foul) continue;
    const GameEvent* kick = last_event(referee);
    EXPECT_EQ(kick->by_team, Team::kYellow);
    EXPECT_EQ(kick->by_bot, 1u);
    EXPECT_NEAR(*kick->value, 6.51, 1e-9);
    EXPECT_EQ(referee.state().command, Command::kForceStart) << "non-stopping";
  }
}

TEST(BuiltinReferee, DribblingFurtherThanOneMetreIsAFoul) {
  for (const auto& [distance, foul] : {std::pair{0.99, false}, std::pair{1.01, true}}) {
    BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
    for (int i = 0; i <= 10; ++i) {
      const double x = -1 + distance * i / 10.0;
      referee.step(ball_at({x, 1}, {yellow(1, {x - 0.11, 1})}), at(1 + 0.1 * i));
    }
    EXPECT_EQ(count_events(referee, GameEventType::kBotDribbledBallTooFar), foul ? 1u : 0u) << distance;
    if (!foul) continue;
    const GameEvent* dribble = last_event(referee);
    ASSERT_EQ(dribble->type, GameEventType::kBotDribbledBallTooFar);
    EXPECT_EQ(dribble->by_bot, 1u);
    expect_near(dribble->location, {-1, 1});
    expect_near(dribble->secondary_location, {-1 + distance, 1});
    EXPECT_EQ(referee.state().next_command, Command::kDirectFreeBlue);
  }
}

TEST(BuiltinReferee, ABallKickedOverTheWallIsABoundaryCrossing) {
  for (const auto& [y, crossing] : {std::pair{3.29, false}, std::pair{3.31, true}}) {
    BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
    referee.step(ball_at({1.0, 2.9}, {blue(2, {1.0, 2.79})}), at(1));
    referee.step(ball_at({1.0, 3.1}), at(1.1));  // over the touch line: placement for yellow
    referee.step(ball_at({1.0, y}), at(1.2));
    EXPECT_EQ(count_events(referee, GameEventType::kBoundaryCrossing), crossing ? 1u : 0u) << y;
    EXPECT_EQ(referee.state().blue.foul_counter, crossing ? 1u : 0u);
    EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow) << "the free kick stays yellow's";
  }
}

TEST(BuiltinReferee, BehindADivisionAGoalLineTheWallIsTheWiderBoundaryAway) {
  // Division A: 0.6 m from the goal lines to the walls (0.3 m along the touch lines).
  for (const auto& [x, crossing] : {std::pair{6.59, false}, std::pair{6.61, true}}) {
    BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_a(),
                           {.yellow = {"Yellow FC", 0}, .blue = {"Blue FC", 0}, .blue_on_positive_half = true});
    ASSERT_TRUE(referee.command(Command::kForceStart, at(0)));
    referee.step(ball_at({5.8, 2.0}, {blue(2, {5.69, 2.0})}), at(1));
    referee.step(ball_at({6.1, 2.0}), at(1.1));  // over the goal line beside the goal
    referee.step(ball_at({x, 2.0}), at(1.2));
    EXPECT_EQ(count_events(referee, GameEventType::kBoundaryCrossing), crossing ? 1u : 0u) << x;
  }
}

TEST(BuiltinReferee, NearTheOpponentsDefenseAreaInStopIsAFoulAfterTheGrace) {
  for (const auto& [gap, foul] : {std::pair{0.19, true}, std::pair{0.21, false}}) {
    BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
    ASSERT_TRUE(referee.command(Command::kStop, at(0)));
    const Observation near = ball_at({0, 0}, {yellow(3, {3.5 - 0.09 - gap, 2.5})});  // outside the area's y range
    const Observation close = ball_at({0, 0}, {yellow(3, {3.5 - 0.09 - gap, 0.5})});
    referee.step(gap < 0.2 ? close : near, at(1));
    referee.step(close, at(2.9));
    referee.step(close, at(3.1));
    EXPECT_EQ(count_events(referee, GameEventType::kAttackerTooCloseToDefenseArea), foul ? 1u : 0u) << gap;
    if (!foul) continue;
    EXPECT_EQ(last_event(referee)->by_bot, 3u);
    EXPECT_NEAR(*last_event(referee)->value, gap, 1e-9);
    expect_near(last_event(referee)->secondary_location, {0, 0});
  }
}

TEST(BuiltinReferee, TheBallLyingInADefenseAreaTooLongIsKeeperHoldingTheBall) {
  for (const auto& [seconds, foul] : {std::pair{9.9, false}, std::pair{10.1, true}}) {
    BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));
    // In blue's area, moving 0.06 m now and then (no "no progress").
    for (double t = 0; t <= seconds + 1e-9; t += 0.05) {
      referee.step(ball_at({3.9 + 0.06 * std::floor(t), 0.2}, {blue(0, {4.3, 0})}), at(1 + t));
    }
    EXPECT_EQ(count_events(referee, GameEventType::kKeeperHeldBall), foul ? 1u : 0u) << seconds;
    if (!foul) continue;
    EXPECT_EQ(last_event(referee)->type, GameEventType::kKeeperHeldBall);
    EXPECT_EQ(last_event(referee)->by_team, Team::kBlue);
    EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow) << "to a legal free-kick spot";
    EXPECT_EQ(referee.state().next_command, Command::kDirectFreeYellow);
  }
}

TEST(BuiltinReferee, MoreRobotsThanAllowedAfterTheGraceIsAFoul) {
  BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));  // 6 allowed
  std::vector<ObservedRobot> seven;
  for (std::uint32_t id = 0; id < 7; ++id) seven.push_back(yellow(id, {-3.0 + 0.4 * id, -2.0}));
  std::vector<ObservedRobot> six(seven.begin(), seven.end() - 1);
  for (double t = 1; t <= 20; t += 0.5) referee.step(ball_at({0, 0.06 * (static_cast<int>(t) % 2)}, six), at(t));
  EXPECT_EQ(count_events(referee, GameEventType::kTooManyRobots), 0u);
  referee.step(ball_at({0, 0}, seven), at(21));
  referee.step(ball_at({0, 0.1}, seven), at(30.9));
  EXPECT_EQ(referee.state().command, Command::kForceStart) << "within the 10 s grace";
  referee.step(ball_at({0, 0.2}, seven), at(31.1));
  const GameEvent* count = last_event(referee);
  ASSERT_NE(count, nullptr);
  EXPECT_EQ(count->type, GameEventType::kTooManyRobots);
  EXPECT_EQ(count->by_team, Team::kYellow);
  EXPECT_EQ(count->text, "7 on field, 6 allowed");
  EXPECT_EQ(referee.state().next_command, Command::kDirectFreeBlue);
}

TEST(BuiltinReferee, ARobotWhollyBeyondTheTouchLineIsNotCountedOnTheField) {
  for (const auto& [y, counted] : {std::pair{-3.08, true}, std::pair{-3.15, false}}) {
    BuiltinReferee referee = running_referee(builtin_profile("strict_ai"));  // 6 allowed, touch line y = -3
    std::vector<ObservedRobot> seven;
    for (std::uint32_t id = 0; id < 6; ++id) seven.push_back(yellow(id, {-3.0 + 0.4 * id, -2.0}));
    seven.push_back(yellow(6, {-0.3, y}));
    for (double t = 1; t <= 12; t += 0.5) referee.step(ball_at({0, 0.06 * (static_cast<int>(t) % 2)}, seven), at(t));
    EXPECT_EQ(count_events(referee, GameEventType::kTooManyRobots), counted ? 1u : 0u) << y;
  }
}

TEST(BuiltinReferee, EveryThirdFoulIsAYellowCardThatTakesARobotFor120SecondsOfPlay) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kStop, at(0)));
  std::vector<ObservedRobot> fast;
  for (std::uint32_t id = 1; id <= 3; ++id) fast.push_back(moving(yellow(id, {-2, -1.0 + id}), {2, 0}));
  referee.step(ball_at({0, 0}, {fast[0], fast[1]}), at(2.5));
  EXPECT_EQ(referee.state().yellow.foul_counter, 2u);
  EXPECT_EQ(referee.state().yellow.yellow_cards, 0u);
  referee.step(ball_at({0, 0}, fast), at(2.6));
  const TeamInfo& yellow_team = referee.state().yellow;
  EXPECT_EQ(yellow_team.foul_counter, 3u);
  EXPECT_EQ(yellow_team.yellow_cards, 1u);
  ASSERT_EQ(yellow_team.yellow_card_times_left.size(), 1u);
  EXPECT_EQ(yellow_team.yellow_card_times_left[0], duration_from_seconds(120));
  EXPECT_EQ(yellow_team.max_allowed_bots, 5u);
  EXPECT_EQ(count_events(referee, GameEventType::kMultipleFouls), 1u);

  // The card's clock runs with the game only.
  referee.step(ball_at({0, 0}), at(30));
  EXPECT_EQ(referee.state().yellow.yellow_card_times_left[0], duration_from_seconds(120)) << "not in STOP";
  ASSERT_TRUE(referee.command(Command::kForceStart, at(30)));
  for (double t = 30; t < 149.9; t += 1) referee.step(ball_at({0, 0.06 * (static_cast<int>(t) % 2)}), at(t));
  referee.step(ball_at({0, 0}), at(149.9));
  EXPECT_EQ(referee.state().yellow.max_allowed_bots, 5u) << "119.9 s of play";
  referee.step(ball_at({0, 0.06}), at(150.1));
  EXPECT_TRUE(referee.state().yellow.yellow_card_times_left.empty());
  EXPECT_EQ(referee.state().yellow.max_allowed_bots, 6u) << "the robot may come back";
}

TEST(BuiltinReferee, AThirdConcurrentYellowCardIsARedCard) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  double t = 0;
  for (int stop = 0; stop < 3; ++stop) {
    ASSERT_TRUE(referee.command(Command::kStop, at(t)));
    std::vector<ObservedRobot> fast;
    for (std::uint32_t id = 1; id <= 3; ++id) fast.push_back(moving(yellow(id, {-2, -1.0 + id}), {2, 0}));
    referee.step(ball_at({0, 0}, fast), at(t + 2.5));
    t += 3;
  }
  EXPECT_EQ(referee.state().yellow.yellow_cards, 2u);
  EXPECT_EQ(referee.state().yellow.red_cards, 1u);
  EXPECT_EQ(referee.state().yellow.max_allowed_bots, 3u);
}

TEST(BuiltinReferee, APlacementInterferenceGivesThePlacingTeamTenSecondsMore) {
  BuiltinReferee referee(builtin_profile("strict_ai"), FieldGeometry::division_b(), kBlueOnPositive);
  ASSERT_TRUE(referee.command(Command::kBallPlacementYellow, at(0), Vec2(1.0, 0.0)));
  const Observation in_the_way = ball_at({-1, 0}, {blue(4, {0.0, 0.3})});  // 0.21 m from the path's side
  referee.step(in_the_way, at(0.5));
  referee.step(in_the_way, at(2.6));
  const GameEvent* interfered = last_event(referee);
  ASSERT_NE(interfered, nullptr);
  EXPECT_EQ(interfered->type, GameEventType::kBotInterferedPlacement);
  EXPECT_EQ(interfered->by_team, Team::kBlue);
  EXPECT_EQ(interfered->by_bot, 4u);
  EXPECT_EQ(referee.state().blue.foul_counter, 1u);
  referee.step(ball_at({-1, 0}), at(3));
  EXPECT_EQ(referee.state().current_action_time_remaining, duration_from_seconds(37)) << "30 + 10 - 3";
  referee.step(ball_at({-1, 0}), at(39.9));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementYellow);
  referee.step(ball_at({-1, 0}), at(40.1));
  EXPECT_EQ(referee.state().command, Command::kBallPlacementBlue);
}

TEST(BuiltinReferee, TheArcadeProfileJudgesNoFouls) {
  BuiltinReferee referee = running_referee(builtin_profile("arcade"));
  std::vector<ObservedRobot> seven;
  for (std::uint32_t id = 0; id < 7; ++id) seven.push_back(moving(yellow(id, {-3.0 + 0.4 * id, -2.0}), {3, 0}));
  seven.push_back(moving(blue(1, {-3.0 + 0.185, -2.0}), {-3, 0}));
  for (double t = 1; t <= 30; t += 0.5) referee.step(ball_at({0, 0}, seven), at(t));
  EXPECT_EQ(referee.state().yellow.foul_counter + referee.state().blue.foul_counter, 0u);
  EXPECT_EQ(referee.state().command, Command::kForceStart);
}

}  // namespace
}  // namespace ssl::referee
