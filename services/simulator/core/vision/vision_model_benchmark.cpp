// Cost of the simulated SSL-Vision per SIMULATED second: 22 robots + a ball moving over a Division A field,
// VisionModel::update() after every 1 ms physics step (1000 calls, 300 camera frames with 4 cameras at 75
// Hz). The simulator must run >= 50x real time, so vision should stay well under 2 ms per simulated second.
//
//   ./build/bench/simulator_vision_benchmark
//
// Snapshots are precomputed (the trigonometry of the motion would otherwise dominate); only their time is
// written per step. Each benchmark iteration is one simulated second, continuing the same match.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <benchmark/benchmark.h>

#include "services/simulator/core/vision/vision_model.h"

namespace ssl::sim {
namespace {

constexpr int kStepsPerSecond = 1000;

// One simulated second of a busy match: robots drive on ellipses, the ball rolls, lifts and passes near
// robots.
std::vector<WorldSnapshot> one_second_of_match() {
  std::vector<WorldSnapshot> snapshots(kStepsPerSecond);
  for (int step = 0; step < kStepsPerSecond; ++step) {
    const double t = static_cast<double>(step) / kStepsPerSecond;
    WorldSnapshot& world = snapshots[static_cast<std::size_t>(step)];
    const double phase = 2.0 * 3.14159265358979 * t;
    world.ball.position =
        Vec3(4.0 * std::sin(phase), 2.5 * std::cos(phase), 0.0215 + 0.3 * std::max(0.0, std::sin(3 * phase)));
    for (std::uint32_t id = 0; id < 11; ++id) {
      for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
        const double side = team == TeamColor::kBlue ? -1.0 : 1.0;
        RobotState robot;
        robot.key = {team, id};
        robot.position = Vec2(side * (0.5 + 0.5 * id) + 0.4 * std::sin(phase + id),
                              -4.0 + 0.8 * id + 0.4 * std::cos(phase + id));
        robot.orientation = std::remainder(phase + id, 2.0 * 3.14159265358979);
        world.robots.push_back(robot);
      }
    }
    std::sort(world.robots.begin(), world.robots.end(),
              [](const RobotState& a, const RobotState& b) { return a.key < b.key; });
  }
  return snapshots;
}

void run_simulated_seconds(benchmark::State& state, int cameras, const RealismConfig& realism) {
  std::vector<WorldSnapshot> snapshots = one_second_of_match();
  VisionConfig config;
  config.camera_count = cameras;
  config.realism = realism;
  VisionModel model(FieldGeometry::division_a(), config, 42);
  std::int64_t second = 0;
  std::size_t frames = 0;
  for (auto _ : state) {
    for (int step = 0; step < kStepsPerSecond; ++step) {
      WorldSnapshot& world = snapshots[static_cast<std::size_t>(step)];
      world.time = time::Timestamp::from_milliseconds(second * kStepsPerSecond + step);
      VisionOutput out = model.update(world);
      frames += out.frames.size();
      benchmark::DoNotOptimize(out);
    }
    ++second;
  }
  state.counters["frames_per_sim_s"] = static_cast<double>(frames) / static_cast<double>(second);
  state.counters["detections_per_frame"] =
      static_cast<double>(model.stats().ball_detections + model.stats().robot_detections +
                          model.stats().false_balls) /
      static_cast<double>(model.stats().frames_captured);
  state.SetLabel("time = per simulated second");
}

void BM_VisionSimSecond_4Cameras_Realistic(benchmark::State& state) {
  run_simulated_seconds(state, 4, RealismConfig::realistic());
}
BENCHMARK(BM_VisionSimSecond_4Cameras_Realistic)->Unit(benchmark::kMicrosecond);

void BM_VisionSimSecond_4Cameras_None(benchmark::State& state) {
  run_simulated_seconds(state, 4, RealismConfig::none());
}
BENCHMARK(BM_VisionSimSecond_4Cameras_None)->Unit(benchmark::kMicrosecond);

void BM_VisionSimSecond_4Cameras_Competition(benchmark::State& state) {
  run_simulated_seconds(state, 4, RealismConfig::competition());
}
BENCHMARK(BM_VisionSimSecond_4Cameras_Competition)->Unit(benchmark::kMicrosecond);

void BM_VisionSimSecond_8Cameras_Realistic(benchmark::State& state) {
  run_simulated_seconds(state, 8, RealismConfig::realistic());
}
BENCHMARK(BM_VisionSimSecond_8Cameras_Realistic)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace ssl::sim

BENCHMARK_MAIN();
