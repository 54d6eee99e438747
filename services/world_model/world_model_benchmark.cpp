// world_model benchmark (./ssl bench): microseconds per camera frame with 22 robots and the ball, on frames
// recorded from the in-process simulator (Division A, 4 cameras, realistic vision), and the error figures
// (filtered vs raw position RMS at capture time) of both teams and the ball, printed for vision as the
// config assumes and for vision it is not tuned to (budgets: bench/budget_table.cpp).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>

#include "services/world_model/core/sim_harness.h"

namespace ssl::wm {
namespace {

using namespace std::chrono_literals;

struct Recording {
  std::vector<DetectionFrame> frames;
  double raw_rms = 0, filtered_rms = 0;              // our robots (commands known)
  double enemy_raw_rms = 0, enemy_filtered_rms = 0;  // the opponents (no commands)
  double ball_raw_rms = 0, ball_filtered_rms = 0;
};

/// The vision the recording's simulator produces and what the model is told of the ball.
struct Scenario {
  sim::RealismConfig realism = sim::RealismConfig::realistic();
  double ball_deceleration_told = 1;  // the model's ball model (geometry) = the simulator's times this
};

/// What the world model's config assumes: the realistic profile (world_model.yaml's noise, the geometry's
/// ball model).
Scenario matched() { return {}; }

/// Vision the model is not tuned to: twice the detection noise, twice the delay with more jitter (still
/// below a frame period, so each camera's frames stay in order), and a ball model in the geometry whose
/// decelerations are 40 % below the simulator's (a carpet slower than calibrated).
Scenario mismatched() {
  Scenario s;
  s.realism.robot_position_stddev *= 2;
  s.realism.robot_orientation_stddev *= 2;
  s.realism.ball_position_stddev *= 2;
  s.realism.vision_delay = 0.025;
  s.realism.processing_time_jitter = 0.008;
  s.ball_deceleration_told = 0.6;
  return s;
}

// 11 v 11 driving curves for 4 s, the ball rolling among them; records every frame and the RMS of both
// teams' robots and of the ball, raw vs filtered, at each frame's capture time (after the first second).
Recording record(const Scenario& scenario) {
  Recording r;
  testing::SimHarness h({.robots_per_team = 11, .realism = scenario.realism, .seed = 21});
  Geometry told = testing::from_sim(h.sim().geometry());
  if (told.ball_model) {
    told.ball_model->acc_slide *= scenario.ball_deceleration_told;
    told.ball_model->acc_roll *= scenario.ball_deceleration_told;
  }
  h.model().on_geometry(told);
  sim::ControlRequest ball;
  ball.ball = sim::BallTeleport{.x = -1.0, .y = 0.5, .vx = 2.0, .vy = 0.3};
  h.sim().apply(ball);
  testing::Rms raw[2], filtered[2];  // [0]: ours (blue), [1]: opponents (yellow)
  testing::Rms ball_raw, ball_filtered;
  time::Timestamp next;
  const time::Timestamp start = h.now();
  h.run(
      4s,
      [&](testing::SimHarness& harness) {
        if (harness.now() < next) return;
        next = harness.now() + 10ms;
        const double t = time::to_seconds(harness.now() - start);
        for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
          std::vector<sim::RobotCommandFor> commands;
          for (std::uint32_t id = 0; id < 11; ++id) {
            commands.push_back({id, testing::curve_command(t, id + 0.5 * (team == TeamColor::kYellow))});
          }
          harness.command(team, commands, team == TeamColor::kBlue);
        }
      },
      [&](const sim::DetectionFrame& frame) {
        r.frames.push_back(testing::from_sim(frame));
        if (time::to_seconds(frame.capture_time - start) < 1.0) return;
        const WorldState world = h.model().state_at_vision_time(frame.capture_time);
        const sim::WorldSnapshot& truth = h.truth(frame.capture_time);
        for (const int side : {0, 1}) {
          const TeamColor team = side == 0 ? TeamColor::kBlue : TeamColor::kYellow;
          for (const auto& d : side == 0 ? frame.robots_blue : frame.robots_yellow) {
            for (const auto& s : side == 0 ? world.friendly : world.enemy) {
              if (s.id != d.robot_id) continue;
              for (const auto& t : truth.robots) {
                if (t.key.team != team || t.key.id != d.robot_id) continue;
                raw[side].add((Vec2(d.x, d.y) - t.position).norm());
                filtered[side].add((s.position - t.position).norm());
              }
            }
          }
        }
        if (frame.balls.size() == 1 && world.has_ball) {
          const Vec2 true_ball = truth.ball.position.head<2>();
          ball_raw.add((Vec2(frame.balls[0].x, frame.balls[0].y) - true_ball).norm());
          ball_filtered.add((world.ball.position.head<2>() - true_ball).norm());
        }
      });
  r.raw_rms = raw[0].value();
  r.filtered_rms = filtered[0].value();
  r.enemy_raw_rms = raw[1].value();
  r.enemy_filtered_rms = filtered[1].value();
  r.ball_raw_rms = ball_raw.value();
  r.ball_filtered_rms = ball_filtered.value();
  return r;
}

const Recording& recording() {
  static const Recording rec = record(matched());
  return rec;
}

double reduction_pct(double raw, double filtered) { return 100 * (1 - filtered / raw); }

/// The error figures of one scenario, and the BUDGET lines of the robots' (bench/budget_table.cpp).
void print_errors(const char* title, const Recording& r, const char* budget_suffix) {
  std::printf("world_model error, %s (11 v 11 on curves, position RMS at capture time, raw -> filtered):\n"
              "  our robots (commands as input) %.2f -> %.2f mm (%.0f%% lower); opponents (no commands) %.2f -> "
              "%.2f mm (%.0f%% lower); ball %.2f -> %.2f mm (%.0f%% lower)\n",
              title, r.raw_rms * 1e3, r.filtered_rms * 1e3, reduction_pct(r.raw_rms, r.filtered_rms),
              r.enemy_raw_rms * 1e3, r.enemy_filtered_rms * 1e3, reduction_pct(r.enemy_raw_rms, r.enemy_filtered_rms),
              r.ball_raw_rms * 1e3, r.ball_filtered_rms * 1e3, reduction_pct(r.ball_raw_rms, r.ball_filtered_rms));
  std::printf("BUDGET world_model_error_reduction_ours%s_pct %.1f\n", budget_suffix,
              reduction_pct(r.raw_rms, r.filtered_rms));
  std::printf("BUDGET world_model_error_reduction_opponents%s_pct %.1f\n", budget_suffix,
              reduction_pct(r.enemy_raw_rms, r.enemy_filtered_rms));
}

void BM_WorldModelPerCameraFrame22Robots(benchmark::State& state) {
  const Recording& rec = recording();
  WorldModel model({.team = TeamColor::kBlue});
  std::size_t i = 0;
  std::size_t robots = 0;
  for (auto _ : state) {
    if (i == rec.frames.size()) {
      state.PauseTiming();
      model = WorldModel({.team = TeamColor::kBlue});
      i = 0;
      state.ResumeTiming();
    }
    const DetectionFrame& frame = rec.frames[i++];
    model.on_detection(frame, frame.sent_time);
    robots += frame.robots_blue.size() + frame.robots_yellow.size();
  }
  state.counters["robots_per_frame"] = static_cast<double>(robots) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_WorldModelPerCameraFrame22Robots)->Unit(benchmark::kMicrosecond);

// One camera seeing all 22 robots and the ball (worst case of one frame), plus state() for publishing.
void BM_WorldModelFrameWithAll22RobotsPlusState(benchmark::State& state) {
  const Recording& rec = recording();
  // Merge the four cameras' frames of one instant into one frame of 22 robots.
  std::vector<DetectionFrame> merged;
  for (std::size_t i = 0; i + 4 <= rec.frames.size(); i += 4) {
    DetectionFrame f = rec.frames[i + 3];
    for (std::size_t k = 0; k < 3; ++k) {
      const auto& o = rec.frames[i + k];
      f.robots_blue.insert(f.robots_blue.end(), o.robots_blue.begin(), o.robots_blue.end());
      f.robots_yellow.insert(f.robots_yellow.end(), o.robots_yellow.begin(), o.robots_yellow.end());
      f.balls.insert(f.balls.end(), o.balls.begin(), o.balls.end());
    }
    merged.push_back(std::move(f));
  }
  WorldModel model({.team = TeamColor::kBlue});
  std::size_t i = 0;
  for (auto _ : state) {
    if (i == merged.size()) {
      state.PauseTiming();
      model = WorldModel({.team = TeamColor::kBlue});
      i = 0;
      state.ResumeTiming();
    }
    const DetectionFrame& frame = merged[i++];
    model.on_detection(frame, frame.sent_time);
    benchmark::DoNotOptimize(model.state(frame.sent_time));
  }
}
BENCHMARK(BM_WorldModelFrameWithAll22RobotsPlusState)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace ssl::wm

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  ssl::wm::print_errors("vision as the config assumes (realistic profile)", ssl::wm::recording(), "");
  ssl::wm::print_errors("vision it is not tuned to (noise x2, delay 25 ms + 8 ms jitter, the geometry's ball model "
                        "decelerating 40 % less than the ball)",
                        ssl::wm::record(ssl::wm::mismatched()), "_mismatched");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
