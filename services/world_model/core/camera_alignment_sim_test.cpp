// CameraAlignment against the real simulator core (competition vision: 2 cm camera calibration errors, 4 mm
// robot noise, missed detections, staggered cameras). Robots of both teams drive nested ellipses about the
// field centre, crossing both overlap strips of the 2 x 2 cameras. The truth of each camera's error field is
// known from the simulator: it reports points computed from where it BELIEVES the camera hangs (the
// published calibration's derived_world) instead of where it really hangs (make_camera_layout).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "services/simulator/core/vision/camera.h"
#include "services/world_model/core/camera_alignment.h"
#include "services/world_model/core/sim_harness.h"

namespace ssl::wm {
namespace {

using namespace std::chrono_literals;
using testing::SimHarness;

constexpr int kRobotsPerTeam = 6;

struct Ellipse {
  double a = 1, b = 1, omega = 0, phase = 0;
  Vec2 at(double t) const { return {a * std::cos(omega * t + phase), b * std::sin(omega * t + phase)}; }
  Vec2 velocity(double t) const {
    return {-a * omega * std::sin(omega * t + phase), b * omega * std::cos(omega * t + phase)};
  }
};

Ellipse path(int index) {  // 12 nested ellipses 0.34 m apart, alternating directions, ~1.2 m/s
  const double a = 0.6 + 0.45 * index;
  const double omega = (index % 2 == 0 ? 1 : -1) * 1.2 / (0.87 * a);
  return {a, 0.75 * a, omega, 1.3 * index};
}

int robot_index(TeamColor team, std::uint32_t id) {
  return 2 * static_cast<int>(id) + (team == TeamColor::kYellow ? 1 : 0);
}

// Where the simulated vision reports a point at height h that camera `real` sees, believing it at `believed`.
struct TrueCamera {
  sim::CameraView view;
  Vec3 believed = Vec3::Zero();
  Vec2 error(const Vec2& p, double h) const {
    const Vec3& real = view.position;
    const double k = (believed.z() - h) / (real.z() - h);
    const Vec3 reported = believed + (Vec3(p.x(), p.y(), h) - real) * k;
    return Vec2(reported.x(), reported.y()) - p;
  }
};

TEST(CameraAlignmentSim, ReducesDisagreementBetweenCamerasInOverlapsUnderCompetitionVision) {
  SimHarness h({.robots_per_team = kRobotsPerTeam, .realism = sim::RealismConfig::competition(), .seed = 4});
  const double robot_height = sim::RobotSpec{}.height;

  // Truth: real camera positions vs the published (believed) ones.
  const std::vector<sim::CameraView> views = sim::make_camera_layout(h.sim().options().field,
                                                                     h.sim().options().vision);
  std::vector<TrueCamera> cameras;
  for (const auto& v : views) {
    TrueCamera c{v, Vec3::Zero()};
    for (const auto& cal : h.sim().geometry().calibrations) {
      if (cal.camera_id == v.camera_id) c.believed = cal.derived_world;
    }
    ASSERT_GT((c.believed - v.position).norm(), 0.0);
    cameras.push_back(c);
  }

  CameraAlignment align({});
  align.set_camera_centers(testing::from_sim(h.sim().geometry()).cameras);

  // Start every robot on its ellipse, then follow it (global velocity + position feedback).
  sim::ControlRequest place;
  for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
    for (std::uint32_t id = 0; id < kRobotsPerTeam; ++id) {
      const Ellipse e = path(robot_index(team, id));
      const Vec2 p = e.at(0), v = e.velocity(0);
      place.robots.push_back({.key = {team, id}, .x = p.x(), .y = p.y(), .orientation = 0.0, .vx = v.x(),
                              .vy = v.y(), .angular = 0.0});
    }
  }
  sim::BallTeleport ball;
  ball.x = 0.0;
  ball.y = 5.5;  // off the field, out of the robots' way
  place.ball = ball;
  ASSERT_TRUE(h.sim().apply(place).empty());

