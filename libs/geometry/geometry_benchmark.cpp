// Timings of the hot geometry calls (the 1 kHz simulator and the 2 ms planner tick use them per robot pair).
// Inputs are pre-generated random shapes on an SSL-sized field, cycled so the work cannot be folded away.
//
//   ./build/bench/geometry_benchmark
#include <cstddef>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "libs/geometry/geometry.h"

namespace ssl::geom {
namespace {

constexpr std::size_t kCount = 1024;  // power of two: index with a mask

struct Inputs {
  std::vector<Vec2> points;
  std::vector<Segment> segments;
  std::vector<Circle> circles;
};

const Inputs& inputs() {
  static const Inputs data = [] {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> x(-6.0, 6.0);
    std::uniform_real_distribution<double> y(-4.5, 4.5);
    std::uniform_real_distribution<double> radius(0.05, 1.0);
    Inputs d;
    for (std::size_t i = 0; i < kCount; ++i) {
      d.points.emplace_back(x(rng), y(rng));
      d.segments.push_back({{x(rng), y(rng)}, {x(rng), y(rng)}});
      d.circles.push_back({{x(rng), y(rng)}, radius(rng)});
    }
    return d;
  }();
  return data;
}

void BM_SegmentCircleIntersection(benchmark::State& state) {
  const Inputs& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    Intersections hits = intersection(in.segments[i], in.circles[(i * 7) & (kCount - 1)]);
    benchmark::DoNotOptimize(hits);
    i = (i + 1) & (kCount - 1);
  }
}
BENCHMARK(BM_SegmentCircleIntersection);

void BM_SegmentCircleIntersects(benchmark::State& state) {
  const Inputs& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(intersects(in.segments[i], in.circles[(i * 7) & (kCount - 1)]));
    i = (i + 1) & (kCount - 1);
  }
}
BENCHMARK(BM_SegmentCircleIntersects);

void BM_PointSegmentDistance(benchmark::State& state) {
  const Inputs& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(distance(in.points[i], in.segments[(i * 7) & (kCount - 1)]));
    i = (i + 1) & (kCount - 1);
  }
}
BENCHMARK(BM_PointSegmentDistance);

void BM_SegmentSegmentIntersection(benchmark::State& state) {
  const Inputs& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    auto hit = intersection(in.segments[i], in.segments[(i * 7 + 1) & (kCount - 1)]);
    benchmark::DoNotOptimize(hit);
    i = (i + 1) & (kCount - 1);
  }
}
BENCHMARK(BM_SegmentSegmentIntersection);

void BM_PolygonContains(benchmark::State& state) {
  const Inputs& in = inputs();
  const Polygon l{{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {1.0, 1.0}, {1.0, 2.0}, {0.0, 2.0}};
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(contains(l, in.points[i]));
    i = (i + 1) & (kCount - 1);
  }
}
BENCHMARK(BM_PolygonContains);

}  // namespace
}  // namespace ssl::geom

BENCHMARK_MAIN();
