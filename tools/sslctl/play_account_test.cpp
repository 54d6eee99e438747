// The play account on scripted frames (division B: 9 m long, goals 1 m wide, blue defending the negative
// half): a ball rolled from robot to robot at explicit times, as a camera would see it every 10 ms.
#include <gtest/gtest.h>

#include <vector>

#include "tools/sslctl/play_account.h"

namespace ssl::sslctl {
namespace {

using geom::Vec2;
using Robot = PlayAccount::Robot;

const time::Timestamp kStart = time::Timestamp::from_seconds(1'000.0);
constexpr Restart kBlueFreeKick{.team = TeamColor::kBlue, .kind = RestartKind::kFreeKick};
constexpr Restart kBlueKickoff{.team = TeamColor::kBlue, .kind = RestartKind::kKickoff};

class PlayAccountTest : public ::testing::Test {
 protected:
  PlayAccountTest() {
    account_.set_field(9.0, 1.0);
    account_.on_referee(true, false);
  }
  /// `seconds` of frames every 10 ms with the ball moving from `from` at `velocity` and the robots standing;
  /// where the ball is at the last of them.
  Vec2 roll(Vec2 from, Vec2 velocity, double seconds) {
    Vec2 ball = from;
    for (int i = 0; i * 0.01 < seconds - 1e-9; ++i) {
      ball = from + velocity * (i * 0.01);
      frame(ball);
    }
    return ball;
  }
  void frame(const Vec2& ball) {
    account_.on_frame(ball, robots_, kStart + time::duration_from_seconds(now_));
    now_ += 0.01;
  }
  PlayAccount account_;
  std::vector<Robot> robots_{{TeamColor::kBlue, 1, {0, 0}},     {TeamColor::kBlue, 2, {2, 1}},
                             {TeamColor::kYellow, 1, {1, -1}},  {TeamColor::kYellow, 2, {3, 0}}};
  double now_ = 0;
};

TEST_F(PlayAccountTest, APassToATeammateIsCompletedAndPossessionStaysWithTheTeam) {
  roll({0.1, 0}, {0, 0}, 0.5);                                      // at blue 1's dribbler
  const Vec2 at = roll({0.1, 0}, Vec2(1.8, 1.0).normalized() * 3, 0.69);  // kicked towards blue 2 at 3 m/s
  roll(at, {0, 0}, 0.5);                                              // received
  const TeamPlay& blue = account_.team(TeamColor::kBlue);
  EXPECT_EQ(blue.passes_tried, 1u);
  EXPECT_EQ(blue.passes_completed, 1u);
  EXPECT_EQ(blue.shots, 0u);
  EXPECT_NEAR(blue.possession, 1.69, 0.05);
  EXPECT_EQ(account_.team(TeamColor::kYellow).possession, 0);
}

TEST_F(PlayAccountTest, AnInterceptedPassFailsAndPossessionChanges) {
  roll({0.1, 0}, {0, 0}, 0.3);
  const Vec2 at = roll({0.1, 0}, Vec2(0.9, -1.0).normalized() * 3, 0.42);  // straight at yellow 1
  roll(at, {0, 0}, 0.5);
  EXPECT_EQ(account_.team(TeamColor::kBlue).passes_tried, 1u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).passes_completed, 0u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).passes_intercepted, 1u);
  EXPECT_GT(account_.team(TeamColor::kYellow).possession, 0.4);
}

TEST_F(PlayAccountTest, AKickAtTheOpponentGoalIsAShotOnTargetAndOneBesideItIsNot) {
  robots_ = {{TeamColor::kBlue, 1, {3, 0}}};
  roll({3.1, 0}, {0, 0}, 0.2);
  roll({3.1, 0}, {5, 0.3}, 0.3);  // crosses x = 4.5 at y = 0.084: on target
  account_.on_referee(false, false);
  account_.on_referee(true, false);
  roll({3.1, 0}, {0, 0}, 0.2);
  roll({3.1, 0}, Vec2(5, 2.5), 0.3);  // crosses at y = 0.7: beside the post, within the margin
  const TeamPlay& blue = account_.team(TeamColor::kBlue);
  EXPECT_EQ(blue.shots, 2u);
  EXPECT_EQ(blue.shots_on_target, 1u);
  EXPECT_EQ(blue.passes_tried, 0u);
}

TEST_F(PlayAccountTest, AShotEndsSavedByTheKeeperBlockedByAnotherOpponentScoredOrWide) {
  account_.set_keepers(0, 1);  // yellow 1 keeps yellow's goal
  const auto shot = [&](std::vector<Robot> robots, Vec2 velocity, double seconds) {
    account_.on_referee(false, false);
    account_.on_referee(true, false);
    robots_ = std::move(robots);
    robots_.insert(robots_.begin(), {TeamColor::kBlue, 1, {3, 0}});
    roll({3.1, 0}, {0, 0}, 0.2);
    roll({3.1, 0}, velocity, seconds);
  };
  shot({{TeamColor::kYellow, 1, {4.2, 0}}}, {5, 0}, 0.3);                                    // at the keeper
  shot({{TeamColor::kYellow, 1, {4.4, 0.4}}, {TeamColor::kYellow, 2, {3.8, 0}}}, {5, 0}, 0.3);  // at yellow 2
  shot({{TeamColor::kBlue, 2, {3.8, 0}}}, {5, 0}, 0.3);  // a teammate's touch: none of them
  shot({}, {5, 0}, 0.28);                                // in
  account_.on_goal(TeamColor::kBlue);
  shot({}, {5, 2.5}, 0.3);  // beside the post, and out
  account_.on_referee(false, false);
  const TeamPlay& blue = account_.team(TeamColor::kBlue);
  EXPECT_EQ(blue.shots, 5u);
  EXPECT_EQ(blue.shots_saved, 1u);
  EXPECT_EQ(blue.shots_blocked, 1u);
  EXPECT_EQ(blue.shots_scored, 1u);
  EXPECT_NEAR(blue.shot_distance / blue.shots, 1.35, 0.01);  // recognised 10 ms (5 cm) after the kick
}

TEST_F(PlayAccountTest, TwoCamerasSeeingTheBallApartMakeNoKickButAKickSeenByEitherCounts) {
  // Camera 0 sees the ball 3 cm from where camera 1 does; their packets arrive 1 ms apart every 16 ms.
  const Vec2 offset(0.03, 0);
  const auto both = [&](const Vec2& ball, double capture) {
    for (std::uint32_t camera : {0u, 1u}) {
      account_.on_frame(ball + (camera == 0 ? offset : Vec2::Zero()), robots_,
                        kStart + time::duration_from_seconds(now_),
                        PlayAccount::Camera{.id = camera, .capture = time::Timestamp::from_seconds(capture)});
      now_ += 0.001;
    }
    now_ += 0.014;
  };
  double capture = 50.0;
  for (int i = 0; i < 30; ++i, capture += 0.016) both({0.1, 0}, capture);  // at blue 1's dribbler
  EXPECT_EQ(account_.team(TeamColor::kBlue).kicks, 0u);
  const Vec2 kick = Vec2(1.8, 1.0).normalized() * 3;  // to blue 2
  for (int i = 1; i < 30; ++i, capture += 0.016) both(Vec2(0.1, 0) + kick * (i * 0.016), capture);
  EXPECT_EQ(account_.team(TeamColor::kBlue).kicks, 1u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).passes_tried, 1u);
}

