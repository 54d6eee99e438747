#include "services/planner/core/path_search.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numbers>
#include <random>

#include "libs/geometry/contains.h"

namespace ssl::planner {
namespace {

using geom::Vec2;

constexpr TrajectoryLimits kLimits{.max_speed = 3.0, .max_acceleration = 3.0};
constexpr double kTwoRobots = 0.18;  // m between two robots' centres when they touch

/// The smallest clearance (m, negative: overlap) of `path` to the obstacles, sampled every millisecond up
/// to `horizon`: an independent check of the sweep, ignoring obstacles the path starts in until it left.
double dense_clearance(const TrajectoryPath& path, const PathObstacles& obstacles, double horizon) {
  double clearance = std::numeric_limits<double>::infinity();
  const Vec2 start = path.position(0);
  std::vector<bool> left;
  for (const MovingCircle& c : obstacles.circles) left.push_back((start - c.position).norm() >= c.radius);
  for (double t = 0; t <= std::min(horizon, path.duration()); t += 1e-3) {
    const Vec2 p = path.position(t);
    for (std::size_t i = 0; i < obstacles.circles.size(); ++i) {
      const MovingCircle& c = obstacles.circles[i];
      const double gap = (p - (c.position + c.velocity * t)).norm() - c.radius;
      if (gap >= 0) left[i] = true;
      if (left[i]) clearance = std::min(clearance, gap);
    }
  }
  return clearance;
}

TEST(PathSearch, AFreeDirectPathIsTakenWithoutSampling) {
  PathObstacles obstacles;
  obstacles.circles.push_back({.position = {0, 2}, .radius = kTwoRobots});
  const PathResult result = search_path({-2, 0}, Vec2::Zero(), {2, 0}, kLimits, obstacles);
  EXPECT_TRUE(result.path.is_direct());
  EXPECT_FALSE(result.first_collision);
  EXPECT_EQ(result.candidates, 1);
  EXPECT_DOUBLE_EQ(result.score, Trajectory2D::plan({-2, 0}, Vec2::Zero(), {2, 0}, kLimits).duration());
}

TEST(PathSearch, ARobotOnTheWayIsGoneAround) {
  PathObstacles obstacles;
  obstacles.circles.push_back({.position = {0, 0.05}, .radius = kTwoRobots + 0.05});
  const PathResult result = search_path({-2, 0}, Vec2::Zero(), {2, 0}, kLimits, obstacles);
  EXPECT_FALSE(result.path.is_direct());
  EXPECT_FALSE(result.first_collision);
  EXPECT_GE(result.candidates, 64);
  EXPECT_GE(dense_clearance(result.path, obstacles, 10), 0.0);
  EXPECT_EQ(result.path.position(result.path.duration()), Vec2(2, 0));
  const double direct = Trajectory2D::plan({-2, 0}, Vec2::Zero(), {2, 0}, kLimits).duration();
  EXPECT_LT(result.path.duration(), direct + 1.0) << "a small detour";
}

TEST(PathSearch, TheWayRoundTheCentreCircleAndARobotBesideItIsFoundFromTheWrongHalf) {
  // Seen in a whole match: their kickoff after half time, one of ours still in their half at (1.15, 1.17),
  // its place at (-0.79, 0) behind the centre circle (the ball's keep-out, 0.64 m for robot centres), one
  // of theirs standing at (0.35, 1.2) above the circle. Going round both takes a sub-destination about a
  // metre out: with switches only within 0.5 s every path collides (on one of the two ring offsets) and the
  // robot dithered for 10 s.
  PathObstacles obstacles;
  obstacles.circles.push_back({.position = {0, 0}, .radius = 0.64});
  obstacles.circles.push_back({.position = {0.35, 1.2}, .radius = kTwoRobots + 0.05});
  obstacles.circles.push_back({.position = {-0.59, 0.79}, .radius = kTwoRobots + 0.03});
  for (const double offset : {0.0, std::numbers::pi / 8}) {
    const PathResult result = search_path({1.15, 1.17}, Vec2::Zero(), {-0.79, 0}, kLimits, obstacles,
                                          {.directions = 8, .direction_offset = offset});
    EXPECT_FALSE(result.first_collision)
        << "offset " << offset << ": collides after " << result.first_collision.value_or(0) << " s";
    EXPECT_GE(dense_clearance(result.path, obstacles, 10), 0.0) << "offset " << offset;
  }
  const PathResult early_only = search_path({1.15, 1.17}, Vec2::Zero(), {-0.79, 0}, kLimits, obstacles,
                                            {.directions = 8, .direction_offset = std::numbers::pi / 8,
                                             .late_switch_times = {}});
  EXPECT_TRUE(early_only.first_collision) << "the scene needs the late switches";
}

TEST(PathSearch, AFastRobotCannotJumpOverAnObstacleBetweenTwoChecks) {
  // At 3 m/s a 50 ms step moves 0.15 m, less than the 0.36 m wide obstacle; with 0.5 s steps it would jump.
  PathObstacles obstacles;
  obstacles.circles.push_back({.position = {0, 0}, .radius = kTwoRobots});
  const Trajectory2D straight = Trajectory2D::plan({-3, 0}, {3, 0}, {3, 0}, kLimits);
  EXPECT_TRUE(first_collision(TrajectoryPath(straight), obstacles, 0.5, 5.0)) << "swept, not sampled";
}

TEST(PathSearch, ACrossingRobotIsAvoidedWhereItWillBe) {
  PathObstacles obstacles;
  // It crosses our straight line at x = 0 when we would be there (after ~1.15 s).
  obstacles.circles.push_back({.position = {0, -2.3}, .velocity = {0, 2.0}, .radius = kTwoRobots + 0.05});
  const Trajectory2D direct = Trajectory2D::plan({-2, 0}, Vec2::Zero(), {2, 0}, kLimits);
  ASSERT_TRUE(first_collision(TrajectoryPath(direct), obstacles, 0.05, 3.0));
  const PathResult result = search_path({-2, 0}, Vec2::Zero(), {2, 0}, kLimits, obstacles);
  EXPECT_FALSE(result.first_collision);
  EXPECT_GE(dense_clearance(result.path, obstacles, 3.0), 0.0);
}

TEST(PathSearch, StartingInsideAnObstacleTheWayOutIsAllowed) {
  PathObstacles obstacles;
  obstacles.rectangles.push_back(geom::Rectangle({-4.5, -1}, {-3.3, 1}));  // e.g. a defense area zone
  const PathResult result = search_path({-4.0, 0}, Vec2::Zero(), {-1, 0}, kLimits, obstacles);
  EXPECT_FALSE(result.first_collision);
  EXPECT_TRUE(result.path.is_direct());
  // Going through it from outside is a collision, though.
  EXPECT_TRUE(first_collision(TrajectoryPath(Trajectory2D::plan({-3, 0}, Vec2::Zero(), {-4.4, 1.5}, kLimits)),
                              obstacles, 0.05, 3.0));
}

TEST(PathSearch, TheBoundsKeepTheCentreInside) {
  PathObstacles obstacles;
  obstacles.bounds = geom::Rectangle({-4.5, -3}, {4.5, 3});
  obstacles.circles.push_back({.position = {0, 2.8}, .radius = 0.4});  // blocks the way along the wall
  const PathResult result = search_path({-2, 2.8}, Vec2::Zero(), {2, 2.8}, kLimits, obstacles);
  EXPECT_FALSE(result.first_collision);
  for (double t = 0; t <= result.path.duration(); t += 0.01) {
    ASSERT_TRUE(obstacles.bounds->contains(result.path.position(t))) << t;
  }
}

TEST(PathSearch, LastTicksDetourIsKeptWhenAnotherIsOnlyAsGood) {
  // A robot on the line: going left or right is about as good, and starting a centimetre to either side
  // picks one of them; the mirrored start picks the other. With last tick's detour given, it stays.
  PathObstacles obstacles;
  obstacles.circles.push_back({.position = {0, 0}, .radius = kTwoRobots + 0.05});
  const PathResult first = search_path({-2, 0.01}, Vec2::Zero(), {2, 0}, kLimits, obstacles);
  ASSERT_FALSE(first.first_collision);
  const bool left = first.path.via().y() > 0;
  const PathResult other_side = search_path({-2, -0.01}, Vec2::Zero(), {2, 0}, kLimits, obstacles);
  ASSERT_NE(other_side.path.via().y() > 0, left) << "the scene's mirror image prefers the other side";
  const PathResult kept =
      search_path({-2, -0.01}, Vec2::Zero(), {2, 0}, kLimits, obstacles, {}, &first.path);
  EXPECT_EQ(kept.path.via().y() > 0, left);
  EXPECT_FALSE(kept.first_collision);
}

TEST(PathSearch, RandomScenesGetPathsThatAreFreeWhenCheckedEveryMillisecond) {
  // Static and moving robots between start and destination, 10,000 seeds: a path the search calls free is
  // free when checked every millisecond, and nearly every scene has one.
  const PathSearchParams params;
  int free_found = 0;
  for (std::uint32_t seed = 0; seed < 10000; ++seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> x(-3.5, 3.5), y(-2.5, 2.5), speed(-1.5, 1.5);
    const Vec2 start(-4, y(random));
    const Vec2 destination(4, y(random));
    PathObstacles obstacles;
    obstacles.bounds = geom::Rectangle({-4.6, -3.1}, {4.6, 3.1});
    const int count = 1 + static_cast<int>(random() % 8);
    for (int i = 0; i < count; ++i) {
      MovingCircle c{.position = {x(random), y(random)}, .radius = kTwoRobots + 0.02};
      if (i % 3 == 2) c.velocity = {speed(random), speed(random)};
      if ((c.position - start).norm() < 0.5 || (c.position - destination).norm() < 0.5) continue;
      obstacles.circles.push_back(c);
    }
    const PathResult result = search_path(start, Vec2::Zero(), destination, kLimits, obstacles, params);
    if (result.first_collision) continue;
    ++free_found;
    ASSERT_GE(dense_clearance(result.path, obstacles, params.horizon), -1e-9) << "seed " << seed;
  }
  EXPECT_GT(free_found, 9000) << "most random scenes have a free way through";
}

}  // namespace
}  // namespace ssl::planner
