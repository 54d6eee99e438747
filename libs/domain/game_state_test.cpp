#include "libs/domain/game_state.h"

#include <gtest/gtest.h>

namespace ssl::wm {
namespace {

using C = RefereeCommand;

const time::Timestamp kKick = time::Timestamp::from_seconds(100.0);

struct Fixture {
  explicit Fixture(TeamColor us) : game(us) {}
  void send(C command, std::optional<Vec2> designated = std::nullopt) {
    RefereeInfo referee;
    referee.command = command;
    referee.command_counter = ++counter;
    referee.designated_position = designated;
    referee.blue_goalkeeper = 1;
    referee.yellow_goalkeeper = 2;
    game.update(referee, frame, ball);
  }
  GameState game;
  TeamFrame frame;
  std::uint32_t counter = 0;
  Vec2 ball = Vec2::Zero();
};

// Every restart command, from our side and theirs, for both colours.
TEST(WorldModelGameState, EveryRefereeCommandFromOurSideAndTheirs) {
  for (TeamColor us : {TeamColor::kBlue, TeamColor::kYellow}) {
    SCOPED_TRACE(std::string(to_string(us)));
    const bool blue = us == TeamColor::kBlue;
    Fixture f(us);
    f.send(C::kHalt);
    EXPECT_TRUE(f.game.is_halted());
    EXPECT_FALSE(f.game.is_playing());
    f.send(C::kStop);
    EXPECT_TRUE(f.game.is_stopped());
    EXPECT_TRUE(f.game.must_keep_distance_from_ball());

    f.send(blue ? C::kPrepareKickoffBlue : C::kPrepareKickoffYellow);
    EXPECT_TRUE(f.game.is_our_kickoff());
    EXPECT_TRUE(f.game.is_setup());
    f.send(C::kNormalStart);
    EXPECT_TRUE(f.game.is_our_kickoff());
    EXPECT_TRUE(f.game.is_ready());
    EXPECT_FALSE(f.game.is_playing());
    f.game.update_ball({0.1, 0}, kKick);  // kicked: moved > 0.05 m ...
    EXPECT_FALSE(f.game.is_playing());
    f.game.update_ball({0.2, 0}, kKick + time::duration_from_seconds(GameState::kBallMovedHold));  // ... and on
    EXPECT_TRUE(f.game.is_playing());
    EXPECT_FALSE(f.game.is_kickoff());

    f.send(C::kStop);
    f.send(blue ? C::kPrepareKickoffYellow : C::kPrepareKickoffBlue);
    EXPECT_TRUE(f.game.is_their_kickoff());
    EXPECT_TRUE(f.game.must_keep_distance_from_ball());

    f.send(C::kStop);
    f.send(blue ? C::kPreparePenaltyBlue : C::kPreparePenaltyYellow);
    EXPECT_TRUE(f.game.is_our_penalty());
    f.send(C::kStop);
    f.send(blue ? C::kPreparePenaltyYellow : C::kPreparePenaltyBlue);
    EXPECT_TRUE(f.game.is_their_penalty());

    for (C ours : {blue ? C::kDirectFreeBlue : C::kDirectFreeYellow,
                   blue ? C::kIndirectFreeBlue : C::kIndirectFreeYellow}) {
      f.send(C::kStop);
      f.send(ours);
      EXPECT_TRUE(f.game.is_our_free_kick());
      EXPECT_TRUE(f.game.is_ready());
    }
    for (C theirs : {blue ? C::kDirectFreeYellow : C::kDirectFreeBlue,
                     blue ? C::kIndirectFreeYellow : C::kIndirectFreeBlue}) {
      f.send(C::kStop);
      f.send(theirs);
      EXPECT_TRUE(f.game.is_their_free_kick());
    }

    f.send(blue ? C::kBallPlacementBlue : C::kBallPlacementYellow, Vec2(1.0, -2.0));
    EXPECT_TRUE(f.game.is_our_ball_placement());
    ASSERT_TRUE(f.game.ball_placement_position().has_value());
    EXPECT_EQ(*f.game.ball_placement_position(), Vec2(1.0, -2.0));
    f.send(blue ? C::kBallPlacementYellow : C::kBallPlacementBlue, Vec2(1.0, -2.0));
    EXPECT_TRUE(f.game.is_their_ball_placement());

    f.send(blue ? C::kTimeoutBlue : C::kTimeoutYellow);
    EXPECT_TRUE(f.game.is_our_timeout());
    f.send(blue ? C::kTimeoutYellow : C::kTimeoutBlue);
    EXPECT_TRUE(f.game.is_their_timeout());

    f.send(C::kGoalBlue);
    EXPECT_TRUE(f.game.is_goal());
    EXPECT_TRUE(f.game.is_stopped());
    f.send(C::kGoalYellow);
    EXPECT_TRUE(f.game.is_stopped());
    f.send(C::kForceStart);
    EXPECT_TRUE(f.game.is_playing());
    f.send(C::kStop);
    f.send(C::kNormalStart);
    EXPECT_TRUE(f.game.is_playing());
    EXPECT_EQ(f.game.our_goalkeeper(), blue ? 1u : 2u);
    EXPECT_EQ(f.game.their_goalkeeper(), blue ? 2u : 1u);
  }
}

TEST(WorldModelGameState, ARestartIsTakenOnlyOnceTheBallStaysMovedNotOnAJumpOfItsEstimate) {
  Fixture f(TeamColor::kBlue);
  f.send(C::kStop);
  f.send(C::kPrepareKickoffYellow);
  f.send(C::kNormalStart);
  ASSERT_TRUE(f.game.is_their_kickoff());
  const auto at = [](double s) { return kKick + time::duration_from_seconds(s); };
  f.game.update_ball({0.0, 0.0}, at(0.0));
  // The estimate jumps 8 cm for 40 ms (its velocity spiked while robots crowd the ball), then is back.
  f.game.update_ball({0.08, 0.0}, at(0.01));
  f.game.update_ball({0.08, 0.0}, at(0.04));
  f.game.update_ball({0.0, 0.0}, at(0.05));
  EXPECT_TRUE(f.game.is_their_kickoff());
  EXPECT_TRUE(f.game.must_keep_distance_from_ball());
  // Kicked: beyond 5 cm from then on, in play once it stayed there 0.05 s (boundary exact).
  f.game.update_ball({0.06, 0.0}, at(1.0));
  f.game.update_ball({0.3, 0.0}, at(1.0 + GameState::kBallMovedHold - 0.001));
  EXPECT_FALSE(f.game.is_playing());
  f.game.update_ball({0.5, 0.0}, at(1.0 + GameState::kBallMovedHold));
  EXPECT_TRUE(f.game.is_playing());
  EXPECT_FALSE(f.game.must_keep_distance_from_ball());
}

TEST(WorldModelGameState, AJumpOfTheEstimateAtNormalStartDoesNotMoveWhereTheBallWas) {
  // Seen in a match: the ball at rest on the centre mark, its estimate (predicted to now) 9 cm off for three
  // ticks just as NORMAL_START came; the ball staying where it was then looked like a taken kickoff.
  Fixture f(TeamColor::kBlue);
  const auto at = [](double s) { return kKick + time::duration_from_seconds(s); };
  f.send(C::kStop);
  f.send(C::kPrepareKickoffBlue);
  for (int i = 0; i < 20; ++i) f.game.update_ball({0.0, 0.0}, at(-0.3 + 0.01 * i));
  f.game.update_ball({0.0, -0.09}, at(-0.02));
  f.game.update_ball({0.0, -0.09}, at(-0.01));
  f.ball = Vec2(0.0, -0.09);
  f.send(C::kNormalStart);
  ASSERT_TRUE(f.game.is_ready());
  f.game.update_ball({0.0, -0.09}, at(0.0));
  for (int i = 1; i <= 30; ++i) f.game.update_ball({0.0, 0.0}, at(0.01 * i));
  EXPECT_TRUE(f.game.is_our_kickoff()) << "the kickoff is still to be taken";
  EXPECT_FALSE(f.game.is_playing());
  // Kicked: in play once beyond 5 cm of the centre mark for the hold.
  f.game.update_ball({0.2, 0.0}, at(1.0));
  f.game.update_ball({0.4, 0.0}, at(1.0 + GameState::kBallMovedHold));
  EXPECT_TRUE(f.game.is_playing());
}

TEST(WorldModelGameState, APenaltyIsInPlayFromItsKickUntilTheNextCommand) {
  const auto at = [](double s) { return kKick + time::duration_from_seconds(s); };
  for (const TeamColor us : {TeamColor::kBlue, TeamColor::kYellow}) {
    Fixture f(us);
    f.send(C::kStop);
    f.send(us == TeamColor::kBlue ? C::kPreparePenaltyBlue : C::kPreparePenaltyYellow);
    f.send(C::kNormalStart);
    f.game.update_ball({0.0, 0.0}, at(0.0));
    EXPECT_TRUE(f.game.is_our_penalty());
    EXPECT_FALSE(f.game.is_our_penalty_in_play());
    f.game.update_ball({0.1, 0.0}, at(0.01));
    f.game.update_ball({0.2, 0.0}, at(0.01 + GameState::kBallMovedHold));
    EXPECT_TRUE(f.game.is_playing());
    EXPECT_FALSE(f.game.is_penalty());
    EXPECT_TRUE(f.game.is_our_penalty_in_play());
    EXPECT_FALSE(f.game.is_their_penalty_in_play());
    f.game.update_ball({1.5, 0.0}, at(3.0));
    EXPECT_TRUE(f.game.is_our_penalty_in_play());
    f.send(C::kStop);
    EXPECT_FALSE(f.game.is_our_penalty_in_play());
    // Their penalty, and a kickoff taken the same way, are not ours.
    f.send(us == TeamColor::kBlue ? C::kPreparePenaltyYellow : C::kPreparePenaltyBlue);
    f.send(C::kNormalStart);
    f.game.update_ball({0.0, 0.0}, at(10.0));
    f.game.update_ball({0.1, 0.0}, at(10.0 + 0.01));
    f.game.update_ball({0.2, 0.0}, at(10.0 + 0.01 + GameState::kBallMovedHold));
    EXPECT_TRUE(f.game.is_their_penalty_in_play());
    EXPECT_FALSE(f.game.is_our_penalty_in_play());
    f.send(C::kStop);
    f.send(us == TeamColor::kBlue ? C::kPrepareKickoffBlue : C::kPrepareKickoffYellow);
    f.send(C::kNormalStart);
    f.game.update_ball({0.0, 0.0}, at(20.0));
    f.game.update_ball({0.1, 0.0}, at(20.0 + 0.01));
    f.game.update_ball({0.2, 0.0}, at(20.0 + 0.01 + GameState::kBallMovedHold));
    EXPECT_TRUE(f.game.is_playing());
    EXPECT_FALSE(f.game.is_our_penalty_in_play());
    EXPECT_FALSE(f.game.is_their_penalty_in_play());
  }
}

TEST(WorldModelGameState, BallPlacementPositionIsInTheTeamFrame) {
  Fixture f(TeamColor::kYellow);
  f.frame = TeamFrame::make(TeamColor::kYellow, /*blue_on_positive_half=*/false);  // yellow defends +x
  f.send(C::kBallPlacementYellow, Vec2(2.0, 1.0));
  ASSERT_TRUE(f.game.ball_placement_position().has_value());
  EXPECT_EQ(*f.game.ball_placement_position(), Vec2(-2.0, -1.0));
}

TEST(WorldModelGameState, OurPlacementRightAndRobotLimitAreOurTeamsOnly) {
  RefereeInfo referee;
  referee.yellow_can_place_ball = false;
  referee.yellow_max_allowed_bots = 5;
  referee.blue_max_allowed_bots = 6;
  for (TeamColor us : {TeamColor::kBlue, TeamColor::kYellow}) {
    GameState game(us);
    game.update(referee, TeamFrame(), std::nullopt);
    EXPECT_EQ(game.we_can_place_ball(), us == TeamColor::kBlue) << to_string(us);
    EXPECT_EQ(game.our_max_allowed_bots(), us == TeamColor::kBlue ? 6u : 5u) << to_string(us);
  }
}

}  // namespace
}  // namespace ssl::wm