TEST_F(PlayAccountTest, AfterTheSideSwapTheOtherGoalIsBluesTarget) {
  account_.on_referee(true, true);  // blue now defends the positive half
  robots_ = {{TeamColor::kBlue, 1, {3, 0}}};
  roll({3.1, 0}, {0, 0}, 0.2);
  roll({3.1, 0}, {5, 0}, 0.3);  // towards its own goal: not a shot
  EXPECT_EQ(account_.team(TeamColor::kBlue).shots, 0u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).passes_tried, 1u);
}

TEST_F(PlayAccountTest, TheKickersIntentOverridesTheGeometry) {
  robots_ = {{TeamColor::kBlue, 1, {3, 0}, PlayAccount::Intent::kClear}};
  roll({3.1, 0}, {0, 0}, 0.2);
  roll({3.1, 0}, {5, 0}, 0.3);
  EXPECT_EQ(account_.team(TeamColor::kBlue).shots, 0u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).passes_tried, 0u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).kicks, 1u);
}

TEST_F(PlayAccountTest, AShootersKickAwayFromTheGoalIsNeitherAShotNorAPass) {
  robots_ = {{TeamColor::kBlue, 1, {3, 0}, PlayAccount::Intent::kShot}};
  roll({3.1, 0}, {0, 0}, 0.2);
  roll({3.1, 0}, {0, 5}, 0.3);
  EXPECT_EQ(account_.team(TeamColor::kBlue).shots, 0u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).passes_tried, 0u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).kicks, 1u);
}

TEST_F(PlayAccountTest, ABallSpedUpByARobotWithoutItsKickerArmedIsATouchAndNoPass) {
  robots_ = {{TeamColor::kBlue, 1, {0, 0}, PlayAccount::Intent::kNoKick}, {TeamColor::kYellow, 1, {1, 0}}};
  roll({0.1, 0}, {0, 0}, 0.2);                     // at blue 1's body
  const Vec2 at = roll({0.1, 0}, {3, 0}, 0.3);     // off it at 3 m/s, to yellow 1
  roll(at, {0, 0}, 0.3);
  const TeamPlay& blue = account_.team(TeamColor::kBlue);
  EXPECT_EQ(blue.kicks, 0u);
  EXPECT_EQ(blue.passes_tried, 0u);
  EXPECT_EQ(blue.passes_intercepted, 0u);
  EXPECT_NEAR(blue.possession, 0.46, 0.05);  // blue's until yellow 1 touches it, 0.26 s after the push
  EXPECT_GT(account_.team(TeamColor::kYellow).possession, 0.2);
}

