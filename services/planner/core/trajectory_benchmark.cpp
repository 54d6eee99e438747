// Trajectory generation (1D, 2D with synchronised axes, 2D sampled every 0.1 s) from random states, and one
// robot's path search among 22 obstacles with the way blocked, so that every candidate is generated
// (BM_PathSearch22Obstacles: budgeted in ./ssl bench's table, bench/budget_table.cpp).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "services/planner/core/path_search.h"
#include "services/planner/core/trajectory.h"

namespace ssl::planner {
namespace {

constexpr TrajectoryLimits kLimits{.max_speed = 3.0, .max_acceleration = 3.0};

struct Start {
  geom::Vec2 position;
  geom::Vec2 velocity;
  geom::Vec2 target;
};

std::vector<Start> random_starts() {
  std::mt19937 random(1);
  std::uniform_real_distribution<double> position(-4.5, 4.5);
  std::uniform_real_distribution<double> speed(-3, 3);
  std::vector<Start> starts(1024);
  for (Start& s : starts) {
    s = {{position(random), position(random)}, {speed(random), speed(random)}, {position(random), position(random)}};
  }
  return starts;
}

void BM_Trajectory1D(benchmark::State& state) {
  const std::vector<Start> starts = random_starts();
  std::size_t i = 0;
  for (auto _ : state) {
    const Start& s = starts[i++ % starts.size()];
    benchmark::DoNotOptimize(Trajectory1D::plan(s.position.x(), s.velocity.x(), s.target.x(), kLimits).duration());
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_Trajectory2D(benchmark::State& state) {
  const std::vector<Start> starts = random_starts();
  std::size_t i = 0;
  for (auto _ : state) {
    const Start& s = starts[i++ % starts.size()];
    benchmark::DoNotOptimize(Trajectory2D::plan(s.position, s.velocity, s.target, kLimits).duration());
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_Trajectory2DSampled(benchmark::State& state) {
  const std::vector<Start> starts = random_starts();
  std::size_t i = 0;
  for (auto _ : state) {
    const Start& s = starts[i++ % starts.size()];
    const Trajectory2D t = Trajectory2D::plan(s.position, s.velocity, s.target, kLimits);
    for (double time = 0; time < t.duration(); time += 0.1) benchmark::DoNotOptimize(t.position(time));
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_PathSearch22Obstacles(benchmark::State& state) {
  std::mt19937 random(2);
  std::uniform_real_distribution<double> x(-4.0, 4.0), y(-2.8, 2.8), speed(-1.5, 1.5);
  PathObstacles obstacles;
  obstacles.bounds = geom::Rectangle({-4.6, -3.1}, {4.6, 3.1});
  obstacles.rectangles = {geom::Rectangle({-5.5, -1.3}, {-3.2, 1.3}), geom::Rectangle({3.2, -1.3}, {5.5, 1.3})};
  obstacles.circles.push_back({.position = {0, 0}, .radius = 0.2});  // on the way: the search must sample
  while (obstacles.circles.size() < 20) {
    const geom::Vec2 p(x(random), y(random));
    if (std::abs(p.y()) < 0.5) continue;  // keeps a way round free
    obstacles.circles.push_back({.position = p, .velocity = {speed(random), speed(random)}, .radius = 0.2});
  }
  int candidates = 0;
  for (auto _ : state) {
    const PathResult result = search_path({-2.5, 0}, {0.5, 0}, {2.5, 0}, kLimits, obstacles);
    candidates = result.candidates;
    benchmark::DoNotOptimize(result.score);
  }
  state.counters["candidates"] = candidates;
  state.counters["obstacles"] = static_cast<double>(obstacles.circles.size() + obstacles.rectangles.size()) + 1;
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(BM_Trajectory1D);
BENCHMARK(BM_Trajectory2D);
BENCHMARK(BM_Trajectory2DSampled);
BENCHMARK(BM_PathSearch22Obstacles);

}  // namespace
}  // namespace ssl::planner

BENCHMARK_MAIN();
