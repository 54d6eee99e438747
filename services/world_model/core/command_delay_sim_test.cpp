// Our robots' command-to-motion delay measured by the world model against the simulator's robot response
// (sim::RobotResponse): a pure delay that changes mid-run, and the realistic profile's delay plus lag.
#include <gtest/gtest.h>

#include <cstdio>

#include "services/world_model/core/sim_harness.h"

namespace ssl::wm {
namespace {

using namespace std::chrono_literals;
using testing::SimHarness;

/// Blue's six robots driven the way a planner drives them, inside the field (a robot pushing a wall tells
/// nothing of its delay): each heads for a new point every 1.5 s at up to 2 m/s (slowing near it), its
/// global velocity sent as a LOCAL command turned by its true heading, while it turns back and forth.
/// Commanded every 10 ms and told to the model.
void drive(SimHarness& h, time::Duration duration, time::Timestamp start) {
  time::Timestamp next = h.now();
  h.run(
      duration,
      [&](SimHarness& harness) {
        if (harness.now() < next) return;
        next = harness.now() + 10ms;
        const double t = time::to_seconds(harness.now() - start);
        std::vector<sim::RobotCommandFor> commands;
        for (const sim::RobotState& robot : harness.sim().snapshot().robots) {
          if (robot.key.team != TeamColor::kBlue) continue;
          const double id = robot.key.id;
          const auto leg = static_cast<int>(t / 1.5);
          const Vec2 target(2.5 * std::sin(1.7 * leg + 2.1 * id), 2.0 * std::cos(2.3 * leg + 1.3 * id));
          const Vec2 to_target = target - robot.position;
          const Vec2 velocity = to_target.normalized() * std::min(2.0, 2.5 * to_target.norm());
          const Vec2 local = geom::rotate(velocity, geom::Angle::from_radians(-robot.orientation));
          sim::RobotCommand command{.move = sim::RobotCommand::Move::kLocalVelocity};
          command.velocity = sim::Vec3(local.x(), local.y(), 2.0 * std::sin(1.1 * t + id));
          commands.push_back({robot.key.id, command});
        }
        harness.command(TeamColor::kBlue, commands, true);
      },
      nullptr);
}

TEST(CommandDelaySim, TheMeasuredDelayFollowsATrueDelayThatChangesFrom30To70Milliseconds) {
  SimHarness h({.robots_per_team = 6, .response = {.command_delay = 0.03}, .seed = 3});
  const time::Timestamp start = h.now();
  drive(h, 10s, start);
  ASSERT_TRUE(h.model().command_delay());
  const double before = *h.model().command_delay();
  h.sim().set_response({.command_delay = 0.07});
  drive(h, 8s, start);
  ASSERT_TRUE(h.model().command_delay());
  const double after = *h.model().command_delay();
  std::printf("[CommandDelay] true 30 ms: measured %.1f ms; 8 s after it became 70 ms: %.1f ms\n", before * 1e3,
              after * 1e3);
  EXPECT_NEAR(before, 0.03, 0.01);
  EXPECT_NEAR(after, 0.07, 0.01);
}

TEST(CommandDelaySim, TheRealisticResponseMeasuresAsItsDelayPlusAboutItsVelocityLag) {
  // 25 ms of radio and firmware, then a velocity that lags the set point by 50 ms (first order): the one
  // pure delay that best explains the motion lies between the two.
  SimHarness h({.robots_per_team = 6, .response = sim::RobotResponse::realistic(), .seed = 3});
  drive(h, 12s, h.now());
  ASSERT_TRUE(h.model().command_delay());
  const double measured = *h.model().command_delay();
  std::printf("[CommandDelay] realistic response (25 ms delay, 50 ms lag): measured %.1f ms\n", measured * 1e3);
  EXPECT_GT(measured, 0.035);
  EXPECT_LT(measured, 0.09);
}

}  // namespace
}  // namespace ssl::wm