TEST_F(PlayAccountTest, NothingCountsWhileTheBallIsNotInPlay) {
  account_.on_referee(false, false);
  roll({0.1, 0}, {0, 0}, 0.3);
  const Vec2 at = roll({0.1, 0}, Vec2(1.8, 1.0).normalized() * 3, 0.69);
  roll(at, {0, 0}, 0.5);
  EXPECT_EQ(account_.team(TeamColor::kBlue).kicks, 0u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).possession, 0);
}

TEST_F(PlayAccountTest, APassOpenWhenPlayStopsFails) {
  roll({0.1, 0}, {0, 0}, 0.3);
  roll({0.1, 0}, {0, 3}, 0.5);  // towards the touch line, nobody there
  account_.on_referee(false, false);
  account_.on_referee(true, false);
  roll({2.0 - 0.1, 1.0}, {0, 0}, 0.3);  // placed at blue 2 for the next play
  EXPECT_EQ(account_.team(TeamColor::kBlue).passes_tried, 1u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).passes_completed, 0u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).passes_out, 1u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).passes_intercepted, 0u);
}

TEST_F(PlayAccountTest, AFreeKickPassedToATeammateIsKept) {
  account_.on_referee(false, false);
  account_.on_referee(true, false, kBlueFreeKick);  // blue's free kick is taken
  roll({0.1, 0}, {0, 0}, 0.3);                                           // blue 1, the taker
  const Vec2 at = roll({0.1, 0}, Vec2(1.8, 1.0).normalized() * 3, 0.69);  // to blue 2
  roll(at, {0, 0}, 0.3);
  EXPECT_EQ(account_.team(TeamColor::kBlue).free_kicks.taken, 1u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).free_kicks.kept, 1u);
  EXPECT_EQ(account_.team(TeamColor::kYellow).free_kicks.taken, 0u);
}

TEST_F(PlayAccountTest, AFreeKickTheOpponentsTouchNextIsNotKeptNorIsALaterGoalFromIt) {
  account_.on_referee(false, false);
  account_.on_referee(true, false, kBlueFreeKick);
  roll({0.1, 0}, {0, 0}, 0.3);
  const Vec2 at = roll({0.1, 0}, Vec2(0.9, -1.0).normalized() * 3, 0.42);  // straight at yellow 1
  roll(at, {0, 0}, 0.3);
  roll({2.0 - 0.1, 1.0}, {0, 0}, 0.3);  // then blue 2 has it: too late
  account_.on_goal(TeamColor::kBlue);   // and scores
  EXPECT_EQ(account_.team(TeamColor::kBlue).free_kicks.taken, 1u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).free_kicks.kept, 0u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).free_kicks.goals, 0u);
}

TEST_F(PlayAccountTest, ARestartThatScoresIsKeptAndOneThatGoesOutIsNot) {
  account_.on_referee(false, false);
  account_.on_referee(true, false, kBlueFreeKick);
  roll({0.1, 0}, {0, 0}, 0.3);
  roll({0.1, 0}, {4, 0}, 0.3);  // a shot
  account_.on_goal(TeamColor::kBlue);
  account_.on_referee(false, false);
  account_.on_referee(true, false, kBlueFreeKick);  // the next one goes out
  roll({0.1, 0}, {0, 0}, 0.3);
  roll({0.1, 0}, {0, 3}, 0.5);
  account_.on_referee(false, false);
  EXPECT_EQ(account_.team(TeamColor::kBlue).free_kicks.taken, 2u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).free_kicks.kept, 1u);
  EXPECT_EQ(account_.team(TeamColor::kBlue).free_kicks.goals, 1u);
}

TEST_F(PlayAccountTest, AKickoffIsCountedApartFromTheFreeKickThatFollowsIt) {
  account_.on_referee(false, false);
  account_.on_referee(true, false, kBlueKickoff);
  roll({0.1, 0}, {0, 0}, 0.3);
  const Vec2 at = roll({0.1, 0}, Vec2(1.8, 1.0).normalized() * 3, 0.69);  // to blue 2: kept
  roll(at, {0, 0}, 0.3);
  account_.on_referee(false, false);
  account_.on_referee(true, false, kBlueFreeKick);  // a free kick from the same spot, shot into the goal
  roll({0.1, 0}, {0, 0}, 0.3);
  roll({0.1, 0}, {4, 0}, 0.3);
  account_.on_goal(TeamColor::kBlue);
  const TeamPlay& blue = account_.team(TeamColor::kBlue);
  EXPECT_EQ(blue.kickoffs.taken, 1u);
  EXPECT_EQ(blue.kickoffs.kept, 1u);
  EXPECT_EQ(blue.kickoffs.goals, 0u);
  EXPECT_EQ(blue.free_kicks.taken, 1u);
  EXPECT_EQ(blue.free_kicks.kept, 1u);
  EXPECT_EQ(blue.free_kicks.goals, 1u);
  EXPECT_EQ(blue.penalties.taken, 0u);
}

}  // namespace
}  // namespace ssl::sslctl
