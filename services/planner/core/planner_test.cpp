#include "services/planner/core/planner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "services/planner/core/motion.h"
#include "services/planner/core/planner_test_util.h"
#include "services/planner/core/skills.h"

namespace ssl::planner {
namespace {

using testing::Restart;
using testing::Script;
using testing::Side;
using wm::RefereeCommand;

constexpr double kR = testing::kRadius;
constexpr double kBallKeepAway = 0.5 + kR;     // rule distance, robot centre
constexpr double kDefenseKeepAway = 0.2 + kR;  // rule distance, robot centre
constexpr double kStopSpeed = 1.5;

class PlannerRefereeTest : public ::testing::TestWithParam<Side> {
 protected:
  PlannerRefereeTest() : script_(GetParam()), planner_(testing::config_for(GetParam())) {
    script_.default_teams();
  }

  PlannerOutput tick() { return planner_.step(script_.inputs(), testing::at_tick(tick_++)); }
  PlannerOutput ticks(int n) {
    PlannerOutput out;
    for (int i = 0; i < n; ++i) out = tick();
    return out;
  }
  const MotionIntent& intent(std::uint32_t id) {
    const MotionIntent* i = planner_.last_intent(id);
    EXPECT_NE(i, nullptr) << "robot " << id;
    static const MotionIntent kNone;
    return i ? *i : kNone;
  }
  const RoleInfo* role(const PlannerOutput& out, std::uint32_t id) {
    for (const RoleInfo& r : out.roles) {
      if (r.robot_id == id) return &r;
    }
    return nullptr;
  }
  std::optional<std::uint32_t> robot_with_role(const PlannerOutput& out, const std::string& name) {
    for (const RoleInfo& r : out.roles) {
      if (r.role == name) return r.robot_id;
    }
    return std::nullopt;
  }
  wm::Field field() const { return script_.field(); }

  /// STOP-like properties of one tick: speeds, robots inside the circle leaving it, legal targets.
  void expect_stop_properties(const PlannerOutput& out, bool check_defense_area = true) {
    const Vec2 ball = script_.ball();
    for (const RobotCommand& c : out.commands) {
      const wm::RobotState* r = script_.robot(c.id);
      ASSERT_NE(r, nullptr);
      EXPECT_LE(testing::speed(c), kStopSpeed) << "robot " << c.id;
      EXPECT_EQ(c.kick, KickType::kNone);
      if ((r->position - ball).norm() < kBallKeepAway) {
        EXPECT_GT(testing::team_velocity(c, r->orientation).dot(r->position - ball), 0.0)
            << "robot " << c.id << " inside the 0.5 m circle must move away from the ball";
      }
      const MotionIntent& i = intent(c.id);
      EXPECT_LE(i.max_speed, kStopSpeed);
      EXPECT_GE((i.target - ball).norm(), kBallKeepAway) << "robot " << c.id;
      if (check_defense_area) {
        EXPECT_GE(testing::distance_to_their_defense_area(field(), i.target), kDefenseKeepAway)
            << "robot " << c.id;
      }
    }
  }

