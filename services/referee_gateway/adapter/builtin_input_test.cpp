// The built-in referee's input conversions: camera frames merged into one observation, operator commands.
#include "services/referee_gateway/adapter/builtin_input.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ssl::referee {
namespace {

using namespace std::chrono_literals;

const time::Timestamp kNow = time::Timestamp::from_seconds(1.8e9);

idl::vision::DetectionFrame frame(std::uint32_t camera, time::Timestamp received) {
  idl::vision::DetectionFrame f;
  f.camera_id(camera);
  f.capture_unix_ns(received.nanoseconds() - 10'000'000);
  f.receive_unix_ns(received.nanoseconds());
  return f;
}

idl::vision::BallDetection ball(double x, double y, float confidence) {
  idl::vision::BallDetection b;
  b.x(x);
  b.y(y);
  b.confidence(confidence);
  return b;
}

idl::vision::RobotDetection robot(std::uint32_t id, double x, double y) {
  idl::vision::RobotDetection r;
  r.robot_id(id);
  r.x(x);
  r.y(y);
  return r;
}

TEST(BuiltinRefereeInput, CamerasAreMergedTheMostConfidentBallWinsAndRobotsAreAveraged) {
  VisionObservation vision;
  auto left = frame(0, kNow - 5ms);
  left.balls().push_back(ball(1.0, 2.0, 0.4F));
  left.robots_blue().push_back(robot(3, -1.0, 0.5));
  auto right = frame(1, kNow - 2ms);
  right.balls().push_back(ball(1.1, 2.1, 0.9F));
  right.robots_blue().push_back(robot(3, -1.2, 0.7));
  right.robots_yellow().push_back(robot(3, 2.0, 0.0));
  vision.add(left);
  vision.add(right);
  const Observation seen = vision.observe(kNow, 100ms);
  ASSERT_TRUE(seen.ball_position);
  EXPECT_DOUBLE_EQ(seen.ball_position->x(), 1.1);
  ASSERT_EQ(seen.robots.size(), 2u);
  for (const ObservedRobot& r : seen.robots) {
    EXPECT_EQ(r.id, 3u);
    if (r.team == TeamColor::kBlue) {
      EXPECT_NEAR(r.position.x(), -1.1, 1e-12);
      EXPECT_NEAR(r.position.y(), 0.6, 1e-12);
    } else {
      EXPECT_DOUBLE_EQ(r.position.x(), 2.0);
    }
  }
}

TEST(BuiltinRefereeInput, StaleCamerasLateFramesAndNonFiniteDetectionsAreLeftOut) {
  VisionObservation vision;
  auto stale = frame(0, kNow - 500ms);
  stale.balls().push_back(ball(1.0, 1.0, 1.0F));
  vision.add(stale);
  EXPECT_FALSE(vision.observe(kNow, 100ms).ball_position) << "a camera silent for 500 ms is not observed";

  auto fresh = frame(1, kNow);
  fresh.balls().push_back(ball(std::numeric_limits<double>::quiet_NaN(), 0.0, 1.0F));
  fresh.balls().push_back(ball(0.5, 0.5, 0.2F));
  fresh.robots_yellow().push_back(robot(1, std::numeric_limits<double>::infinity(), 0.0));
  vision.add(fresh);
  const Observation seen = vision.observe(kNow, 100ms);
  ASSERT_TRUE(seen.ball_position);
  EXPECT_DOUBLE_EQ(seen.ball_position->x(), 0.5);
  EXPECT_TRUE(seen.robots.empty());
  EXPECT_EQ(vision.invalid_detections(), 2u);

  auto late = frame(1, kNow - 50ms);  // captured before the kept frame of camera 1
  late.balls().push_back(ball(-3.0, -3.0, 1.0F));
  vision.add(late);
  EXPECT_DOUBLE_EQ(vision.observe(kNow, 100ms).ball_position->x(), 0.5);
}

TEST(BuiltinRefereeInput, OperatorCommandsConvertWithTheirTargetAndUnknownOnesAreRefused) {
  idl::referee::RefereeOperatorCommand sample;
  sample.command(idl::referee::COMMAND_BALL_PLACEMENT_BLUE);
  sample.has_designated_position(true);
  sample.designated_position().x(1.5);
  sample.designated_position().y(-0.25);
  const auto placement = operator_command(sample);
  ASSERT_TRUE(placement);
  EXPECT_EQ(placement->command, Command::kBallPlacementBlue);
  ASSERT_TRUE(placement->designated_position);
  EXPECT_DOUBLE_EQ(placement->designated_position->y(), -0.25);

  sample.has_designated_position(false);
  sample.command(idl::referee::COMMAND_HALT);
  EXPECT_FALSE(operator_command(sample)->designated_position);
  sample.command(static_cast<idl::referee::Command>(42));
  EXPECT_FALSE(operator_command(sample));
}

}  // namespace
}  // namespace ssl::referee
