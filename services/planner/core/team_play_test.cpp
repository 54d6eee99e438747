// The coach and the base strategy's team play as pure functions: the style each reading asks for and its
// hysteresis, the pass ratings, and the roles handed out (one marker per opponent, defenders goal-side).
// How they play in the simulator: tests/simulated (the 2 v 0 pass scenario, the whole match) and
// bench/match_series.
#include "services/planner/core/team_play.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "services/planner/core/planner_test_util.h"
#include "services/planner/core/skills.h"

namespace ssl::planner {
namespace {

using testing::robot_at;

struct Scene {
  PlannerConfig config;
  std::vector<wm::RobotState> robots;
  std::vector<wm::RobotState> enemies;
  Situation s;

  explicit Scene(const Vec2& ball) {
    s.config = &config;
    s.field = wm::Field(FieldGeometry::division_b());
    s.ball_known = true;
    s.ball = ball;
  }
  const Situation& situation() {
    s.robots = robots;
    s.enemies = enemies;
    s.zones.field = s.field;
    return s;
  }
};

GameReading reading(wm::Possession possession, Third third, int advantage = 0, double momentum = 0) {
  return {.possession = possession, .ball_third = third, .momentum = momentum, .advantage = advantage};
}

TEST(Coach, EachReadingAsksForItsStyle) {
  using P = wm::Possession;
  EXPECT_EQ(style_for(reading(P::kFriendly, Third::kMiddle)), Style::kBuildUpAttack);
  EXPECT_EQ(style_for(reading(P::kFriendly, Third::kTheirs)), Style::kHighPressureAttack);
  EXPECT_EQ(style_for(reading(P::kFriendly, Third::kMiddle, -1)), Style::kHoldPossession);
  EXPECT_EQ(style_for(reading(P::kFriendly, Third::kOurs, -2)), Style::kClearance);
  EXPECT_EQ(style_for(reading(P::kEnemy, Third::kOurs)), Style::kScrambleDefence);
  EXPECT_EQ(style_for(reading(P::kEnemy, Third::kTheirs)), Style::kPressBall);
  EXPECT_EQ(style_for(reading(P::kNone, Third::kMiddle)), Style::kContestBall);
  EXPECT_EQ(style_for(reading(P::kContested, Third::kOurs, 0, -0.5)), Style::kScrambleDefence);
  EXPECT_EQ(mode_of(Style::kHoldPossession), TeamMode::kAttacking);
  EXPECT_EQ(mode_of(Style::kPressBall), TeamMode::kDefending);
  EXPECT_EQ(mode_of(Style::kContestBall), TeamMode::kContesting);
}

TEST(Coach, ANewStyleWaitsForItsDelayExceptAScrambleDefence) {
  Coach coach({.switch_delay = 0.3});
  const GameReading attack = reading(wm::Possession::kFriendly, Third::kMiddle);
  const GameReading press = reading(wm::Possession::kEnemy, Third::kMiddle);
  EXPECT_EQ(coach.decide(attack, 0.0), Style::kBuildUpAttack);  // the first style at once
  EXPECT_EQ(coach.decide(press, 0.1), Style::kBuildUpAttack);
  EXPECT_EQ(coach.decide(press, 0.39), Style::kBuildUpAttack);   // 0.29 s asked for: not yet
  EXPECT_EQ(coach.decide(press, 0.40), Style::kPressBall);       // 0.3 s: switched
  // A flicker back and forth never switches.
  for (int i = 0; i < 20; ++i) {
    EXPECT_EQ(coach.decide(i % 2 == 0 ? attack : press, 0.5 + 0.1 * i), Style::kPressBall);
  }
  // Danger does not wait.
  EXPECT_EQ(coach.decide(reading(wm::Possession::kEnemy, Third::kOurs), 3.0), Style::kScrambleDefence);
}

TEST(Coach, MomentumFollowsTheBallsDriftAndNumbersCountAroundTheBall) {
  Coach coach({.momentum_time = 1.0, .momentum_speed = 2.0});
  Scene scene({0, 0});
  scene.robots = {robot_at({0.5, 0}, 0, 1), robot_at({1.0, 0.5}, 0, 2), robot_at({3.0, 0}, 0, 3)};
  scene.enemies = {robot_at({-0.5, 0}, 0, 1)};
  scene.s.ball_velocity = Vec2(-2.0, 0);  // towards our goal at the momentum speed
  GameReading r;
  for (int i = 0; i < 300; ++i) {
    scene.s.now = i * 0.01;
    r = coach.read(scene.situation());
  }
  EXPECT_LT(r.momentum, -0.9);
  EXPECT_EQ(r.advantage, 1);  // two of ours, one of theirs within 1.5 m
  EXPECT_EQ(r.ball_third, Third::kMiddle);
}

TEST(TeamPlay, APassIntoAnOpponentsPathIsRejectedAndAnOpenOneIsRated) {
  Scene scene({0, 0});
  scene.robots = {robot_at({-0.1, 0}, 0, 1), robot_at({2.5, 1.0}, 0, 2), robot_at({2.5, -1.0}, 0, 3)};
  scene.enemies = {robot_at({1.25, 0.45}, 0, 7)};  // just beside the line to robot 2
  const std::vector<PassOption> options = rate_passes(scene.situation(), 1);
  ASSERT_EQ(options.size(), 1u);
  EXPECT_EQ(options.front().receiver, 3u);
  EXPECT_GT(options.front().margin, 0.15);
  // Up the field to robot 3's dribbler, on its line from the ball.
  const double dd = dribbler_distance(scene.situation());
  EXPECT_NEAR(options.front().progress, 2.5 - dd * 2.5 / std::hypot(2.5, 1.0), 1e-9);
}

TEST(TeamPlay, APassGoesToTheDribblerOfItsReceiverStopped) {
  // A teammate standing still takes the ball at its dribbler, on the line from the ball; one running takes it
  // at its dribbler where it can stop (at 3 m/s^2). A pass to its centre makes a receiver run into the ball.
  Scene scene({0, 0});
  wm::RobotState running = robot_at({-1.0, 2.0}, 0, 3);
  running.velocity = Vec2(0.0, 1.5);
  scene.robots = {robot_at({-0.1, 0}, 0, 1), robot_at({2.0, 0.0}, 0, 2), running};
  const Situation& s = scene.situation();
  const double dd = dribbler_distance(s);
  std::map<std::uint32_t, Vec2> point_of;
  for (const PassOption& option : rate_passes(s, 1)) point_of[option.receiver] = option.point;
  ASSERT_EQ(point_of.size(), 2u);
  EXPECT_NEAR((point_of[2] - Vec2(2.0 - dd, 0.0)).norm(), 0.0, 1e-9);
  const Vec2 stop(-1.0, 2.0 + 1.5 * 1.5 / (2 * 3.0));
  EXPECT_NEAR((point_of[3] - (stop - stop.normalized() * dd)).norm(), 0.0, 1e-9);
}

TEST(TeamPlay, TheReceiverNearTheirGoalIsPreferredAndPassesOutOfRangeAreNotRated) {
  Scene scene({0, 0});
  scene.robots = {robot_at({-0.1, 0}, 0, 1), robot_at({3.0, 0.3}, 0, 2), robot_at({-1.5, 1.0}, 0, 3),
                  robot_at({0.4, 0.2}, 0, 4), robot_at({-4.2, 0}, 0, 5)};
  const std::vector<PassOption> options = rate_passes(scene.situation(), 1, {.max_pass = 4.0});
  ASSERT_EQ(options.size(), 2u);  // 4: too short; 5: too long
  EXPECT_EQ(options[0].receiver, 2u);
  EXPECT_EQ(options[1].receiver, 3u);
  EXPECT_GT(options[0].receiver_shot, options[1].receiver_shot);
}

TEST(TeamPlay, EveryMarkerMarksADifferentOpponentAndDefendersBlockTheLanesGoalSide) {
  Scene scene({-2.0, 0.5});
  scene.s.possession = wm::Possession::kEnemy;
  scene.s.keeper = 0;
  scene.robots = {robot_at({-4.3, 0}, 0, 0),  robot_at({-1.0, 0}, 0, 1), robot_at({0.0, 1.0}, 0, 2),
                  robot_at({0.0, -1.0}, 0, 3), robot_at({1.0, 0.0}, 0, 4), robot_at({2.0, 2.0}, 0, 5)};
  scene.enemies = {robot_at({-2.1, 0.5}, 0, 1), robot_at({-2.5, -1.5}, 0, 2), robot_at({-1.0, 2.0}, 0, 3),
                   robot_at({0.5, -2.0}, 0, 4), robot_at({4.3, 0}, 0, 5)};
  TeamPlayMemory memory;
  TeamIntents out;
  read_game(scene.situation(), memory);
  ASSERT_EQ(memory.style, Style::kScrambleDefence);
  const std::optional<std::uint32_t> attacker = assign_roles(scene.situation(), memory, out);
  ASSERT_TRUE(attacker);
  EXPECT_EQ(memory.role_of[*attacker], Role::kPresser);
  attack(scene.situation(), memory, *attacker, out);
  EXPECT_EQ(memory.role_of[0], Role::kGoalie);
  std::set<std::uint32_t> marked;
  int defenders = 0;
  for (std::uint32_t id = 1; id < 6; ++id) {
    ASSERT_TRUE(memory.role_of[id]) << "robot " << id << " has no role";
    if (memory.role_of[id] == Role::kMarker) {
      ASSERT_TRUE(memory.marked[id]);
      EXPECT_TRUE(marked.insert(*memory.marked[id]).second) << "two markers on opponent " << *memory.marked[id];
      EXPECT_NE(*memory.marked[id], 5u) << "their keeper is not worth a marker";
    }
    if (memory.role_of[id] == Role::kDefender) {
      ++defenders;
      EXPECT_LT(memory.formation[id].x(), scene.s.ball.x()) << "a defender stands goal-side of the ball";
      EXPECT_FALSE(scene.s.field.in_our_defense_area(memory.formation[id], 0.09)) << "robot " << id;
    }
    EXPECT_TRUE(out.robots[id].active) << "robot " << id;
  }
  EXPECT_EQ(defenders, 2);
}

/// One strategy tick up to the attacker's play: the game read, the roles assigned (robot 1 the attacker), the
/// attacker's play.
TeamIntents attacker_plays(Scene& scene, TeamPlayMemory& memory) {
  TeamIntents out;
  read_game(scene.situation(), memory);
  const std::optional<std::uint32_t> attacker = assign_roles(scene.situation(), memory, out);
  EXPECT_EQ(attacker, 1u);
  if (attacker) attack(scene.situation(), memory, *attacker, out);
  return out;
}

TEST(TeamPlay, AnAttackerWithAPoorShotStartsAPassAndItsReceiverWaitsForIt) {
  // Building up (the ball in midfield, ours), the attacker holds the ball facing its open teammate.
  Scene scene({1.0, 2.5});
  scene.s.possession = wm::Possession::kFriendly;
  const Vec2 to_mate = Vec2(Vec2(3.0, 0.0) - Vec2(1.0, 2.5)).normalized();
  const double facing = std::atan2(to_mate.y(), to_mate.x());
  scene.robots = {robot_at(Vec2(Vec2(1.0, 2.5) - to_mate * 0.12), facing, 1), robot_at({3.0, 0.0}, 0, 2)};
  TeamPlayMemory memory;
  const TeamIntents out = attacker_plays(scene, memory);
  ASSERT_TRUE(memory.pass);
  EXPECT_EQ(memory.pass->receiver, 2u);
  EXPECT_EQ(out.robots[1].tactic, "pass");
  EXPECT_EQ(out.robots[2].role, to_string(Role::kReceiver));
  EXPECT_TRUE(pass_in_progress(scene.situation(), memory));
  // Set up for longer than its timeout without a kick: the pass is off.
  scene.s.now = 3.0;
  EXPECT_FALSE(pass_in_progress(scene.situation(), memory));
  EXPECT_FALSE(memory.pass);
}

TEST(TeamPlay, AnAttackerInTheirThirdKeepsTheBallRatherThanTakeAPoorShot) {
  // Division B, ours in their third pressing (the high-pressure style): the attacker has the ball at its
  // dribbler facing their goal, a wall of three of theirs 1.5 m ahead and their keeper hide most of the
  // mouth; its one teammate in range is marked (an opponent in the lane). It keeps the ball (a shot this poor
  // gives it away) instead of shooting.
  Scene scene({2.5, 0.3});
  scene.s.possession = wm::Possession::kFriendly;
  scene.robots = {robot_at({2.5 - 0.12, 0.3}, 0, 1), robot_at({1.0, -2.0}, 0, 2)};
  const std::vector<wm::RobotState> wall = {robot_at({4.0, -0.25}, M_PI, 6), robot_at({4.0, 0.0}, M_PI, 7),
                                            robot_at({4.0, 0.25}, M_PI, 8), robot_at({4.4, 0.1}, M_PI, 9)};
  scene.enemies = wall;
  scene.enemies.push_back(robot_at({1.75, -0.85}, 0, 10));
  ASSERT_LT(shot_quality(scene.situation(), scene.s.ball, 1u), TeamPlayParams{}.hold_below);
  ASSERT_TRUE(rate_passes(scene.situation(), 1).empty());
  TeamPlayMemory memory;
  const TeamIntents out = attacker_plays(scene, memory);
  EXPECT_EQ(memory.style, Style::kHighPressureAttack);
  EXPECT_EQ(out.robots[1].tactic, "hold");
  EXPECT_EQ(out.robots[1].kick, KickType::kNone);
  // Kept up to max_hold; held longer, it does not move and the referee restarts it (no progress): the shot.
  scene.s.now += TeamPlayParams{}.max_hold;
  EXPECT_EQ(attacker_plays(scene, memory).robots[1].tactic, "hold");
  scene.s.now += 0.1;
  EXPECT_EQ(attacker_plays(scene, memory).robots[1].tactic, "attack");
  scene.s.now = 0;
  // With no teammate in passing range, holding the ball leads nowhere: the shot.
  scene.robots = {robot_at({2.5 - 0.12, 0.3}, 0, 1)};
  TeamPlayMemory alone;
  EXPECT_EQ(attacker_plays(scene, alone).robots[1].tactic, "attack");
  // With the mouth open, the shot.
  scene.robots = {robot_at({2.5 - 0.12, 0.3}, 0, 1), robot_at({1.0, -2.0}, 0, 2)};
  scene.enemies = {robot_at({4.4, 0.1}, M_PI, 9), robot_at({1.75, -0.85}, 0, 10)};
  TeamPlayMemory open;
  EXPECT_EQ(attacker_plays(scene, open).robots[1].tactic, "attack");
}

TEST(TeamPlay, APassInFlightIsJudgedDeflectedOnlyAfterARobotReachedTheBall) {
  // A pass from robot 1 at (0, 0) to robot 2 at (3, 0), 1 m on its way.
  Scene scene({1.0, 0.0});
  scene.robots = {robot_at({0.0, 0.0}, 0, 1), robot_at({3.0, 0.0}, M_PI, 2)};
  scene.enemies = {robot_at({1.0, 1.5}, 0, 7)};
  TeamPlayMemory memory;
  memory.pass = PassIntent{.passer = 1, .receiver = 2, .point = {3.0, 0.0}, .phase = PassIntent::Phase::kInFlight};
  scene.s.ball_velocity = {2.0, 0.0};
  scene.s.now = 0.1;
  EXPECT_TRUE(pass_in_progress(scene.situation(), memory));
  // The estimate turns 45 degrees with no robot near the ball (a camera seam): still the same pass.
  scene.s.ball_velocity = {1.5, 1.5};
  scene.s.now = 0.2;
  EXPECT_TRUE(pass_in_progress(scene.situation(), memory));
  // The opponent reaches the ball's line just short of touching it (within 5 cm) ...
  scene.s.ball_velocity = {2.0, 0.0};
  scene.enemies = {robot_at({1.0, scene.config.robot_radius + scene.s.field.size().ball_radius + 0.04}, 0, 7)};
  scene.s.now = 0.3;
  EXPECT_TRUE(pass_in_progress(scene.situation(), memory));
  // ... and the ball runs off the line a moment later: deflected, the pass is over.
  scene.enemies = {robot_at({1.0, 1.0}, 0, 7)};
  scene.s.ball = {1.2, -0.1};
  scene.s.ball_velocity = {1.0, -1.5};
  scene.s.now = 0.5;
  EXPECT_FALSE(pass_in_progress(scene.situation(), memory));
  EXPECT_FALSE(memory.pass);
}

TEST(TeamPlay, AFreeKickBehindAWallIsPassedRoundItToATeammateWhoShootsItOnAtOnce) {
  // Division B: our free kick 1 m in front of their defense area, a wall of two 0.6 m in front of the ball,
  // their keeper in the goal near the +y post: the straight shot is hidden. Robot 2 waits wide on +y.
  Scene scene({2.5, 0.0});
  scene.robots = {robot_at({2.38, 0.0}, 0, 1), robot_at({2.6, 1.6}, 0, 2), robot_at({-1.0, 0.0}, 0, 3)};
  scene.enemies = {robot_at({3.1, -0.1}, M_PI, 7), robot_at({3.1, 0.1}, M_PI, 8), robot_at({4.35, 0.25}, M_PI, 9)};
  const TeamPlayParams params;
  EXPECT_LT(shot_quality(scene.situation(), scene.s.ball, 1u), 0.05);
  const std::optional<PassOption> option = rate_redirect(scene.situation(), 1, params);
  ASSERT_TRUE(option);
  EXPECT_EQ(option->receiver, 2u);
  const Vec2 point = option->point;
  EXPECT_GT(point.y(), 0.5);  // round the wall
  const double length = (point - scene.s.ball).norm();
  EXPECT_GE(length, params.redirect_min_pass);
  EXPECT_LE(length, params.redirect_max_pass);
  EXPECT_GE(option->receiver_shot, params.redirect_min_shot);
  const Vec2 back = (scene.s.ball - point).normalized();
  const Vec2 on = (goal_opening(scene.situation(), point).target - point).normalized();
  EXPECT_LE(std::acos(back.dot(on)), params.redirect_max_angle + 1e-9);
  // Without the wall the straight shot is open: no set play.
  scene.enemies = {robot_at({4.35, 0.25}, M_PI, 9)};
  EXPECT_FALSE(rate_redirect(scene.situation(), 1, params));
}

TEST(TeamPlay, AFreeKickWithNoShotAndNoRedirectIsPassedToAFreeTeammate) {
  // Division B, our free kick at midfield (FreeKickPlay::kPass): a wall of two 0.6 m ahead and their keeper
  // hide the goal; no point near their goal for a one-touch shot. Robot 2 stands free on +y.
  Scene scene({0.0, 0.0});
  scene.config.free_kick = FreeKickPlay::kPass;
  scene.s.restart_kicker = 1u;
  scene.robots = {robot_at({-0.12, 0.0}, 0, 1), robot_at({1.0, 2.2}, 0, 2), robot_at({-2.0, -1.0}, 0, 3)};
  scene.enemies = {robot_at({0.6, -0.1}, M_PI, 7), robot_at({0.6, 0.1}, M_PI, 8), robot_at({4.4, 0.0}, M_PI, 9)};
  ASSERT_LT(shot_quality(scene.situation(), scene.s.ball, 1u), TeamPlayParams{}.shoot_quality);
  ASSERT_FALSE(rate_redirect(scene.situation(), 1));
  const std::optional<PassOption> option = rate_free_kick_pass(scene.situation(), 1);
  ASSERT_TRUE(option);
  EXPECT_EQ(option->receiver, 2u);
  TeamPlayMemory memory;
  TeamIntents out;
  free_kick_set_play(scene.situation(), memory, out);
  ASSERT_TRUE(memory.pass);
  EXPECT_EQ(memory.pass->receiver, 2u);
  EXPECT_FALSE(memory.pass->one_touch);
  EXPECT_EQ(out.robots[1].tactic, "free_kick_pass");
  EXPECT_EQ(out.robots[1].skill, "pass");
  EXPECT_EQ(out.robots[2].tactic, "free_kick_receive");
  // FreeKickPlay::kRedirect (the set play alone) keeps the straight shot here.
  scene.config.free_kick = FreeKickPlay::kRedirect;
  TeamPlayMemory redirect_only;
  TeamIntents shot;
  free_kick_set_play(scene.situation(), redirect_only, shot);
  EXPECT_FALSE(redirect_only.pass);
  // With the goal open from the ball (no wall, no keeper, 2 m out), the straight shot: no pass.
  scene.config.free_kick = FreeKickPlay::kPass;
  scene.s.ball = {2.5, 0.0};
  scene.robots = {robot_at({2.38, 0.0}, 0, 1), robot_at({1.0, 2.2}, 0, 2), robot_at({-2.0, -1.0}, 0, 3)};
  scene.enemies.clear();
  EXPECT_FALSE(rate_free_kick_pass(scene.situation(), 1));
}

/// Division B, our kickoff may be taken: the kicker (1) behind the ball on the centre mark, the wings (2 on +y,
/// 3 on -y) beside the centre circle in our half, a defender (4) in front of our defense area; their robots
/// out of the circle in their half.
Scene kickoff_scene() {
  Scene scene({0.0, 0.0});
  scene.s.restart_kicker = 1u;
  scene.robots = {robot_at({-0.12, 0.0}, 0, 1), robot_at({-0.35, 1.2}, 0, 2), robot_at({-0.35, -1.2}, 0, 3),
                  robot_at({-3.2, 0.0}, 0, 4)};
  scene.enemies = {robot_at({0.7, 0.0}, M_PI, 7), robot_at({1.5, -1.5}, M_PI, 8)};
  return scene;
}

TEST(TeamPlay, AKickoffIsPassedToAnOpenWingWhoWaitsForItInOurHalf) {
  Scene scene = kickoff_scene();
  scene.enemies.push_back(robot_at({0.1, 0.65}, M_PI, 9));  // beside the +y wing's lane
  TeamPlayMemory memory;
  TeamIntents out;
  kickoff_set_play(scene.situation(), memory, out);
  ASSERT_TRUE(memory.pass);
  EXPECT_EQ(memory.pass->passer, 1u);
  EXPECT_EQ(memory.pass->receiver, 3u);  // the open wing
  EXPECT_FALSE(memory.pass->one_touch);
  EXPECT_LT(memory.pass->point.x(), 0.0);
  EXPECT_EQ(out.robots[1].tactic, "kickoff_pass");
  EXPECT_EQ(out.robots[1].skill, "pass");
  EXPECT_EQ(out.robots[3].tactic, "kickoff_receive");
  EXPECT_LT(out.robots[3].target.x(), 0.0);  // it stays in our half until the ball is in play
  EXPECT_FALSE(out.robots[2].active);
  // Still being set up a tick later: the same pass.
  scene.s.now = 0.01;
  TeamIntents next;
  kickoff_set_play(scene.situation(), memory, next);
  ASSERT_TRUE(memory.pass);
  EXPECT_EQ(memory.pass->receiver, 3u);
  EXPECT_EQ(next.robots[1].tactic, "kickoff_pass");
}

TEST(TeamPlay, AKickoffWithNoOpenWingOrNotKickedInTimeIsTheStraightShot) {
  {
    Scene scene = kickoff_scene();
    scene.enemies.push_back(robot_at({0.15, 1.1}, M_PI, 9));   // beside both wings
    scene.enemies.push_back(robot_at({0.15, -1.1}, M_PI, 10));
    TeamPlayMemory memory;
    TeamIntents out;
    kickoff_set_play(scene.situation(), memory, out);
    EXPECT_FALSE(memory.pass);
    ASSERT_TRUE(memory.restart);
    EXPECT_TRUE(memory.restart->shoot);
    EXPECT_FALSE(out.robots[1].active);  // the kickoff play's straight shot stands
  }
  Scene scene = kickoff_scene();
  TeamPlayMemory memory;
  const TeamPlayParams params;
  for (double t = 0; t <= params.kickoff_set_up_timeout; t += 0.01) {
    scene.s.now = t;
    TeamIntents out;
    kickoff_set_play(scene.situation(), memory, out);
    ASSERT_TRUE(memory.pass) << t;
  }
  scene.s.now = params.kickoff_set_up_timeout + 0.02;
  TeamIntents out;
  kickoff_set_play(scene.situation(), memory, out);
  EXPECT_FALSE(memory.pass);
  EXPECT_FALSE(out.robots[1].active);
}

TEST(TeamPlay, AHolderFacingAwayFromItsOpenTeammateTurnsWithTheBallBeforePassing) {
  Scene scene({1.0, 2.5});
  scene.s.possession = wm::Possession::kFriendly;
  scene.robots = {robot_at({1.0 - 0.12, 2.5}, 0.0, 1), robot_at({3.0, 0.0}, 0, 2)};  // facing +x, 51 degrees off
  TeamPlayMemory memory;
  const TeamIntents out = attacker_plays(scene, memory);
  EXPECT_FALSE(memory.pass);
  EXPECT_EQ(out.robots[1].tactic, "hold");
  EXPECT_EQ(out.robots[1].skill, "turn_with_ball");
  EXPECT_TRUE(out.robots[1].dribble);
  EXPECT_NEAR(out.robots[1].orientation, std::atan2(-2.5, 2.0), 1e-6);  // towards the teammate
}

TEST(TeamPlay, AnAttackerHoldingTheBallOnTheEdgeOfTheirDefenseAreaDoesNotTurnWithIt) {
  // Division B: the ball 2 cm in front of their defense area (its front at x = 3.5), at the attacker's
  // dribbler, the attacker facing 1 rad off their goal. Turning with the ball would drag it into the area.
  for (const double x : {3.48, 2.5}) {
    Scene scene({x, -0.06});
    scene.s.possession = wm::Possession::kFriendly;
    const double facing = 1.0;
    const Vec2 at = scene.s.ball - Vec2(std::cos(facing), std::sin(facing)) * 0.12;
    scene.robots = {robot_at(at, facing, 1)};
    TeamPlayMemory memory;
    const TeamIntents out = attacker_plays(scene, memory);
    if (x > 3.0) {
      EXPECT_NE(out.robots[1].skill, "turn_with_ball");
    } else {
      EXPECT_EQ(out.robots[1].skill, "turn_with_ball");  // away from the area it turns with the ball as before
    }
  }
}

TEST(StableAssigner, GivenCostsAreAssignedOptimallyAndKeptUnlessClearlyCheaper) {
  StableAssigner assigner(0.3);
  CostMatrix cost{};
  cost[0] = {1.0, 2.0};
  cost[1] = {2.0, 1.5};
  const std::array<std::uint32_t, 2> ids{4, 7};
  auto first = assigner.assign_costs(1, ids, cost, 2);
  EXPECT_EQ(first[0], 0);
  EXPECT_EQ(first[1], 1);
  cost[0] = {1.9, 2.0};  // swapping would save 0.2: within the hysteresis
  cost[1] = {2.0, 2.1};
  auto second = assigner.assign_costs(1, ids, cost, 2);
  EXPECT_EQ(second[0], 0);
  cost[0] = {3.0, 1.0};  // now clearly cheaper the other way round
  cost[1] = {1.0, 3.0};
  auto third = assigner.assign_costs(1, ids, cost, 2);
  EXPECT_EQ(third[0], 1);
  EXPECT_EQ(third[1], 0);
}

}  // namespace
}  // namespace ssl::planner