  Script script_;
  Planner planner_;
  int tick_ = 0;
};

TEST_P(PlannerRefereeTest, TheWanderStrategyToursWaypointsAndYieldsToTheReferee) {
  PlannerConfig config = testing::config_for(GetParam());
  config.strategy = Strategy::kWander;
  Planner planner(config);
  script_.command(RefereeCommand::kForceStart);
  PlannerOutput out = planner.step(script_.inputs(), testing::at_tick(0));
  EXPECT_EQ(out.play, "wander");
  const wm::Field field = script_.field();
  for (const RobotCommand& c : out.commands) {
    const MotionIntent* intent = planner.last_intent(c.id);
    ASSERT_NE(intent, nullptr);
    EXPECT_EQ(intent->role, "wanderer");
    EXPECT_LT(std::abs(intent->target.x()), field.size().field_length / 2 - field.size().penalty_area_depth);
    EXPECT_LT(std::abs(intent->target.y()), field.size().field_width / 2);
  }
  // A robot on its waypoint gets the next one.
  const std::uint32_t id = out.commands.front().id;
  const Vec2 first = planner.last_intent(id)->target;
  script_.robot(id)->position = first;
  planner.step(script_.inputs(), testing::at_tick(1));
  EXPECT_GT((planner.last_intent(id)->target - first).norm(), 0.1);
  // The referee override stays above the strategy.
  script_.command(RefereeCommand::kStop);
  EXPECT_EQ(planner.step(script_.inputs(), testing::at_tick(2)).play, "stop");
}

TEST_P(PlannerRefereeTest, TheBallChaserSendsTheNearestToShootAndEveryOtherFieldPlayerToTheBall) {
  PlannerConfig config = testing::config_for(GetParam());
  config.strategy = Strategy::kBallChaser;
  Planner planner(config);
  script_.command(RefereeCommand::kForceStart);
  const PlannerOutput out = planner.step(script_.inputs(), testing::at_tick(0));
  EXPECT_EQ(out.play, "ball_chaser");
  const Vec2 ball = script_.ball();
  std::optional<std::uint32_t> nearest;
  for (const RobotCommand& c : out.commands) {
    if (c.id == testing::kOurKeeper) continue;
    if (!nearest || (script_.robot(c.id)->position - ball).norm() < (script_.robot(*nearest)->position - ball).norm()) {
      nearest = c.id;
    }
  }
  ASSERT_TRUE(nearest);
  int chasers = 0;
  for (const RobotCommand& c : out.commands) {
    const MotionIntent* intent = planner.last_intent(c.id);
    ASSERT_NE(intent, nullptr) << "robot " << c.id;
    if (c.id == testing::kOurKeeper) {
      EXPECT_EQ(intent->role, "goalkeeper");
    } else if (c.id == *nearest) {
      EXPECT_EQ(intent->role, "attacker");
      EXPECT_EQ(intent->skill, "shoot");
    } else {
      EXPECT_EQ(intent->role, "chaser");
      EXPECT_LT((intent->target - ball).norm(), 0.5) << "robot " << c.id << " does not go for the ball";
      ++chasers;
    }
  }
  EXPECT_EQ(chasers, static_cast<int>(out.commands.size()) - 2);
  script_.command(RefereeCommand::kStop);
  EXPECT_EQ(planner.step(script_.inputs(), testing::at_tick(1)).play, "stop");
}

TEST_P(PlannerRefereeTest, TheBaseStrategyReportsTheCoachsModeAndStyleAndTheOverrideNone) {
  script_.command(RefereeCommand::kForceStart);
  const PlannerOutput play = tick();
  EXPECT_EQ(play.play, "base_strategy");
  const std::size_t slash = play.game_tactic.find('/');
  ASSERT_NE(slash, std::string::npos) << play.game_tactic;
  const std::string mode = play.game_tactic.substr(0, slash);
  EXPECT_TRUE(mode == "attacking" || mode == "defending" || mode == "contesting") << play.game_tactic;
  script_.command(RefereeCommand::kStop);
  EXPECT_EQ(tick().game_tactic, "");
}

TEST_P(PlannerRefereeTest, AReconfiguredSpeedLimitHoldsFromTheNextTick) {
  script_.command(RefereeCommand::kForceStart);
  double fastest = 0;
  for (int i = 0; i < 100; ++i) {
    for (const RobotCommand& c : tick().commands) fastest = std::max(fastest, std::hypot(c.forward, c.left));
  }
  ASSERT_GT(fastest, 1.0) << "robots must go faster than the new limit before it";
  PlannerConfig slower = testing::config_for(GetParam());
  slower.limits.max_speed = 0.8;
  planner_.reconfigure(slower);
  for (int i = 0; i < 100; ++i) {
    for (const RobotCommand& c : tick().commands) {
      EXPECT_LE(std::hypot(c.forward, c.left), 0.8 + 1e-9) << "robot " << c.id << " at tick " << i;
    }
  }
}

TEST_P(PlannerRefereeTest, HaltStopsEveryRobot) {
  for (auto& r : script_.friends()) r.velocity = Vec2(1.0, 0.5);
  script_.command(RefereeCommand::kForceStart);
  ticks(30);  // moving
  script_.command(RefereeCommand::kHalt);
  const PlannerOutput out = tick();
  EXPECT_EQ(out.play, "halt");
  ASSERT_EQ(out.commands.size(), 11u);
  for (const RobotCommand& c : out.commands) {
    EXPECT_EQ(c.forward, 0.0);
    EXPECT_EQ(c.left, 0.0);
    EXPECT_EQ(c.angular, 0.0);
    EXPECT_EQ(c.kick, KickType::kNone);
    EXPECT_EQ(c.dribbler_rpm, 0.0);
  }
}

TEST_P(PlannerRefereeTest, StopLimitsSpeedAndClearsTheBall) {
  script_.set_ball({1.0, 0.5});
  script_.robot(5)->position = {0.8, 0.5};   // 0.2 m from the ball
  script_.robot(6)->position = {1.0, 0.85};  // 0.35 m
  script_.robot(7)->position = {1.3, 0.2};   // 0.42 m
  script_.robot(8)->velocity = Vec2(3.0, 0);
  script_.command(RefereeCommand::kStop);
  for (int i = 0; i < 40; ++i) {
    const PlannerOutput out = tick();
    EXPECT_EQ(out.play, "stop");
    expect_stop_properties(out);
  }
}

TEST_P(PlannerRefereeTest, InStopARobotEscapingTheBallsCircleDoesNotDriveIntoATeammateOnItsEdge) {
  // Robot 5 inside the circle, robot 6 just outside it straight out from the ball, 2 radii + 3 cm apart:
  // the rule layer's escape (straight out) would drive 5 into 6; the contact guard holds it.
  script_.set_ball({1.0, 0.5});
  script_.robot(5)->position = {1.45, 0.5};
  script_.robot(6)->position = {1.66, 0.5};
  script_.command(RefereeCommand::kStop);
  for (int i = 0; i < 20; ++i) {
    const PlannerOutput out = tick();
    for (const RobotCommand& c : out.commands) {
      if (c.id != 5) continue;
      const Vec2 velocity = testing::team_velocity(c, script_.robot(5)->orientation);
      EXPECT_LE(velocity.x(), 1e-9) << "towards robot 6 at tick " << i;
    }
  }
}

TEST_P(PlannerRefereeTest, StopTargetsKeepClearOfTheirDefenseArea) {
  const wm::Field f = field();
  script_.set_ball({f.half_length() - f.size().penalty_area_depth - 0.3, 0.4});  // ball just outside it
  script_.command(RefereeCommand::kStop);
  expect_stop_properties(ticks(3));
}

TEST_P(PlannerRefereeTest, ACardSendsOneRobotOffToTheSubstitutionAreaAndThePlaysUseTheRest) {
  script_.command(RefereeCommand::kForceStart);
  script_.max_allowed_bots(10);  // 11 on the field
  PlannerOutput out = ticks(3);
  std::vector<std::uint32_t> substitutes;
  for (const RoleInfo& r : out.roles) {
    if (r.role == "substitute") substitutes.push_back(r.robot_id);
  }
  ASSERT_EQ(substitutes, std::vector<std::uint32_t>{3}) << "(-2, 2.5): nearest to its spot";
  const RoleInfo* leaving = role(out, 3);
  EXPECT_LT(leaving->target.x(), 0.0);
  EXPECT_GT(leaving->target.x(), -1.0);
  EXPECT_GT(leaving->target.y(), field().half_width() + kR) << "wholly beyond the touch line";
  EXPECT_EQ(out.commands.size(), 11u) << "the leaving robot is still commanded";
  EXPECT_NE(robot_with_role(out, "goalkeeper"), std::nullopt);

  script_.command(RefereeCommand::kHalt);
  out = tick();
  for (const RobotCommand& c : out.commands) EXPECT_EQ(testing::speed(c), 0.0) << "robot " << c.id;

  script_.command(RefereeCommand::kForceStart);
  script_.max_allowed_bots(11);  // the card expired
  out = ticks(2);
  EXPECT_EQ(robot_with_role(out, "substitute"), std::nullopt);
}

TEST_P(PlannerRefereeTest, OurKickoffPositionsAndKickerStaysOffTheBall) {
  script_.command(script_.ours(Restart::kKickoff));
  const PlannerOutput out = ticks(5);
  EXPECT_EQ(out.play, "our_kickoff");
  const auto kicker = robot_with_role(out, "kicker");
  ASSERT_TRUE(kicker);
  for (const RoleInfo& r : out.roles) {
    if (r.robot_id == *kicker) {
      EXPECT_LT(r.target.norm(), 0.5);                 // in the centre circle, approaching
      EXPECT_GT(r.target.norm(), kR + 0.0215 + 0.02);  // not touching the ball
      EXPECT_LT(r.target.x(), 0.0);                    // from our side
      continue;
    }
    EXPECT_LE(r.target.x(), -kR) << "robot " << r.robot_id;
    EXPECT_GE(r.target.norm(), 0.5 + kR) << "robot " << r.robot_id;
  }
  for (const RobotCommand& c : out.commands) EXPECT_EQ(c.kick, KickType::kNone);
}

TEST_P(PlannerRefereeTest, OurKickoffKickerKicksAfterNormalStart) {
  script_.command(script_.ours(Restart::kKickoff));
  ticks(3);
  const auto kicker = robot_with_role(tick(), "kicker");
  ASSERT_TRUE(kicker);
  // Put the kicker right behind the ball, aligned with the goal centre (no opponents: the aim is the
  // centre): after NORMAL_START it must fire.
  script_.enemies().clear();
  script_.robot(*kicker)->position = {-(kR + 0.0215 + 0.01), 0};
  script_.robot(*kicker)->orientation = 0;
  script_.command(RefereeCommand::kNormalStart);
  const PlannerOutput out = tick();
  EXPECT_EQ(out.play, "our_kickoff");
  const RoleInfo* r = role(out, *kicker);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->skill, skill_name(Skill::kShoot));
  bool kicked = false;
  for (const RobotCommand& c : out.commands) kicked |= c.id == *kicker && c.kick == KickType::kFlat;
  EXPECT_TRUE(kicked);
}

TEST_P(PlannerRefereeTest, WithTheKickoffSetPlayOurKickoffIsPassedToTheOpenWing) {
  // Division B, our kickoff (the team play test's scene): the kicker behind the ball, the wings beside the
  // centre circle in our half, one of theirs beside the +y wing's lane.
  PlannerConfig config = testing::config_for(GetParam());
  config.default_field = FieldGeometry::division_b();
  Script script(GetParam());
  script.set_ball({0.0, 0.0});
  script.add_friend(testing::kOurKeeper, {-4.3, 0.0});
  script.add_friend(1, {-(kR + 0.0215 + 0.01), 0.0});
  script.add_friend(2, {-0.35, 1.2});
  script.add_friend(3, {-0.35, -1.2});
  script.add_friend(4, {-2.5, 0.0});
  script.add_enemy(7, {0.7, 0.0});
  script.add_enemy(8, {1.5, -1.5});
  script.add_enemy(9, {0.1, 0.65});
  script.command(script.ours(Restart::kKickoff));
  const auto role_of_robot = [](const PlannerOutput& out, std::uint32_t id) {
    for (const RoleInfo& r : out.roles) {
      if (r.robot_id == id) return r;
    }
    return RoleInfo{};
  };
  const auto kick_off = [&](Planner& planner) {
    for (int i = 0; i < 3; ++i) planner.step(script.inputs(), testing::at_tick(i));
    script.command(RefereeCommand::kNormalStart);
    PlannerOutput out;
    for (int i = 3; i < 5; ++i) out = planner.step(script.inputs(), testing::at_tick(i));
    script.command(script.ours(Restart::kKickoff));
    return out;
  };
  // KickoffPlay::kShot: the kicker shoots.
  config.kickoff = KickoffPlay::kShot;
  Planner shooting(config);
  EXPECT_EQ(role_of_robot(kick_off(shooting), 1).skill, "shoot");
  // The set play (the default): the kicker passes to the open wing (3), who waits for it where it stands.
  config.kickoff = KickoffPlay::kPass;
  Planner planner(config);
  const PlannerOutput out = kick_off(planner);
  EXPECT_EQ(out.play, "our_kickoff");
  EXPECT_EQ(role_of_robot(out, 1).tactic, "kickoff_pass");
  EXPECT_EQ(role_of_robot(out, 1).skill, "pass");
  EXPECT_EQ(role_of_robot(out, 3).tactic, "kickoff_receive");
  EXPECT_LT(role_of_robot(out, 3).target.x(), 0.0);
  EXPECT_NE(role_of_robot(out, 2).tactic, "kickoff_receive");
}

TEST_P(PlannerRefereeTest, TheirKickoffEveryoneInOurHalfOutsideTheCircle) {
  script_.command(script_.theirs(Restart::kKickoff));
  const PlannerOutput out = ticks(3);
  EXPECT_EQ(out.play, "their_kickoff");
  for (const RoleInfo& r : out.roles) {
    EXPECT_LE(r.target.x(), -kR) << "robot " << r.robot_id;
    EXPECT_GE(r.target.norm(), 0.5 + kR) << "robot " << r.robot_id;
  }
}

TEST_P(PlannerRefereeTest, OurPenaltyKickerAtTheMarkOthersBehind) {
  const Vec2 mark = field().their_penalty_mark();
  script_.set_ball(mark);
  script_.command(script_.ours(Restart::kPenalty));
  const PlannerOutput out = ticks(3);
  EXPECT_EQ(out.play, "our_penalty");
  const auto kicker = robot_with_role(out, "kicker");
  ASSERT_TRUE(kicker);
  for (const RoleInfo& r : out.roles) {
    if (r.robot_id == *kicker) {
      EXPECT_LT((r.target - mark).norm(), 0.35);
      EXPECT_LT(r.target.x(), mark.x());
      EXPECT_GT((r.target - mark).norm(), kR + 0.0215);
    } else {
      EXPECT_LE(r.target.x(), mark.x() - 1.0 - kR) << "robot " << r.robot_id;
    }
  }
}

TEST_P(PlannerRefereeTest, TheirPenaltyKeeperOnGoalLineOthersBehind) {
  const Vec2 mark = field().our_penalty_mark();
  script_.set_ball(mark);
  script_.command(script_.theirs(Restart::kPenalty));
  const PlannerOutput out = ticks(3);
  EXPECT_EQ(out.play, "their_penalty");
  for (const RoleInfo& r : out.roles) {
    if (r.robot_id == testing::kOurKeeper) {
      EXPECT_EQ(r.role, "goalkeeper");
      EXPECT_LE(std::abs(r.target.x() + field().half_length()), kR);  // touches the goal line
      EXPECT_LE(std::abs(r.target.y()), field().size().goal_width / 2);
    } else {
      EXPECT_GE(r.target.x(), mark.x() + 1.0 + kR) << "robot " << r.robot_id;
    }
  }
}

TEST_P(PlannerRefereeTest, OurFreeKickTakerIsTheClosestRobot) {
  script_.set_ball({1.5, -2.0});
  script_.robot(9)->position = {1.8, -2.1};
  script_.command(script_.ours(Restart::kFreeKick));
  const PlannerOutput out = tick();
  EXPECT_EQ(out.play, "our_free_kick");
  EXPECT_EQ(robot_with_role(out, "kicker"), std::optional<std::uint32_t>(9));
  // Someone else closer now: a fresh planner (no history) takes it.
  script_.robot(3)->position = {1.45, -2.05};
  Planner fresh(testing::config_for(GetParam()));
  EXPECT_EQ(robot_with_role(fresh.step(script_.inputs(), testing::at_tick(0)), "kicker"),
            std::optional<std::uint32_t>(3));
}

TEST_P(PlannerRefereeTest, WithTheRedirectSetPlayOurFreeKickWaitsForItsReceiverThenPasses) {
  // Division B, our free kick 1 m in front of their defense area behind a wall (the team play test's scene).
  PlannerConfig config = testing::config_for(GetParam());
  config.default_field = FieldGeometry::division_b();
  Script script(GetParam());
  script.set_ball({2.5, 0.0});
  script.add_friend(testing::kOurKeeper, {-4.3, 0.0});
  script.add_friend(1, {2.38, 0.0});
  script.add_friend(2, {2.6, 1.6});
  script.add_friend(3, {-1.0, 0.0});
  script.add_enemy(7, {3.1, -0.1});
  script.add_enemy(8, {3.1, 0.1});
  script.add_enemy(9, {4.35, 0.25});
  script.command(script.ours(Restart::kFreeKick));
  const auto skill_of_robot = [](const PlannerOutput& out, std::uint32_t id) {
    for (const RoleInfo& r : out.roles) {
      if (r.robot_id == id) return r.skill;
    }
    return std::string();
  };
  // The default (FreeKickPlay::kShot): the taker shoots, nobody redirects.
  Planner shooting(config);
  PlannerOutput out;
  for (int i = 0; i < 3; ++i) out = shooting.step(script.inputs(), testing::at_tick(i));
  EXPECT_EQ(skill_of_robot(out, 1), "shoot");
  EXPECT_NE(skill_of_robot(out, 2), "redirect");
  // The set play: robot 2 goes to its spot to redirect; the taker waits behind the ball, kicker off.
  config.free_kick = FreeKickPlay::kRedirect;
  Planner planner(config);
  for (int i = 0; i < 3; ++i) out = planner.step(script.inputs(), testing::at_tick(i));
  EXPECT_EQ(skill_of_robot(out, 2), "redirect");
  ASSERT_NE(planner.last_intent(1), nullptr);
  EXPECT_EQ(planner.last_intent(1)->kick, KickType::kNone);
  EXPECT_GT((planner.last_intent(1)->target - script.ball()).norm(), kR + 0.0215);
  // Robot 2 stands on its spot and the taker behind the ball facing the pass: it passes (kicker armed).
  ASSERT_NE(planner.last_intent(2), nullptr);
  const MotionIntent spot = *planner.last_intent(2);
  script.robot(2)->position = spot.target;
  script.robot(2)->orientation = spot.orientation;
  const double dribbler = kR + FieldGeometry::division_b().ball_radius;
  const Vec2 point = spot.target + dribbler * Vec2(std::cos(spot.orientation), std::sin(spot.orientation));
  const Vec2 u = (point - script.ball()).normalized();
  script.robot(1)->position = script.ball() - u * dribbler;
  script.robot(1)->orientation = std::atan2(u.y(), u.x());
  for (int i = 3; i < 5; ++i) out = planner.step(script.inputs(), testing::at_tick(i));
  EXPECT_EQ(skill_of_robot(out, 1), "pass");
  EXPECT_EQ(planner.last_intent(1)->kick, KickType::kFlat);
  EXPECT_EQ(skill_of_robot(out, 2), "redirect");
}

TEST_P(PlannerRefereeTest, TheirFreeKickKeepsDistanceAtFullSpeed) {
  script_.set_ball({-2.0, 1.0});
  script_.robot(3)->position = {-2.2, 1.2};  // inside 0.5 m
  script_.command(script_.theirs(Restart::kFreeKick));
  const PlannerOutput out = ticks(3);
  EXPECT_EQ(out.play, "their_free_kick");
  for (const RobotCommand& c : out.commands) {
    const MotionIntent& i = intent(c.id);
    EXPECT_GE((i.target - script_.ball()).norm(), kBallKeepAway) << "robot " << c.id;
    EXPECT_GE(i.avoid_ball_radius, kBallKeepAway);
    EXPECT_GT(i.max_speed, kStopSpeed);
  }
  const wm::RobotState* r3 = script_.robot(3);
  const RobotCommand* c3 = nullptr;
  for (const RobotCommand& c : out.commands) c3 = c.id == 3 ? &c : c3;
  ASSERT_NE(c3, nullptr);
  EXPECT_GT(testing::team_velocity(*c3, r3->orientation).dot(r3->position - script_.ball()), 0.0);
}

TEST_P(PlannerRefereeTest, OurPlacementPlacerGoesToBallThenToTarget) {
  const Vec2 ball(2.0, 1.0);
  const Vec2 target(-1.0, -2.0);
  script_.set_ball(ball);
  script_.robot(10)->position = {2.6, 1.2};
  script_.command(script_.ours(Restart::kPlacement), script_.ours(Restart::kFreeKick), target);
  PlannerOutput out = tick();
  EXPECT_EQ(out.play, "our_ball_placement");
  const auto placer = robot_with_role(out, "placer");
  ASSERT_TRUE(placer);
  EXPECT_EQ(*placer, 10u);
  EXPECT_LT((intent(10).target - ball).norm(), 0.3);  // first to the ball
  // Others: clear of the ball and of the corridor to the target.
  for (const RoleInfo& r : out.roles) {
    if (r.robot_id == *placer) continue;
    EXPECT_GE((r.target - ball).norm(), kBallKeepAway) << "robot " << r.robot_id;
    EXPECT_GE(testing::distance_to_segment(r.target, ball, target), kBallKeepAway) << "robot " << r.robot_id;
  }
  // With the ball on its dribbler, facing the target: it carries it there.
  const Vec2 u = (target - ball).normalized();
  script_.robot(10)->position = ball - u * (kR + 0.0215);
  script_.robot(10)->orientation = geom::angle_of(u).radians();
  out = ticks(2);
  EXPECT_EQ(role(out, 10)->skill, "dribble_to");
  EXPECT_LT((intent(10).target - target).norm(), 0.2);
  EXPECT_TRUE(intent(10).dribble);
}

TEST_P(PlannerRefereeTest, OurPlacementLeavesABallAlreadyOnTheTargetAlone) {
  // The simulator (or a human) put the ball on the target: the placer keeps clear instead of grabbing it.
  const Vec2 target(1.0, -1.0);
  script_.set_ball(target + Vec2(0.03, 0.0));
  script_.robot(10)->position = target + Vec2(0.4, 0.2);
  script_.command(script_.ours(Restart::kPlacement), script_.ours(Restart::kFreeKick), target);
  const PlannerOutput out = ticks(3);
  const auto placer = robot_with_role(out, "placer");
  ASSERT_TRUE(placer);
  EXPECT_EQ(role(out, *placer)->skill, "release_ball");
  EXPECT_FALSE(intent(*placer).dribble);
  EXPECT_GT((intent(*placer).target - script_.ball()).norm(), kR + 0.0215) << "not onto the ball";
}

TEST_P(PlannerRefereeTest, TheirPlacementClearsBallAndCorridor) {
  const Vec2 ball(-1.0, 2.0);
  const Vec2 target(-3.0, 0.0);
  script_.set_ball(ball);
  script_.robot(3)->position = {-2.0, 1.0};  // on the corridor
  script_.command(script_.theirs(Restart::kPlacement), std::nullopt, target);
  for (int i = 0; i < 3; ++i) {
    const PlannerOutput out = tick();
    EXPECT_EQ(out.play, "their_ball_placement");
    for (const RobotCommand& c : out.commands) {
      const MotionIntent& in = intent(c.id);
      EXPECT_GE((in.target - ball).norm(), kBallKeepAway) << "robot " << c.id;
      EXPECT_GE(testing::distance_to_segment(in.target, ball, target), kBallKeepAway) << "robot " << c.id;
      EXPECT_LE(testing::speed(c), kStopSpeed);
    }
  }
}

TEST_P(PlannerRefereeTest, OurPlacementNotAllowedBehavesLikeStop) {
  script_.set_ball({1.0, 1.0});
  script_.robot(6)->position = {1.2, 1.1};
  script_.can_place(false);
  script_.command(script_.ours(Restart::kPlacement), std::nullopt, Vec2(0, 0));
  const PlannerOutput out = ticks(3);
  EXPECT_EQ(out.play, "our_ball_placement_not_allowed");
  EXPECT_FALSE(robot_with_role(out, "placer"));
  expect_stop_properties(out);
}

TEST_P(PlannerRefereeTest, StopPrepositionsForOurKickoff) {
  script_.command(RefereeCommand::kStop, script_.ours(Restart::kKickoff));
  const PlannerOutput out = ticks(3);
  EXPECT_EQ(out.play, "stop");
  expect_stop_properties(out);
  const auto kicker = robot_with_role(out, "kicker");
  ASSERT_TRUE(kicker);  // already chosen, waiting outside the 0.5 m circle
  for (const RoleInfo& r : out.roles) {
    EXPECT_LE(r.target.x(), 0.0) << "robot " << r.robot_id;
    if (r.robot_id != *kicker) {
      EXPECT_GE(r.target.norm(), 0.5 + kR) << "robot " << r.robot_id;
    }
  }
}

TEST_P(PlannerRefereeTest, StopPrepositionsForTheirPenalty) {
  const Vec2 mark = field().our_penalty_mark();
  script_.set_ball(mark);
  script_.command(RefereeCommand::kStop, script_.theirs(Restart::kPenalty));
  const PlannerOutput out = ticks(3);
  expect_stop_properties(out, /*check_defense_area=*/true);
  for (const RoleInfo& r : out.roles) {
    if (r.robot_id != testing::kOurKeeper) {
      EXPECT_GE(r.target.x(), mark.x() + 1.0 + kR) << "robot " << r.robot_id;
    }
  }
}

TEST_P(PlannerRefereeTest, NormalStartAndForceStartReachTheStrategy) {
  script_.set_ball({1.0, 1.0});
  script_.robot(6)->position = {1.3, 1.2};
  script_.command(RefereeCommand::kStop);
  ticks(2);
  script_.command(RefereeCommand::kNormalStart);
  PlannerOutput out = tick();
  EXPECT_EQ(out.play, "base_strategy");
  EXPECT_EQ(robot_with_role(out, "attacker"), std::optional<std::uint32_t>(6));
  const RoleInfo* keeper = role(out, testing::kOurKeeper);
  ASSERT_NE(keeper, nullptr);
  EXPECT_EQ(keeper->role, "goalkeeper");
  EXPECT_LT(std::abs(keeper->target.x() + field().half_length()), 0.2);
  EXPECT_LE(std::abs(keeper->target.y()), field().size().goal_width / 2);
  EXPECT_GT(keeper->target.y(), 0.0);  // towards the ball's side

  script_.command(RefereeCommand::kStop);
  ticks(2);
  script_.command(RefereeCommand::kForceStart);
  out = tick();
  EXPECT_EQ(out.play, "base_strategy");
  EXPECT_EQ(robot_with_role(out, "attacker"), std::optional<std::uint32_t>(6));
}

TEST_P(PlannerRefereeTest, TimeoutParksOnOurSide) {
  script_.command(script_.ours(Restart::kTimeout));
  const PlannerOutput out = ticks(3);
  EXPECT_EQ(out.play, "timeout");
  for (const RoleInfo& r : out.roles) {
    if (r.robot_id == testing::kOurKeeper) {
      EXPECT_EQ(r.role, "goalkeeper");
      continue;
    }
    EXPECT_EQ(r.role, "parked");
    EXPECT_LT(r.target.x(), 0.0);
    EXPECT_LT(r.target.y(), -field().half_width() + 0.5);
  }
  for (const RobotCommand& c : out.commands) EXPECT_LE(testing::speed(c), kStopSpeed);
}

TEST_P(PlannerRefereeTest, GoalkeeperFromTheRefereeKeepsItsRole) {
  const RefereeCommand commands[] = {RefereeCommand::kStop, script_.theirs(Restart::kFreeKick),
                                     script_.ours(Restart::kFreeKick), script_.theirs(Restart::kKickoff),
                                     RefereeCommand::kForceStart};
  for (RefereeCommand command : commands) {
    script_.command(command);
    const PlannerOutput out = ticks(2);
    EXPECT_EQ(role(out, testing::kOurKeeper)->role, "goalkeeper") << out.play;
  }
}

TEST_P(PlannerRefereeTest, TheKeeperStandsWhereAShotWillCrossItsLine) {
  script_.command(RefereeCommand::kForceStart);
  const double goal_line = -field().half_length();
  const double half_goal = field().size().goal_width / 2;
  // A shot from (-1.5, 0.6) aimed 0.3 m inside the far post: the keeper leaves the ball-goal line for it.
  const Vec2 from(-1.5, 0.6);
  const Vec2 aim(goal_line, -(half_goal - 0.1));
  script_.set_ball(from, (aim - from).normalized() * 4.0);
  ticks(2);
  const MotionIntent& keeper = intent(testing::kOurKeeper);
  EXPECT_EQ(keeper.skill, skill_name(Skill::kDefendGoal));
  const double t = (keeper.target.x() - from.x()) / (aim - from).x();
  EXPECT_NEAR(keeper.target.y(), from.y() + t * (aim - from).y(), 1e-6);
  EXPECT_LT(keeper.target.y(), 0.0) << "on the far side of the goal centre from the ball";

  // The same ball rolling away from our goal, or wide of it: no shot, the keeper stays on the ball's side.
  for (const Vec2& velocity : {Vec2((from - aim).normalized() * 4.0), Vec2(-4.0, 2.0)}) {
    script_.set_ball(from, velocity);
    ticks(2);
    EXPECT_GT(intent(testing::kOurKeeper).target.y(), 0.0) << velocity.transpose();
  }
}

INSTANTIATE_TEST_SUITE_P(AllSides, PlannerRefereeTest, ::testing::ValuesIn(testing::all_sides()),
                         testing::side_name);

// ---- debug, determinism ----------------------------------------------------------------------------------

TEST(PlannerDebugTest, TreeDrawingsAndSnapshotRows) {
  Script script(Side{});
  script.default_teams();
  script.command(RefereeCommand::kStop);
  Planner planner(testing::config_for(Side{}));
  const PlannerOutput out = planner.step(script.inputs(), testing::at_tick(0));
  const std::string ascii = planner.tree_ascii();
  EXPECT_NE(ascii.find("RefereeOverride"), std::string::npos);
  EXPECT_NE(ascii.find("BaseStrategy"), std::string::npos);
  EXPECT_NE(ascii.find("StopFormation"), std::string::npos);
  EXPECT_EQ(planner.tree_dot().rfind("digraph", 0), 0u);
  ASSERT_FALSE(out.tree.empty());
  EXPECT_EQ(out.tree.front().name, "Root");
  EXPECT_EQ(out.tree.front().status, TreeNodeInfo::Status::kSuccess);
  bool stop_ran = false;
  for (const TreeNodeInfo& row : out.tree) {
    stop_ran |=
        row.name == "Root/RefereeOverride/Stop/StopFormation" && row.status == TreeNodeInfo::Status::kSuccess;
  }
  EXPECT_TRUE(stop_ran);
  EXPECT_EQ(out.roles.size(), 11u);
  EXPECT_EQ(out.tick, 1u);
}

TEST(PlannerDeterminismTest, SameInputsSameOutputs) {
  Script script(Side{TeamColor::kYellow, true});
  script.default_teams();
  script.set_ball({0.3, -1.0});
  script.command(RefereeCommand::kForceStart);
  Planner a(testing::config_for(script.side()));
  Planner b(testing::config_for(script.side()));
  for (int i = 0; i < 20; ++i) {
    const PlannerOutput oa = a.step(script.inputs(), testing::at_tick(i));
    const PlannerOutput ob = b.step(script.inputs(), testing::at_tick(i));
    ASSERT_EQ(oa.commands.size(), ob.commands.size());
    for (std::size_t k = 0; k < oa.commands.size(); ++k) {
      EXPECT_EQ(oa.commands[k].forward, ob.commands[k].forward);
      EXPECT_EQ(oa.commands[k].left, ob.commands[k].left);
      EXPECT_EQ(oa.commands[k].angular, ob.commands[k].angular);
      EXPECT_EQ(oa.roles[k].role, ob.roles[k].role);
    }
  }
}

TEST(PlannerRoleStabilityTest, RolesDoNotFlapWhenRobotsJitter) {
  Script script(Side{});
  script.default_teams();
  script.set_ball({0.0, 0.0});
  script.robot(5)->position = {-0.3, 0.0};
  script.robot(6)->position = {0.31, 0.0};  // nearly as close
  script.command(RefereeCommand::kForceStart);
  Planner planner(testing::config_for(script.side()));
  std::vector<std::string> first;
  for (int i = 0; i < 50; ++i) {
    // Jitter: 6 and 5 swap being the closest every tick by 2 cm.
    script.robot(6)->position.x() = (i % 2 == 0) ? 0.29 : 0.32;
    for (auto& r : script.friends()) r.position.y() += (i % 2 == 0 ? 0.01 : -0.01);
    const PlannerOutput out = planner.step(script.inputs(), testing::at_tick(i));
    std::vector<std::string> roles;
    for (const RoleInfo& r : out.roles) roles.push_back(r.role + "@" + std::to_string(r.robot_id));
    if (i == 0) first = roles;
    EXPECT_EQ(roles, first) << "tick " << i;
  }
}

}  // namespace
}  // namespace ssl::planner

