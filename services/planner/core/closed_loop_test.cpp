// Closed loop: the planner's commands drive kinematic robots (and a ball that sticks to a dribbling
// robot) for a few seconds; the rule properties must hold at every tick and the targets must be reached.
#include <gtest/gtest.h>

#include <cmath>

#include "services/planner/core/motion.h"
#include "services/planner/core/planner.h"
#include "services/planner/core/planner_test_util.h"

namespace ssl::planner {
namespace {

using testing::KinematicSim;
using testing::Restart;
using testing::Script;
using testing::Side;
using wm::RefereeCommand;

constexpr double kR = testing::kRadius;
constexpr double kDt = 0.01;

class PlannerClosedLoopTest : public ::testing::TestWithParam<Side> {
 protected:
  PlannerClosedLoopTest() : script_(GetParam()), planner_(testing::config_for(GetParam())), sim_(script_) {
    script_.default_teams();
  }

  PlannerOutput step() {
    PlannerOutput out = planner_.step(script_.inputs(), testing::at_tick(tick_++));
    sim_.apply(out, kDt);
    return out;
  }

  Script script_;
  Planner planner_;
  KinematicSim sim_;
  int tick_ = 0;
};

TEST_P(PlannerClosedLoopTest, StopFromACrowdedBallClearsItWithinTheGraceTime) {
  script_.set_ball({2.0, 0.5});
  script_.robot(6)->position = {1.8, 0.5};
  script_.robot(7)->position = {2.2, 0.6};
  script_.robot(8)->position = {2.0, 0.25};
  script_.command(RefereeCommand::kStop);
  const wm::Field field = script_.field();
  for (int i = 0; i < 400; ++i) {
    const PlannerOutput out = step();
    for (const RobotCommand& c : out.commands) {
      ASSERT_LE(testing::speed(c), 1.5) << "tick " << i;
      ASSERT_EQ(c.kick, KickType::kNone);
    }
    if (i * kDt < 2.0) continue;  // rules: 2 s grace
    for (const wm::RobotState& r : script_.friends()) {
      ASSERT_GE((r.position - script_.ball()).norm(), 0.5 + kR) << "robot " << r.id << " tick " << i;
      ASSERT_GE(testing::distance_to_their_defense_area(field, r.position), 0.2 + kR) << "robot " << r.id;
    }
  }
  EXPECT_FALSE(sim_.touched());
}

TEST_P(PlannerClosedLoopTest, OurPlacementBringsTheBallToTheDesignatedPosition) {
  const Vec2 target(-1.5, -2.0);
  script_.set_ball({1.0, 1.0});
  script_.command(script_.ours(Restart::kPlacement), script_.ours(Restart::kFreeKick), target);
  bool placed = false;
  std::optional<std::uint32_t> placer;
  for (int i = 0; i < 2000 && !placed; ++i) {
    const PlannerOutput out = step();
    for (const RobotCommand& c : out.commands) ASSERT_LE(testing::speed(c), 1.5) << "tick " << i;
    for (const RoleInfo& r : out.roles) {
      if (r.role == "placer") placer = r.robot_id;
    }
    ASSERT_TRUE(placer);
    // Everybody else keeps clear of the ball and the corridor once they had 2 s.
    if (i * kDt > 2.0) {
      for (const wm::RobotState& r : script_.friends()) {
        if (r.id == *placer) continue;
        ASSERT_GE((r.position - script_.ball()).norm(), 0.5 + kR) << "robot " << r.id << " tick " << i;
      }
    }
    const wm::RobotState* p = script_.robot(*placer);
    placed = (script_.ball() - target).norm() < 0.15 && (p->position - script_.ball()).norm() > 0.3;
  }
  EXPECT_TRUE(placed) << "ball at " << script_.ball().transpose() << " target " << target.transpose();
  EXPECT_LT((script_.ball() - target).norm(), 0.15);
}

TEST_P(PlannerClosedLoopTest, OurKickoffPositionsThenTheKickerKicks) {
  script_.set_ball({0, 0});
  script_.command(script_.ours(Restart::kKickoff));
  std::optional<std::uint32_t> kicker;
  for (int i = 0; i < 500; ++i) {
    const PlannerOutput out = step();
    for (const RoleInfo& r : out.roles) {
      if (r.role == "kicker") kicker = r.robot_id;
    }
    ASSERT_FALSE(sim_.touched()) << "tick " << i;
    ASSERT_FALSE(sim_.kicked()) << "tick " << i;
  }
  ASSERT_TRUE(kicker);
  for (const wm::RobotState& r : script_.friends()) {
    if (r.id == *kicker) continue;
    EXPECT_LE(r.position.x(), -kR + 0.02) << "robot " << r.id;
    EXPECT_GE(r.position.norm(), 0.5 + kR - 0.02) << "robot " << r.id;
  }
  script_.command(RefereeCommand::kNormalStart);
  for (int i = 0; i < 300 && !sim_.kicked(); ++i) step();
  EXPECT_TRUE(sim_.kicked());
  for (int i = 0; i < 30; ++i) step();
  // The kickoff set play's pass back to an open wing, or the straight shot at their goal.
  EXPECT_GT(script_.inputs().world.ball.velocity.norm(), 1.0);
}

TEST_P(PlannerClosedLoopTest, TheirFreeKickKeepsTheDistanceActively) {
  script_.set_ball({-1.0, 1.5});
  script_.robot(5)->position = {-1.2, 1.4};
  script_.command(script_.theirs(Restart::kFreeKick));
  for (int i = 0; i < 300; ++i) {
    step();
    if (i * kDt < 1.0) continue;
    for (const wm::RobotState& r : script_.friends()) {
      ASSERT_GE((r.position - script_.ball()).norm(), 0.5 + kR) << "robot " << r.id << " tick " << i;
    }
  }
}

TEST_P(PlannerClosedLoopTest, NormalPlayAttackerShootsAtTheGoal) {
  script_.set_ball({1.5, -1.0});
  script_.command(RefereeCommand::kForceStart);
  for (int i = 0; i < 600 && !sim_.kicked(); ++i) step();
  EXPECT_TRUE(sim_.kicked());
  for (int i = 0; i < 20; ++i) step();
  const Vec2 v = script_.inputs().world.ball.velocity.head<2>();
  EXPECT_GT(v.x(), 1.0);
}

INSTANTIATE_TEST_SUITE_P(AllSides, PlannerClosedLoopTest, ::testing::ValuesIn(testing::all_sides()),
                         testing::side_name);

}  // namespace
}  // namespace ssl::planner
