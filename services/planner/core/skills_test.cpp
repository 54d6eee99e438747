// The action nodes one by one, as pure functions: the intent each skill writes for a given situation. Their
// behaviour in the simulator (shots go in, passes are received, marks hold) is checked in
// tests/simulated/planner_referee_sim_test.cpp (the action nodes section).
#include "services/planner/core/skills.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "libs/geometry/angle.h"
#include "services/planner/core/planner_test_util.h"

namespace ssl::planner {
namespace {

using testing::robot_at;

constexpr double kDribbler = 0.09 + 0.0215;  // robot radius + ball radius (division B)

struct Scene {
  PlannerConfig config;
  std::vector<wm::RobotState> robots;
  std::vector<wm::RobotState> enemies;
  Situation s;

  explicit Scene(const Vec2& ball, const Vec2& ball_velocity = Vec2::Zero()) {
    s.config = &config;
    s.field = wm::Field(FieldGeometry::division_b());
    s.ball_known = true;
    s.ball = ball;
    s.ball_velocity = ball_velocity;
  }
  const Situation& situation() {
    s.robots = robots;
    s.enemies = enemies;
    return s;
  }
};

wm::RobotState enemy_at(const Vec2& position, std::uint32_t id, double heading = M_PI) {
  wm::RobotState robot = robot_at(position, heading, id);
  return robot;
}

TEST(Skills, EverySkillNamesItselfAndRunSkillDispatchesByParams) {
  Scene scene({0, 0});
  const wm::RobotState robot = robot_at({-1, 0});
  scene.robots = {robot};
  scene.enemies = {enemy_at({1, 1}, 3)};
  const std::vector<SkillCall> calls = {PassParams{},      ReceiveParams{},  GoToBallParams{},   GoToPointParams{},
                                        TurnWithBallParams{}, ClearParams{},  ShootParams{},      StopParams{},
                                        OpenSpaceParams{},  ManMarkParams{.opponent = 3}, BlockParams{.opponent = 3},
                                        DefendGoalParams{}, ChallengeParams{}, RedirectParams{}};
  for (const SkillCall& call : calls) {
    const MotionIntent intent = run_skill(scene.situation(), robot, call);
    EXPECT_TRUE(intent.active);
    EXPECT_EQ(intent.skill, skill_name(skill_of(call)));
  }
}

TEST(Skills, PassKicksAtTheSpeedThatArrivesAtTheReceiversSpeed) {
  Scene scene({0, 0});
  const PassParams params{.receiver = {3, 0}, .arrival_speed = 1.5, .ball_deceleration = 0.4, .rolling_fraction = 0.7};
  // Not behind the ball yet: approach, no kick.
  const wm::RobotState aside = robot_at({0, 1});
  EXPECT_EQ(pass(scene.situation(), aside, params).kick, KickType::kNone);
  // Behind it, facing the receiver: kick so that it rolls at v0 with v0^2 = 1.5^2 + 2 * 0.4 * 3.
  const wm::RobotState behind = robot_at({-kDribbler, 0}, 0);
  const MotionIntent kick = pass(scene.situation(), behind, params);
  EXPECT_EQ(kick.kick, KickType::kFlat);
  EXPECT_NEAR(kick.kick_speed, std::sqrt(1.5 * 1.5 + 2 * 0.4 * 3) / 0.7, 1e-9);
}

TEST(Skills, ReceiveStandsOnTheBallsLineFacingIt) {
  // The ball rolls along +x at 3 m/s; the receiver is 2 m ahead, 0.3 m off its line.
  Scene scene({0, 0}, {3, 0});
  const wm::RobotState robot = robot_at({2, 0.3}, M_PI);
  const MotionIntent intent = receive(scene.situation(), robot, {.point = {2, 0.3}});
  EXPECT_NEAR(intent.target.y(), 0.0, 1e-9) << "on the line";
  EXPECT_NEAR(intent.target.x(), 2 + kDribbler, 1e-9) << "the dribbler where the ball passes";
  EXPECT_NEAR(std::abs(intent.orientation), M_PI, 1e-9) << "facing the ball";
  EXPECT_TRUE(intent.dribble);
  // A ball that is not coming: wait at the point, facing the ball.
  Scene still({0, 0});
  const MotionIntent wait = receive(still.situation(), robot, {.point = {2, 0.3}});
  EXPECT_EQ(wait.target, Vec2(2, 0.3));
}

TEST(Skills, AReceiverBesideTheLineOfANearBallStepsOntoItAtFullSpeedAndGivesWayOnlyOnIt) {
  // The ball rolls along +x at 2 m/s, 0.3 m in front of the receiver.
  Scene scene({0, 0}, {2, 0});
  const MotionIntent beside = receive(scene.situation(), robot_at({0.3, 0.07}, M_PI), {.point = {1, 0}});
  EXPECT_NEAR(beside.target.x(), 0.3, 1e-9) << "straight across onto the line";
  EXPECT_NEAR(beside.target.y(), 0.0, 1e-9);
  EXPECT_EQ(beside.max_speed, scene.config.limits.max_speed) << "no speed cap while beside the line";
  const ReceiveParams params{.point = {1, 0}};
  const MotionIntent on = receive(scene.situation(), robot_at({0.3, 0.01}, M_PI), params);
  EXPECT_NEAR(on.target.y(), 0.0, 1e-9);
  EXPECT_NEAR(on.target.x(), 0.3 + params.cushion * 2 * 0.5, 1e-9) << "back along the line with the ball";
  EXPECT_NEAR(on.max_speed, params.cushion * 2, 1e-9);
}

TEST(Skills, GoToPointWithTheBallStopsShortOfTheDribblingLimit) {
  Scene scene({0, 0});
  const wm::RobotState robot = robot_at({-kDribbler, 0}, 0);
  const MotionIntent intent =
      go_to_point(scene.situation(), robot, {.point = {3, 0}, .orientation = 0.0, .with_ball = true,
                                              .dribble_start = Vec2(0, 0)});
  EXPECT_TRUE(intent.dribble);
  EXPECT_LE(intent.target.x() + kDribbler, rules::kMaxDribblingDistance) << "the ball stays within 1 m";
  EXPECT_LE(intent.max_speed, 1.0);
  // Without the ball it faces the ball.
  const MotionIntent free = go_to_point(scene.situation(), robot_at({-2, 0}), {.point = {-1, 1}});
  EXPECT_NEAR(free.orientation, geom::angle_of(Vec2(Vec2(0, 0) - Vec2(-1, 1))).radians(), 1e-9);
}

TEST(Skills, TurnWithBallHoldsThePlaceAndLimitsTheTurnRate) {
  Scene scene({0, 0});
  const wm::RobotState robot = robot_at({-kDribbler, 0}, 0);
  const MotionIntent intent = turn_with_ball(scene.situation(), robot, {.orientation = 2.0, .max_angular_speed = 2.5});
  EXPECT_EQ(intent.target, robot.position);
  EXPECT_DOUBLE_EQ(intent.orientation, 2.0);
  EXPECT_DOUBLE_EQ(intent.max_angular_speed, 2.5);
  EXPECT_TRUE(intent.dribble);
}

TEST(Skills, ShootAimsInsideThePostOfTheWidestOpenPartOfTheGoal) {
  // Division B goal: 1 m wide at x = 4.5. From a ball at (2.5, 0) an opponent at (3.5, 0.25) hides the goal
  // from y = +0.28 to the +y post: the open part is y in [-0.457, +0.28] (a ball's width off the post). It
  // lies against the -y post: the shot goes 0.06 m inside that edge, y = -0.394, furthest from the opponent.
  Scene scene({2.5, 0});
  scene.enemies = {enemy_at({3.5, 0.25}, 1)};
  const Vec2 target = shot_target(scene.situation());
  EXPECT_NEAR(target.x(), 4.5, 1e-9);
  EXPECT_NEAR(target.y(), -0.394, 0.001);
  // A gap between two opponents (both posts hidden): its middle, y = -0.088 by angle between them.
  Scene between({2.5, 0});
  between.enemies = {enemy_at({3.5, 0.25}, 1), enemy_at({4.45, -0.45}, 2)};
  const Vec2 middle = shot_target(between.situation());
  EXPECT_GT(middle.y(), -0.35);
  EXPECT_LT(middle.y(), 0.2);
  // An empty goal: the middle.
  Scene empty({2.5, 0});
  EXPECT_NEAR(shot_target(empty.situation()).y(), 0.0, 1e-9);
}

TEST(Skills, OfTwoGapsAboutAsWideTheShooterKeepsToTheOneItFaces) {
  // Their keeper in the middle of the mouth leaves two gaps about as wide: the shooter (id 1, behind the ball)
  // aims beside the post on the side it faces, so that its aim does not flip with the keeper's jitter.
  const Vec2 ball(2.5, 0);
  for (const double facing : {0.1, -0.1}) {
    Scene scene(ball);
    scene.robots = {robot_at({2.39, 0}, facing, 1)};
    scene.enemies = {enemy_at({4.4, 0.01}, 0)};
    const Vec2 target = shot_target(scene.situation(), 1);
    EXPECT_GT(target.y() * facing, 0.3 * std::abs(facing)) << "facing " << facing;
    EXPECT_GT(std::abs(target.y()), 0.3);
  }
  // A gap clearly the wider is taken whichever way the shooter faces.
  Scene wide(ball);
  wide.robots = {robot_at({2.39, 0}, 0.1, 1)};
  wide.enemies = {enemy_at({4.4, 0.2}, 0)};
  EXPECT_LT(shot_target(wide.situation(), 1).y(), -0.3);
}

TEST(Skills, ShootBeyondItsMaxDistanceGetsBehindTheBallWithoutKicking) {
  // Division B: their goal centre at (4.5, 0). The ball 3 m from it, the shooter behind it facing the goal.
  const Vec2 ball(1.5, 0);
  Scene scene(ball);
  const wm::RobotState shooter = robot_at({ball.x() - kDribbler - 0.05, 0.0}, 0.0, 1);
  scene.robots = {shooter};
  const MotionIntent beyond = run_skill(scene.situation(), shooter, ShootParams{.max_distance = 2.9});
  EXPECT_EQ(beyond.kick, KickType::kNone);
  EXPECT_LT(beyond.target.x(), ball.x());
  const MotionIntent within = run_skill(scene.situation(), shooter, ShootParams{.max_distance = 3.0});
  EXPECT_EQ(within.kick, KickType::kFlat);
}

TEST(Skills, TheLastPartOfAnApproachToABallRollingAwayClosesOnItAtItsSpeedAndMovesWithIt) {
  // The ball rolls away from the shooter behind it at 1.5 m/s: the kick's approach closes at 1 m/s on top of
  // that, moving with the ball; at rest it is 1 m/s. Within 0.4 m of their defense area (x = 3.5) it does not
  // move with the ball (which would steer past the path search's keep-out), nor does our restart's kicker.
  for (const double speed : {1.5, 0.0}) {
    const Vec2 ball(0.0, 0.0);
    Scene scene(ball, {speed, 0.0});
    const wm::RobotState shooter = robot_at({ball.x() - kDribbler - 0.03, 0.0}, 0.0, 1);
    scene.robots = {shooter};
    const MotionIntent intent = run_skill(scene.situation(), shooter, ShootParams{});
    EXPECT_EQ(intent.kick, KickType::kFlat);
    EXPECT_NEAR(intent.max_speed, 1.0 + speed, 1e-9);
    EXPECT_NEAR(intent.target_velocity.x(), speed, 1e-9);
  }
  // Our restart's kicker (which may not touch the ball again) lets a ball its push set rolling go: slower.
  Scene restart({0.0, 0.0}, {1.5, 0.0});
  const wm::RobotState kicker = robot_at({-kDribbler - 0.03, 0.0}, 0.0, 1);
  restart.robots = {kicker};
  restart.s.restart_kicker = 1;
  const MotionIntent pushed = run_skill(restart.situation(), kicker, ShootParams{});
  EXPECT_NEAR(pushed.max_speed, 0.75, 1e-9);
  EXPECT_EQ(pushed.target_velocity, Vec2::Zero());
  const Vec2 near_area(3.2, 0.0);
  Scene scene(near_area, {1.5, 0.0});
  const wm::RobotState shooter = robot_at({near_area.x() - kDribbler - 0.03, 0.0}, 0.0, 1);
  scene.robots = {shooter};
  const MotionIntent intent = run_skill(scene.situation(), shooter, ShootParams{});
  EXPECT_NEAR(intent.max_speed, 2.5, 1e-9);
  EXPECT_EQ(intent.target_velocity, Vec2::Zero());
}

TEST(Skills, OnTheEdgeOfADefenseAreaTheLastPartOfAnApproachClosesAtHalfTheSpeed) {
  // Division B: the defense areas' fronts at x = +-3.5. A ball lying within 0.15 m of either is closed on at
  // 0.5 m/s (faster, the robot stops a few cm beyond its target, partly inside their area while touching the
  // ball); 0.2 m out, at the usual 1 m/s.
  for (const double side : {1.0, -1.0}) {
    for (const auto& [x, closing] : {std::pair{3.4, 0.5}, std::pair{3.3, 1.0}}) {
      const Vec2 ball(side * x, 0.0);
      Scene scene(ball);
      const wm::RobotState shooter = robot_at({ball.x() - kDribbler - 0.03, 0.0}, 0.0, 1);
      scene.robots = {shooter};
      const MotionIntent intent = run_skill(scene.situation(), shooter, ShootParams{});
      EXPECT_EQ(intent.kick, KickType::kFlat) << ball.x();
      EXPECT_NEAR(intent.max_speed, closing, 1e-9) << ball.x();
    }
  }
}

TEST(Skills, GoToBallMovesWithABallRollingAwayButNotNearADefenseArea) {
  // The robot 0.5 m behind the ball: a ball rolling away at 1.2 m/s is arrived at with its velocity (planned
  // to rest at where it lies, the robot trails it and never reaches it); a ball lying still or rolling
  // towards the robot is not, nor one within 0.4 m of their defense area (x = 3.5).
  struct Case {
    Vec2 ball;
    Vec2 velocity;
    Vec2 expected;
  };
  for (const Case& c : {Case{{0.0, 0.0}, {1.2, 0.0}, {1.2, 0.0}}, Case{{0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}},
                        Case{{0.0, 0.0}, {-1.2, 0.0}, {0.0, 0.0}}, Case{{3.2, 0.0}, {1.2, 0.0}, {0.0, 0.0}}}) {
    Scene scene(c.ball, c.velocity);
    const wm::RobotState robot = robot_at(c.ball - Vec2(0.5, 0.0), 0.0, 1);
    scene.robots = {robot};
    const MotionIntent intent = go_to_ball(scene.situation(), robot, {});
    EXPECT_TRUE(intent.dribble);
    EXPECT_NEAR((intent.target_velocity - c.expected).norm(), 0.0, 1e-9)
        << "ball at " << c.ball.x() << " rolling " << c.velocity.x();
  }
}

TEST(Skills, AShotAtABallOnTheEdgeOfTheirDefenseAreaStopsWhollyOutsideIt) {
  // Division B: their defense area begins at x = 3.5. The ball lies 2 cm before it, the shooter behind it
  // facing their goal; the kick drives through the ball but stops before any part of the robot (with the
  // touch clearance) would stand in the area, and not beyond the ball's contact point.
  const Vec2 ball(3.48, 0.0);
  Scene scene(ball);
  const wm::RobotState shooter = robot_at({ball.x() - kDribbler, 0.0}, 0.0, 1);
  scene.robots = {shooter};
  const MotionIntent intent = run_skill(scene.situation(), shooter, ShootParams{});
  EXPECT_EQ(intent.kick, KickType::kFlat);
  EXPECT_FALSE(intent.avoid_their_defense_area);
  EXPECT_LT(intent.target.x() + scene.config.robot_radius, 3.5);
  EXPECT_GE(intent.target.x(), ball.x() - kDribbler - 1e-9);
  EXPECT_NEAR(intent.target.y(), 0.0, 1e-9);
}

TEST(Skills, RedirectPutsItsKickerOnThePointFacingTheAimTurnedAtMostMaxAngleFromTheBall) {
  // The ball lies at (0, 0), the pass will come to (0, 2): the way back to the ball is -90 degrees.
  Scene scene({0.0, 0.0});
  const wm::RobotState robot = robot_at({0.5, 2.5}, 0.0, 2);
  scene.robots = {robot};
  const Vec2 point(0.0, 2.0);
  // An aim 45 degrees off that way (within max_angle, 0.9 rad): faced exactly, kicker armed, on the point.
  MotionIntent intent = redirect(scene.situation(), robot, {.point = point, .aim = {2.0, 0.0}});
  EXPECT_EQ(intent.skill, "redirect");
  EXPECT_EQ(intent.kick, KickType::kFlat);
  EXPECT_NEAR(intent.kick_speed, rules::kMaxBallSpeed - 0.5, 1e-9);
  EXPECT_FALSE(intent.dribble);
  EXPECT_NEAR(intent.orientation, -M_PI / 4, 1e-9);
  const Vec2 facing(std::cos(intent.orientation), std::sin(intent.orientation));
  EXPECT_NEAR((intent.target + facing * kDribbler - point).norm(), 0.0, 1e-9);
  // Their goal centre, 66 degrees off: turned only max_angle from the ball (the ball must meet the front).
  intent = redirect(scene.situation(), robot, {.point = point, .aim = {4.5, 0.0}});
  EXPECT_NEAR(intent.orientation, -M_PI / 2 + 0.9, 1e-9);
  // The ball rolling past the point's side: met where its line passes the point, not at the point.
  Scene rolling({0.0, 1.0}, {0.0, 2.0});
  rolling.robots = {robot};
  const Vec2 off_line(0.1, 2.0);
  intent = redirect(rolling.situation(), robot, {.point = off_line, .aim = {2.0, 0.0}});
  const Vec2 heading(std::cos(intent.orientation), std::sin(intent.orientation));
  EXPECT_NEAR((intent.target + heading * kDribbler - point).norm(), 0.0, 1e-9);
}

TEST(Skills, ClearKicksAwayFromOurGoalWhereNoOpponentIs) {
  Scene scene({-3, 0});
  scene.enemies = {enemy_at({-2, 0}, 1), enemy_at({-2, 0.3}, 2)};
  const wm::RobotState robot = robot_at({-3.5, 0}, 0);
  const MotionIntent intent = clear_ball(scene.situation(), robot, {});
  const Vec2 direction = geom::Angle::from_radians(intent.orientation).to_unit_vector();
  EXPECT_GT(direction.x(), 0.3) << "upfield";
  EXPECT_LT(direction.y(), -0.3) << "away from the two opponents ahead and to the left";
}

TEST(Skills, AKickAtTheSpeedToRestAfterADistanceRestsThere) {
  // The straight-ball model stepped at 1 ms: slide at 3 m/s^2 to 0.7 of the kick speed, then roll at 0.35.
  for (const double distance : {1.0, 4.0, 9.0}) {
    double v = kick_speed_to_rest_after(distance);
    const double switch_speed = 0.7 * v;
    double travelled = 0;
    while (v > 0) {
      travelled += v * 1e-3;
      v -= (v > switch_speed ? 3.0 : 0.35) * 1e-3;
    }
    EXPECT_NEAR(travelled, distance, 0.02 * distance) << distance;
  }
  EXPECT_EQ(kick_speed_to_rest_after(-1.0), 0.0);
}

TEST(Skills, AClearComesToRestInsideTheField) {
  // Ball 0.4 m off our left touch line (division B: 9 x 6), opponents straight upfield and to the right: the
  // widest room is towards the line, but the ball must not cross it.
  Scene scene({-3, 2.6});
  scene.enemies = {enemy_at({-1.5, 2.6}, 1), enemy_at({-2, 1.5}, 2)};
  wm::RobotState robot = robot_at({-3.5, 2.6}, 0);
  MotionIntent intent = clear_ball(scene.situation(), robot, {});
  const Vec2 u = geom::Angle::from_radians(intent.orientation).to_unit_vector();
  const double room = scene.s.field.distance_inside(scene.s.ball, u);
  EXPECT_GE(room, 3.0) << "a direction with at least 3 m of field before a line";
  // Behind the ball facing that way: the kick's speed rests the ball 1 m inside the field.
  robot = robot_at(scene.s.ball - u * (kDribbler + 0.005), intent.orientation, 0);
  intent = clear_ball(scene.situation(), robot, {});
  ASSERT_EQ(intent.kick, KickType::kFlat);
  EXPECT_NEAR(intent.kick_speed, kick_speed_to_rest_after(room - 1.0), 1e-9);
  EXPECT_LT(intent.kick_speed, ClearParams{}.speed);
}

TEST(Skills, AClearWithRoomEveryWayGoesTheWayTheRobotFaces) {
  // Division B, the ball in front of our defense area, no opponent within 3 m: every direction has the same
  // room. The clear goes the way the robot faces, wherever it stands round the ball: getting behind the ball
  // turns it that way, so the choice holds while its bearing to the ball drifts. It used to take the first
  // direction, 0.8 rad to the right, whichever way the robot came.
  for (const double facing : {0.3, -0.5}) {
    for (const double bearing : {0.0, 0.6}) {
      Scene scene({-3.0, 0.0});
      scene.enemies = {enemy_at({1.5, 0.0}, 1)};
      const Vec2 from(std::cos(bearing), std::sin(bearing));
      const wm::RobotState robot = robot_at(scene.s.ball - from * 0.5, facing, 0);
      const MotionIntent intent = clear_ball(scene.situation(), robot, {});
      EXPECT_NEAR(intent.orientation, facing, 0.05 + 1e-9) << "facing " << facing << ", bearing " << bearing;
    }
  }
}

TEST(Skills, AClearOfABallOnOurGoalLineBesideAPostGoesAlongTheLineAwayFromTheGoal) {
  // Division B (posts at y = +-0.5): the ball 6 cm inside our goal line, 1 cm beyond a post's line, the
  // keeper inside the goal mouth facing it. No kicking spot behind the ball within 0.8 rad of upfield lies on
  // the field, so the clear goes along the line, away from the goal (not across the mouth), from inside the
  // mouth where the robot kicking clears the post.
  Scene scene({-4.44, -0.51});
  const wm::RobotState keeper = robot_at({-4.4, -0.2}, -M_PI / 2, 0);
  const MotionIntent intent = clear_ball(scene.situation(), keeper, {});
  EXPECT_GT(intent.orientation, -M_PI / 2) << "not back towards the goal line";
  EXPECT_LT(intent.orientation, -1.2) << "along the line";
  const Vec2 u = geom::Angle::from_radians(intent.orientation).to_unit_vector();
  EXPECT_GE(scene.s.field.distance_to_our_goal_walls(scene.s.ball - u * kDribbler), 0.09);
}

TEST(Skills, ABallJustBeyondAPostOnOurGoalLineIsTakenFromTheFieldSideAndPulledOnceTouched) {
  // Division B: the ball 1 cm inside our goal line, 7 cm beyond a post: along the line the post stands where
  // the robot would kick, and no spot behind it upfield lies on the field. The robot comes round to the field
  // side facing the goal line; 3 cm short of the ball (within holds_ball's reach) it still closes in, into
  // the ball; touching it, it pulls the ball out upfield, slowly.
  Scene scene({-4.49, -0.57});
  MotionIntent intent = clear_ball(scene.situation(), robot_at({-4.0, -0.3}, 0.0, 0), {});
  EXPECT_GT(intent.target.x(), scene.s.ball.x() + kDribbler + 0.1) << "round to the field side first";
  EXPECT_NEAR(std::abs(intent.orientation), M_PI, 1e-9);
  EXPECT_TRUE(intent.dribble);
  const wm::RobotState short_of_it = robot_at(scene.s.ball + Vec2(kDribbler + 0.03, 0), M_PI, 0);
  intent = clear_ball(scene.situation(), short_of_it, {});
  EXPECT_LT(intent.target.x(), scene.s.ball.x() + kDribbler) << "closing in, into the ball";
  EXPECT_EQ(intent.kick, KickType::kNone);
  const wm::RobotState touching = robot_at(scene.s.ball + Vec2(kDribbler + 0.005, 0), M_PI, 0);
  intent = clear_ball(scene.situation(), touching, {});
  EXPECT_GT(intent.target.x(), touching.position.x() + 0.3) << "pulled out upfield";
  EXPECT_LE(intent.max_speed, 0.5);
  EXPECT_TRUE(intent.dribble);
}

TEST(Skills, ALongShotComesToRestBeforeTheirGoalLine) {
  // 8 m from their goal centre (beyond kShotRange): the shot is a long ball.
  Scene far({-3.5, 0});
  wm::RobotState robot = robot_at({-3.5 - kDribbler - 0.005, 0}, 0.0, 0);
  MotionIntent intent = shoot(far.situation(), robot, {});
  ASSERT_EQ(intent.kick, KickType::kFlat);
  EXPECT_NEAR(intent.kick_speed, kick_speed_to_rest_after(8.0 - 1.0), 0.05);
  // 3 m out: a shot at the configured speed.
  Scene near({1.5, 0});
  robot = robot_at({1.5 - kDribbler - 0.005, 0}, 0.0, 0);
  intent = shoot(near.situation(), robot, {});
  ASSERT_EQ(intent.kick, KickType::kFlat);
  EXPECT_NEAR(intent.kick_speed, std::min(near.config.kick_speed, rules::kMaxBallSpeed - 0.3), 1e-9);
}

TEST(Skills, StopHalts) {
  Scene scene({0, 0});
  EXPECT_TRUE(stop(scene.situation(), robot_at({1, 1}), {}).halt);
}

TEST(Skills, OpenSpaceMovesAwayFromACrowdedAnchor) {
  Scene scene({0, 0});
  scene.enemies = {enemy_at({2, 1}, 1), enemy_at({2.2, 0.8}, 2)};
  const MotionIntent intent = open_space(scene.situation(), robot_at({0, 2}), {.anchor = {2, 1}, .radius = 1.0});
  double nearest = 1e9;
  for (const wm::RobotState& enemy : scene.enemies) nearest = std::min(nearest, (enemy.position - intent.target).norm());
  EXPECT_GT(nearest, 0.6);
  EXPECT_LE((intent.target - Vec2(2, 1)).norm(), 1.0 + 1e-9);
  EXPECT_TRUE(intent.keep_off_ball) << "a robot opening space has no business at the ball";
}

TEST(Skills, ManMarkStandsGoalSideOfItsOpponent) {
  Scene scene({0, 0});
  scene.enemies = {enemy_at({-1, 1}, 4)};
  const MotionIntent intent = man_mark(scene.situation(), robot_at({0, 2}), {.opponent = 4, .distance = 0.35});
  EXPECT_NEAR((intent.target - Vec2(-1, 1)).norm(), 0.35, 1e-9);
  const Vec2 goal = scene.situation().field.our_goal_center();
  EXPECT_LT((intent.target - goal).norm(), (Vec2(-1, 1) - goal).norm()) << "between it and our goal";
}

TEST(Skills, BlockStandsInTheMouthThenOnTheLineOfSight) {
  Scene scene({-1.9, 0});
  // Facing our goal (heading pi): in front of its kicker.
  scene.enemies = {enemy_at({-1.8, 0}, 2, M_PI)};
  const MotionIntent mouth = block(scene.situation(), robot_at({-3, 1}), {.opponent = 2, .distance = 0.3});
  EXPECT_NEAR(mouth.target.x(), -2.1, 1e-9);
  EXPECT_NEAR(mouth.target.y(), 0.0, 1e-9);
  // Turned away (heading +y): between it and our goal instead.
  scene.enemies = {enemy_at({-1.8, 0}, 2, M_PI / 2)};
  const MotionIntent sight = block(scene.situation(), robot_at({-3, 1}), {.opponent = 2, .distance = 0.3});
  EXPECT_NEAR(sight.target.y(), 0.0, 1e-9);
  EXPECT_LT(sight.target.x(), -1.8);
}

TEST(Skills, DefendGoalStandsOnTheBisectorOfThePosts) {
  // Ball straight in front of the goal: the keeper at the centre; off to the side: towards the ball's side,
  // on the bisector of the posts' directions.
  Scene centre({-2, 0});
  EXPECT_NEAR(defend_goal(centre.situation(), robot_at({-4.4, 0}), {}).target.y(), 0.0, 1e-9);
  Scene side({-3.5, 1.5});
  const MotionIntent intent = defend_goal(side.situation(), robot_at({-4.4, 0}), {});
  const Vec2 ball(-3.5, 1.5);
  const Vec2 left = (Vec2(-4.5, 0.5) - ball).normalized();
  const Vec2 right = (Vec2(-4.5, -0.5) - ball).normalized();
  const Vec2 to_keeper = (intent.target - ball).normalized();
  EXPECT_NEAR(std::acos(to_keeper.dot(left)), std::acos(to_keeper.dot(right)), 1e-6) << "equal angles to both posts";
  EXPECT_FALSE(intent.avoid_our_defense_area);
}

TEST(Skills, DefendGoalGuardsAWideBallFromNearTheGoalLine) {
  // Ball near the corner (goal line x = -4.5): the keeper on the bisector close to the line, so that a ball
  // played along the line meets it; a ball straight ahead keeps it 0.14 m out, in front of the mouth.
  Scene wide({-4.3, -2.8});
  const MotionIntent corner = defend_goal(wide.situation(), robot_at({-4.36, 0}), {});
  EXPECT_LT(corner.target.x(), -4.5 + 0.05);
  EXPECT_LT(corner.target.y(), 0.0) << "the ball's side";
  Scene ahead({-2, 0});
  EXPECT_NEAR(defend_goal(ahead.situation(), robot_at({-4.36, 0}), {}).target.x(), -4.5 + 0.14, 1e-9);
}

TEST(Skills, DefendGoalMeetsABallRollingAlongTheGoalLine) {
  // 0.05 m in front of the line, rolling at 3.5 m/s along it into the mouth (crossing at y = -0.23): it
  // passes behind a keeper 0.14 m out. The keeper steps onto its path.
  const Vec2 ball(-4.45, -1.4);
  const Vec2 velocity(-0.15, 3.5);
  Scene along(ball, velocity);
  const MotionIntent intent = defend_goal(along.situation(), robot_at({-4.36, -0.1}), {});
  EXPECT_LT(std::abs(geom::cross(velocity.normalized(), Vec2(intent.target - ball))), 0.025) << "on the path (kept 2 cm off the line)";
  EXPECT_GT(intent.target.y(), -0.5);
  EXPECT_LT(intent.target.x(), -4.45);
  Scene wide_of_goal({-4.45, -1.4}, {-0.3, 3.5});  // crosses the goal line before the mouth: no shot
  EXPECT_GT(defend_goal(wide_of_goal.situation(), robot_at({-4.36, -0.1}), {}).target.y(), -0.45);
}

TEST(Skills, AnOverriddenRobotRunsItsSkillInsteadOfTheTree) {
  const testing::Side side{};
  testing::Script script(side);
  script.default_teams();
  script.command(wm::RefereeCommand::kForceStart);
  Planner planner(testing::config_for(side));
  planner.override_skill(5, SkillOverride{StopParams{}});
  (void)planner.step(script.inputs(), testing::at_tick(0));
  ASSERT_NE(planner.last_intent(5), nullptr);
  EXPECT_EQ(planner.last_intent(5)->skill, skill_name(Skill::kStop));
  EXPECT_TRUE(planner.last_intent(5)->halt);
  planner.override_skill(5, std::nullopt);
  (void)planner.step(script.inputs(), testing::at_tick(1));
  EXPECT_NE(planner.last_intent(5)->skill, skill_name(Skill::kStop)) << "back to the tree";
}

}  // namespace
}  // namespace ssl::planner