namespace ssl::planner {
namespace {

TEST(PlannerDebugTest, TrajectoriesReportTheirPathAndTrackingError) {
  const Side side{};
  Script script(side);
  script.default_teams();
  script.command(RefereeCommand::kStop);
  Planner planner(testing::config_for(side));  // trajectories are the default skill layer
  const PlannerOutput first = planner.step(script.inputs(), testing::at_tick(0));
  ASSERT_FALSE(first.roles.empty());
  bool some_path = false;
  for (const RoleInfo& role : first.roles) {
    EXPECT_FALSE(role.tracking_error) << "no trajectory last tick";
    if (role.path.size() < 2) continue;
    some_path = true;
    EXPECT_LT((role.path.front() - script.robot(role.robot_id)->position).norm(), 1e-9) << "starts at the robot";
    EXPECT_LE((role.path[1] - role.path[0]).norm(), kStopSpeed * 0.1 + 1e-6) << "0.1 s apart within the STOP limit";
  }
  EXPECT_TRUE(some_path) << "robots moving to their STOP positions have paths";

  // The robots did not move (the script is static): the error is how far the plan expected them to go.
  const PlannerOutput second = planner.step(script.inputs(), testing::at_tick(1));
  for (const RoleInfo& role : second.roles) {
    ASSERT_TRUE(role.tracking_error) << "robot " << role.robot_id;
    EXPECT_GE(*role.tracking_error, 0.0);
    EXPECT_LT(*role.tracking_error, 0.01) << "one tick of a trajectory from rest is less than a centimetre";
  }

  PlannerConfig simple_config = testing::config_for(side);
  simple_config.motion = MotionControl::kSimple;
  Planner simple(simple_config);
  for (const RoleInfo& role : simple.step(script.inputs(), testing::at_tick(0)).roles) {
    EXPECT_TRUE(role.path.empty());
    EXPECT_FALSE(role.tracking_error);
  }
}

// Ticks follow the vision frames, which may come 0.2 ms apart (two cameras): the acceleration limit holds
// over that real interval, not over a minimum tick.
TEST(PlannerTickTimeTest, AccelerationIsLimitedOverTheRealTimeBetweenTicks) {
  const Side side{};
  Script script(side);
  script.default_teams();
  script.command(RefereeCommand::kStop);  // every robot heads for its STOP position, from rest
  PlannerConfig config = testing::config_for(side);
  config.motion = MotionControl::kSimple;
  Planner planner(config);
  const PlannerOutput first = planner.step(script.inputs(), testing::at_tick(0));
  constexpr double kApart = 0.0002;  // s
  const PlannerOutput second =
      planner.step(script.inputs(), testing::at_tick(0) + time::duration_from_seconds(kApart));
  ASSERT_EQ(first.commands.size(), second.commands.size());
  bool accelerating = false;
  for (std::size_t i = 0; i < first.commands.size(); ++i) {
    const RobotCommand& a = first.commands[i];
    const RobotCommand& b = second.commands[i];
    const double change = std::hypot(b.forward - a.forward, b.left - a.left);
    EXPECT_LE(change, config.limits.max_acceleration * kApart + 1e-9) << "robot " << a.id;
    accelerating = accelerating || change > 0.5 * config.limits.max_acceleration * kApart;
  }
  EXPECT_TRUE(accelerating) << "some robot speeds up at the limit (the test would be empty otherwise)";
}

}  // namespace
}  // namespace ssl::planner
