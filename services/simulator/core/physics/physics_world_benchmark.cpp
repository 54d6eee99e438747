// Speed of the physics core: an 11 v 11 match on a Division A field, every robot driving a velocity
// command that changes every few frames, dribbling and kicking now and then, and a moving ball. One
// iteration = one vision frame: 1/75 s of simulated time plus a snapshot. The counter `rtf` is the
// real-time factor (simulated seconds per wall-clock second); physics is one part of the whole simulator's
// budgeted real-time factor (bench/simulator_realtime_factor). The argument is the sub-step in microseconds (PhysicsParams::step).
//
//   ./build/bench/simulator_physics_benchmark --benchmark_filter=Match
#include <benchmark/benchmark.h>
#include <time.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "services/simulator/core/physics/physics_world.h"

namespace ssl::sim {
namespace {

constexpr auto kFrame = std::chrono::nanoseconds(13'333'333);  // 75 Hz vision

// CPU time of this thread, s: on a shared machine the wall-clock rate also counts time spent waiting for
// the CPU, so both counters are reported (they agree on an idle core).
double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
}

void report_rates(benchmark::State& state, double cpu_seconds) {
  const double simulated =
      static_cast<double>(state.iterations()) * std::chrono::duration<double>(kFrame).count();
  state.counters["rtf"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
  state.counters["rtf_cpu"] = simulated / cpu_seconds;
}

void add_teams(PhysicsWorld& world) {
  for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
    const double side = team == TeamColor::kBlue ? -1.0 : 1.0;
    for (std::uint32_t id = 0; id < 11; ++id) {
      world.add_robot({team, id}, Vec2(side * (0.5 + 0.45 * id), -4.0 + 0.8 * id),
                      side > 0 ? std::numbers::pi : 0.0);
    }
  }
}

// Deterministic, varied commands: each robot circles with its own phase, changing every 10 frames.
void command_robots(PhysicsWorld& world, long frame) {
  const double t = static_cast<double>(frame) * 0.0133;
  for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
    for (std::uint32_t id = 0; id < 11; ++id) {
      const double phase = 0.7 * id + (team == TeamColor::kBlue ? 0.0 : 2.0);
      RobotCommand command;
      command.move = RobotCommand::Move::kGlobalVelocity;
      command.velocity =
          Vec3(2.0 * std::cos(0.8 * t + phase), 2.0 * std::sin(1.1 * t + phase), std::sin(t + phase));
      command.dribbler_rpm = id % 2 == 0 ? 3000 : 0;
      command.kick_speed = id % 3 == 0 ? 4.0 : 0.0;
      command.kick_angle = id % 6 == 0 ? 0.5 : 0.0;
      world.set_command({team, id}, command);
    }
  }
}

void BM_Match11v11(benchmark::State& state) {
  PhysicsParams params;
  params.step = static_cast<double>(state.range(0)) * 1e-6;
  PhysicsWorld world(FieldGeometry::division_a(), params);
  add_teams(world);
  world.teleport_ball(Vec3(0, 0, params.ball_radius), Vec3(3.0, 1.0, 0));
  long frame = 0;
  double ball_speed_sum = 0;
  const double cpu_start = thread_cpu_seconds();
  for (auto _ : state) {
    if (frame % 10 == 0) command_robots(world, frame);
    if (frame % 150 == 0) {  // keep the ball moving: a new pass every 2 s
      const double a = 0.9 * static_cast<double>(frame / 150);
      world.teleport_ball(world.snapshot().ball.position, Vec3(4.0 * std::cos(a), 4.0 * std::sin(a), 0));
    }
    world.step(kFrame);
    const WorldSnapshot snapshot = world.snapshot();
    ball_speed_sum += snapshot.ball.velocity.norm();
    benchmark::DoNotOptimize(snapshot);
    ++frame;
  }
  report_rates(state, thread_cpu_seconds() - cpu_start);
  state.counters["ball_speed"] = ball_speed_sum / static_cast<double>(state.iterations());
}
BENCHMARK(BM_Match11v11)->Arg(1000)->Arg(2000)->Arg(4000)->UseRealTime()->Unit(benchmark::kMicrosecond);

// The ball alone on the field: the floor of what a sub-step costs.
void BM_BallOnly(benchmark::State& state) {
  PhysicsParams params;
  params.step = static_cast<double>(state.range(0)) * 1e-6;
  PhysicsWorld world(FieldGeometry::division_a(), params);
  world.teleport_ball(Vec3(0, 0, params.ball_radius), Vec3(3.0, 1.0, 0));
  const double cpu_start = thread_cpu_seconds();
  for (auto _ : state) {
    world.step(kFrame);
    benchmark::DoNotOptimize(world.snapshot());
  }
  report_rates(state, thread_cpu_seconds() - cpu_start);
}
BENCHMARK(BM_BallOnly)->Arg(2000)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace ssl::sim

BENCHMARK_MAIN();