  const time::Timestamp start = h.now();
  time::Timestamp next_command;
  auto drive = [&](SimHarness& harness) {
    if (harness.now() < next_command) return;
    next_command = harness.now() + 10ms;
    const double t = time::to_seconds(harness.now() - start);
    const sim::WorldSnapshot world = harness.sim().snapshot();
    for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
      std::vector<sim::RobotCommandFor> commands;
      for (const auto& r : world.robots) {
        if (r.key.team != team) continue;
        const Ellipse e = path(robot_index(team, r.key.id));
        const Vec2 v = e.velocity(t + 0.05) + 2.0 * (e.at(t + 0.05) - r.position);
        sim::RobotCommand c;
        c.move = sim::RobotCommand::Move::kGlobalVelocity;
        c.velocity = sim::Vec3(v.x(), v.y(), 0.0);
        commands.push_back({r.key.id, c});
      }
      harness.command(team, commands, false);
    }
  };

  // Per (camera, 0.5 m cell): mean raw and corrected error (detection - truth) over the measurement window.
  struct Mean {
    Vec2 raw = Vec2::Zero(), fixed = Vec2::Zero();
    int n = 0;
  };
  std::map<std::tuple<std::uint32_t, int, int>, Mean> cells;
  constexpr double kWarmup = 10.0, kDuration = 30.0;
  h.run(std::chrono::seconds(static_cast<int>(kDuration)), drive, [&](const sim::DetectionFrame& frame) {
    const sim::WorldSnapshot& truth = h.truth(frame.capture_time);
    const bool measure = time::to_seconds(frame.capture_time - start) >= kWarmup;
    for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
      for (const auto& d : team == TeamColor::kBlue ? frame.robots_blue : frame.robots_yellow) {
        const Vec2 position(d.x, d.y);
        align.observe(frame.camera_id, ObjectKey::robot(team, d.robot_id), position, frame.capture_time);
        if (!measure) continue;
        for (const auto& r : truth.robots) {
          if (r.key.team != team || r.key.id != d.robot_id) continue;
          Mean& m = cells[{frame.camera_id, static_cast<int>(std::floor(r.position.x() / 0.5)),
                           static_cast<int>(std::floor(r.position.y() / 0.5))}];
          m.raw += position - r.position;
          m.fixed += align.correct(frame.camera_id, position) - r.position;
          ++m.n;
        }
      }
    }
  });

  // Empirical: cameras' mean errors in the same cell, compared pairwise.
  double raw_sq = 0, fixed_sq = 0;
  int compared = 0;
  for (const auto& [key_a, a] : cells) {
    for (const auto& [key_b, b] : cells) {
      const auto [cam_a, xa, ya] = key_a;
      const auto [cam_b, xb, yb] = key_b;
      if (cam_a >= cam_b || xa != xb || ya != yb || a.n < 30 || b.n < 30) continue;
      raw_sq += (a.raw / a.n - b.raw / b.n).squaredNorm();
      fixed_sq += (a.fixed / a.n - b.fixed / b.n).squaredNorm();
      ++compared;
    }
  }
  ASSERT_GT(compared, 20);
  const double raw_rms = std::sqrt(raw_sq / compared), fixed_rms = std::sqrt(fixed_sq / compared);

  // Against the simulator's true error fields: noise-free points on a grid in every overlap.
  double model_raw_sq = 0, model_fixed_sq = 0, model_fixed_worst = 0;
  int points = 0;
  for (double x = -6.6; x <= 6.6; x += 0.1) {
    for (double y = -5.1; y <= 5.1; y += 0.1) {
      const Vec2 p(x, y);
      for (std::size_t i = 0; i < cameras.size(); ++i) {
        for (std::size_t j = i + 1; j < cameras.size(); ++j) {
          if (!cameras[i].view.view.contains(p) || !cameras[j].view.view.contains(p)) continue;
          const Vec2 di = p + cameras[i].error(p, robot_height);
          const Vec2 dj = p + cameras[j].error(p, robot_height);
          const std::uint32_t ci = cameras[i].view.camera_id, cj = cameras[j].view.camera_id;
          model_raw_sq += (di - dj).squaredNorm();
          const double fixed = (align.correct(ci, di) - align.correct(cj, dj)).norm();
          model_fixed_sq += fixed * fixed;
          model_fixed_worst = std::max(model_fixed_worst, fixed);
          ++points;
        }
      }
    }
  }
  const double model_raw = std::sqrt(model_raw_sq / points), model_fixed = std::sqrt(model_fixed_sq / points);

  // The truth in the consensus frame: subtract the common similarity with the mean scale and the mean
  // translation at the centres (no rotation in the simulator's error model).
  double mean_s = 0;
  Vec2 mean_t = Vec2::Zero(), mean_c = Vec2::Zero();
  std::vector<std::pair<Vec2, double>> truth_fields;  // (error at centre, scale)
  for (const TrueCamera& c : cameras) {
    const Vec2 centre(c.believed.x(), c.believed.y());
    const double s = (c.believed.z() - robot_height) / (c.view.position.z() - robot_height) - 1;
    truth_fields.emplace_back(c.error(centre, robot_height), s);
    mean_s += s / static_cast<double>(cameras.size());
    mean_t += truth_fields.back().first / static_cast<double>(cameras.size());
    mean_c += centre / static_cast<double>(cameras.size());
  }
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const TrueCamera& c = cameras[i];
    const CameraOffset o = align.offset(c.view.camera_id);
    const Vec2 centre(c.believed.x(), c.believed.y());
    const Vec2 t_rel = truth_fields[i].first - mean_t - mean_s * (centre - mean_c);
    const double s_rel = truth_fields[i].second - mean_s;
    std::printf("[CameraAlignmentSim] camera %u (calibration off by %.1f mm): true vs consensus: %+.1f %+.1f mm, "
                "scale %+.2e; estimated %+.1f %+.1f mm +- %.2f mm, scale %+.2e +- %.1e, rotation %+.1e; %llu pairs\n",
                c.view.camera_id, (c.believed - c.view.position).norm() * 1e3, t_rel.x() * 1e3, t_rel.y() * 1e3,
                s_rel, o.translation.x() * 1e3, o.translation.y() * 1e3, o.translation_stddev * 1e3, o.scale,
                o.scale_stddev, o.rotation, static_cast<unsigned long long>(o.pairs));
    EXPECT_TRUE(o.calibrated);
    EXPECT_LT((o.translation - t_rel).norm(), 0.003);
    EXPECT_LT(std::abs(o.scale - s_rel), 5e-4);
  }
  const auto& k = align.counters();
  std::printf("[CameraAlignmentSim] competition vision, 12 robots, %.0f s (measured after %.0f s): overlap "
              "disagreement of cameras' mean errors per 0.5 m cell (%d cell pairs) raw %.2f mm RMS, corrected "
              "%.2f mm (%.0f%% lower); true error fields on the overlap grid (%d points) raw %.2f mm RMS, "
              "corrected %.2f mm RMS (%.0f%% lower), worst %.2f mm; pairs accepted %llu, rejected %llu, too "
              "fast %llu, restarts %llu\n",
              kDuration, kWarmup, compared, raw_rms * 1e3, fixed_rms * 1e3, 100 * (1 - fixed_rms / raw_rms),
              points, model_raw * 1e3, model_fixed * 1e3, 100 * (1 - model_fixed / model_raw),
              model_fixed_worst * 1e3, static_cast<unsigned long long>(k.pairs_accepted),
              static_cast<unsigned long long>(k.pairs_rejected), static_cast<unsigned long long>(k.pairs_too_fast),
              static_cast<unsigned long long>(k.camera_restarts));
  EXPECT_GT(raw_rms, 0.005);  // the calibration errors are really there
  EXPECT_LE(fixed_rms, 0.3 * raw_rms);
  EXPECT_LE(model_fixed, 0.3 * model_raw);
  EXPECT_EQ(k.camera_restarts, 0u);
}

}  // namespace
}  // namespace ssl::wm
