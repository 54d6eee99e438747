// ChipEstimator on synthetic chips: exact recovery without noise (one and two cameras, with and without a
// kick prior), accuracy after 10 noisy detections, chip-vs-flat classification, degenerate input, the
// bounce model, and detections made by the simulator's own vision model (sim::VisionModel).
#include "services/world_model/core/chip_estimator.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "services/simulator/core/vision/vision_model.h"

namespace ssl::wm {
namespace {

using namespace std::chrono_literals;

constexpr double kG = 9.81;
constexpr double kRadius = 0.0215;
constexpr double kFramePeriod = 1.0 / 75;
const time::Timestamp kStart = time::Timestamp::from_seconds(1700000000.0);

// Two cameras 4 m above the carpet, as the simulator hangs them over a 2x2 division A layout.
const Vec3 kCameraA(-3.0, -2.25, 4.0);
const Vec3 kCameraB(3.0, -2.25, 4.0);

struct Chip {
  std::string name;
  Vec3 origin;    // z = kRadius
  Vec3 velocity;  // take-off
};

std::vector<Chip> typical_chips() {
  // vxy 2..4 m/s, vz 2..4 m/s, in several directions relative to camera A's nadir.
  return {
      {"away_diagonal", Vec3(-2.0, -1.0, kRadius), Vec3(3.0, 0.5, 3.0)},
      {"across", Vec3(-4.0, -3.0, kRadius), Vec3(2.0, 2.0, 2.5)},
      {"steep_back", Vec3(-1.0, -2.0, kRadius), Vec3(-2.5, 1.5, 4.0)},
      {"flat_lateral", Vec3(-1.5, 0.5, kRadius), Vec3(0.5, -3.5, 2.0)},
      {"long", Vec3(-5.0, -0.5, kRadius), Vec3(4.0, 0.0, 3.0)},
      {"high_diagonal", Vec3(-3.5, -3.5, kRadius), Vec3(2.5, 2.5, 3.5)},
  };
}

ChipBounceModel bounce_model() { return ChipParams{}.bounce; }

// The truth as a ChipFit (its state_at is tested separately against the closed form below).
ChipFit truth_of(const Chip& chip, time::Timestamp t0) {
  ChipFit truth;
  truth.origin = chip.origin;
  truth.velocity = chip.velocity;
  truth.t0 = t0;
  truth.bounce = bounce_model();
  return truth;
}

// Where SSL-Vision (and the simulator, vision_model.cpp detect_ball) reports a ball centred at `ball`: the
// camera ray through the centre meets the plane z = ball radius.
Vec2 project(const Vec3& eye, const Vec3& ball) {
  if (ball.z() <= kRadius) return ball.head<2>();
  const Vec3 on_plane = eye + (ball - eye) * ((eye.z() - kRadius) / (eye.z() - ball.z()));
  return on_plane.head<2>();
}

struct Scenario {
  std::vector<Vec3> cameras;      // frames alternate between them (staggered, each at 75 Hz)
  double noise = 0;               // m per axis
  std::uint32_t seed = 1;
  double first_frame_delay = 0.004;  // s after the kick
};

// Detections of `truth` (including its bounces), in capture order.
std::vector<ChipObservation> observe(const ChipFit& truth, const Scenario& scenario, int count) {
  std::mt19937 rng(scenario.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<ChipObservation> out;
  const double step = kFramePeriod / static_cast<double>(scenario.cameras.size());
  for (int i = 0; i < count; ++i) {
    const Vec3& camera = scenario.cameras[static_cast<std::size_t>(i) % scenario.cameras.size()];
    const time::Timestamp t = truth.t0 + time::duration_from_seconds(scenario.first_frame_delay + i * step);
    Vec2 d = project(camera, truth.position_at(t));
    if (scenario.noise > 0) d += scenario.noise * Vec2(normal(rng), normal(rng));
    out.push_back({d, camera, t});
  }
  return out;
}

double relative_error(const Vec3& estimate, const Vec3& truth) { return (estimate - truth).norm() / truth.norm(); }

Vec2 true_landing(const Chip& chip) {
  return chip.origin.head<2>() + chip.velocity.head<2>() * (2 * chip.velocity.z() / kG);
}

// ---- exact recovery ------------------------------------------------------------------------------------

void expect_exact(const ChipFit& fit, const Chip& chip, time::Timestamp t0) {
  EXPECT_LT(relative_error(fit.velocity, chip.velocity), 1e-6) << fit.velocity.transpose();
  EXPECT_LT((fit.origin - chip.origin).norm(), 1e-6);
  EXPECT_LT((fit.landing_point - true_landing(chip)).norm(), 1e-3);
  EXPECT_LT(std::abs(time::to_seconds(fit.t0 - t0)), 1e-6);
  EXPECT_NEAR(fit.apex_height, kRadius + chip.velocity.z() * chip.velocity.z() / (2 * kG), 1e-6);
  EXPECT_LT(fit.rms_residual_m, 1e-6);
}

TEST(ChipEstimatorTest, NoiseFreeOneCameraRecoversTheFlightExactly) {
  for (const Chip& chip : typical_chips()) {
    SCOPED_TRACE(chip.name);
    const ChipFit truth = truth_of(chip, kStart);
    ChipEstimator estimator;
    estimator.reset(chip.origin.head<2>(), kStart);
    for (const ChipObservation& o : observe(truth, {.cameras = {kCameraA}}, 12)) ASSERT_TRUE(estimator.add(o));
    const std::optional<ChipFit> fit = estimator.fit();
    ASSERT_TRUE(fit.has_value());
    EXPECT_EQ(fit->observations, 12);
    expect_exact(*fit, chip, kStart);
  }
}

TEST(ChipEstimatorTest, NoiseFreeTwoCamerasRecoverTheFlightExactly) {
  for (const Chip& chip : typical_chips()) {
    SCOPED_TRACE(chip.name);
    const ChipFit truth = truth_of(chip, kStart);
    ChipEstimator estimator;
    estimator.reset(chip.origin.head<2>(), kStart);
    for (const ChipObservation& o : observe(truth, {.cameras = {kCameraA, kCameraB}}, 12)) estimator.add(o);
    const std::optional<ChipFit> fit = estimator.fit();
    ASSERT_TRUE(fit.has_value());
    expect_exact(*fit, chip, kStart);
  }
}

TEST(ChipEstimatorTest, NoiseFreeWithoutAKickPriorFindsTheTakeOffTime) {
  // Without a prior, t0 comes from where the fitted parabola leaves the carpet (no search needed).
  for (const Chip& chip : typical_chips()) {
    SCOPED_TRACE(chip.name);
    for (const auto& cameras : {std::vector<Vec3>{kCameraA}, std::vector<Vec3>{kCameraA, kCameraB}}) {
      const ChipFit truth = truth_of(chip, kStart);
      ChipEstimator estimator;
      estimator.reset();
      EXPECT_FALSE(estimator.has_prior());
      for (const ChipObservation& o : observe(truth, {.cameras = cameras, .first_frame_delay = 0.011}, 15)) {
        estimator.add(o);
      }
      const std::optional<ChipFit> fit = estimator.fit();
      ASSERT_TRUE(fit.has_value());
      expect_exact(*fit, chip, kStart);
    }
  }
}

TEST(ChipEstimatorTest, AWrongKickTimeIsCorrectedByTheDetections) {
  // The ball filter reports the kick at the first detection after it (here 12 ms late, 3 cm off); two
  // cameras see the height directly, so the detections overrule the soft prior.
  const Chip chip = typical_chips()[0];
  const ChipFit truth = truth_of(chip, kStart);
  ChipEstimator estimator;
  estimator.reset(chip.origin.head<2>() + Vec2(0.03, 0.0), kStart + 12ms);
  for (const ChipObservation& o : observe(truth, {.cameras = {kCameraA, kCameraB}}, 30)) estimator.add(o);
  const std::optional<ChipFit> fit = estimator.fit();
  ASSERT_TRUE(fit.has_value());
  EXPECT_LT(relative_error(fit->velocity, chip.velocity), 1e-3);
  EXPECT_LT((fit->landing_point - true_landing(chip)).norm(), 0.01);
  EXPECT_LT(std::abs(time::to_seconds(fit->t0 - kStart)), 0.002);
}

TEST(ChipEstimatorTest, DetectionsAfterTheLandingAreLeftOutOfTheFit) {
  // The whole first flight and most of the second hop: the fit is still the first flight, exactly.
  const Chip chip = typical_chips()[0];
  const ChipFit truth = truth_of(chip, kStart);
  const double flight = 2 * chip.velocity.z() / kG;
  const int count = static_cast<int>((flight * 1.4) / kFramePeriod);
  const std::vector<ChipObservation> observations = observe(truth, {.cameras = {kCameraA}}, count);
  ChipEstimator estimator;
  estimator.reset(chip.origin.head<2>(), kStart);
  int airborne = 0;
  for (const ChipObservation& o : observations) {
    estimator.add(o);
    airborne += time::to_seconds(o.t_capture - kStart) < flight;
  }
  ASSERT_LT(airborne, count);
  const std::optional<ChipFit> fit = estimator.fit();
  ASSERT_TRUE(fit.has_value());
  EXPECT_EQ(fit->observations, airborne);
  expect_exact(*fit, chip, kStart);
}

TEST(ChipEstimatorTest, IncrementalAndBatchFitsAgree) {
  // classify() after every detection (cached, warm-started) ends where one fit of them all does.
  for (const Chip& chip : typical_chips()) {
    SCOPED_TRACE(chip.name);
    const ChipFit truth = truth_of(chip, kStart);
    const std::vector<ChipObservation> observations =
        observe(truth, {.cameras = {kCameraA, kCameraB}, .noise = 0.003, .seed = 3}, 40);
    ChipEstimator incremental, batch;
    incremental.reset(observations.front().detection, observations.front().t_capture);
    batch.reset(observations.front().detection, observations.front().t_capture);
    for (const ChipObservation& o : observations) {
      incremental.add(o);
      (void)incremental.classify();
      batch.add(o);
    }
    const std::optional<ChipFit> a = incremental.fit();
    const std::optional<ChipFit> b = batch.fit();
    ASSERT_TRUE(a.has_value());
    ASSERT_TRUE(b.has_value());
    EXPECT_EQ(a->observations, b->observations);
    EXPECT_LT((a->landing_point - b->landing_point).norm(), 1e-6);
    EXPECT_LT((a->velocity - b->velocity).norm(), 1e-6);
    EXPECT_EQ(incremental.is_chip(), batch.is_chip());
  }
}

TEST(ChipEstimatorTest, ANoisierCameraCountsLess) {
  // Per-detection noise: camera B's detections are declared 10x noisier and are 10x noisier.
  const Chip chip = typical_chips()[0];
  const ChipFit truth = truth_of(chip, kStart);
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  ChipEstimator weighted, unweighted;
  weighted.reset(chip.origin.head<2>(), kStart);
  unweighted.reset(chip.origin.head<2>(), kStart);
  for (ChipObservation o : observe(truth, {.cameras = {kCameraA, kCameraB}}, 30)) {
    const bool noisy = o.camera == kCameraB;
    o.detection += (noisy ? 0.03 : 0.003) * Vec2(normal(rng), normal(rng));
    unweighted.add(o);
    o.stddev = noisy ? 0.03 : 0.003;
    weighted.add(o);
  }
  const double err_weighted = (weighted.fit()->landing_point - true_landing(chip)).norm();
  const double err_unweighted = (unweighted.fit()->landing_point - true_landing(chip)).norm();
  EXPECT_LT(err_weighted, err_unweighted);
  EXPECT_NEAR(weighted.fit()->normalised_rms, 1.0, 0.3);
}

// ---- noisy accuracy -------------------------------------------------------------------------------------

// What the estimator is told about the kick.
enum class Prior {
  kBallFilter,           // BallFilter's KickEvent today: its first post-kick detection and capture time
  kBallFilterDirection,  // ... plus the kicker's heading (0.03 rad off)
  kOwnChip,              // ... plus the commanded chip angle (0.03 rad off): one of our robots chipped
};

const char* name_of(Prior prior) {
  switch (prior) {
    case Prior::kBallFilter:
      return "ball-filter kick";
    case Prior::kBallFilterDirection:
      return "ball-filter kick + heading";
    case Prior::kOwnChip:
      return "kick + heading + chip angle";
  }
  return "";
}

ChipKick kick_prior(const Chip& chip, const std::vector<ChipObservation>& observations, Prior prior) {
  ChipKick kick{.position = observations.front().detection, .time = observations.front().t_capture};
  if (prior != Prior::kBallFilter) {
    kick.direction = geom::rotate(chip.velocity.head<2>(), geom::Angle::from_radians(0.03));
  }
  if (prior == Prior::kOwnChip) {
    kick.elevation = std::atan2(chip.velocity.z(), chip.velocity.head<2>().norm()) + 0.03;
  }
  return kick;
}

struct Accuracy {
  double landing_error = 0;   // m
  double speed_error = 0;     // relative, of the 3-D take-off speed
  double landing_stddev = 0;  // m, the fit's own estimate (sqrt of the larger eigenvalue)
};

Accuracy accuracy_after(const Chip& chip, const Scenario& scenario, int detections, Prior prior) {
  const ChipFit truth = truth_of(chip, kStart);
  const std::vector<ChipObservation> observations = observe(truth, scenario, detections);
  ChipEstimator estimator;
  estimator.reset(kick_prior(chip, observations, prior));
  for (const ChipObservation& o : observations) estimator.add(o);
  const std::optional<ChipFit> fit = estimator.fit();
  if (!fit) return {1e9, 1e9, 0};
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(fit->landing_covariance);
  return {(fit->landing_point - true_landing(chip)).norm(),
          std::abs(fit->velocity.norm() - chip.velocity.norm()) / chip.velocity.norm(),
          std::sqrt(std::max(0.0, eigen.eigenvalues()(1)))};
}

struct Summary {
  double landing_rms = 0, landing_worst = 0, speed_rms = 0, speed_worst = 0;
};

// Every typical chip with seeds 1..5, 3 mm noise, 75 Hz per camera, `detections` in all.
Summary summarise(const std::vector<Vec3>& cameras, Prior prior, int detections, bool expect_requirement) {
  Summary s;
  int runs = 0;
  for (const Chip& chip : typical_chips()) {
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
      SCOPED_TRACE(chip.name + " seed " + std::to_string(seed));
      const Accuracy a = accuracy_after(chip, {.cameras = cameras, .noise = 0.003, .seed = seed}, detections, prior);
      if (expect_requirement) {
        EXPECT_LT(a.landing_error, 0.15);
        EXPECT_LT(a.speed_error, 0.10);
      }
      s.landing_worst = std::max(s.landing_worst, a.landing_error);
      s.speed_worst = std::max(s.speed_worst, a.speed_error);
      s.landing_rms += a.landing_error * a.landing_error;
      s.speed_rms += a.speed_error * a.speed_error;
      ++runs;
    }
  }
  s.landing_rms = std::sqrt(s.landing_rms / runs);
  s.speed_rms = std::sqrt(s.speed_rms / runs);
  std::printf("[Chip] %2d detections, 3 mm noise, %zu camera(s), %-26s: landing RMS %.3f m (worst %.3f), "
              "speed RMS %4.1f%% (worst %4.1f%%)\n",
              detections, cameras.size(), name_of(prior), s.landing_rms, s.landing_worst, 100 * s.speed_rms,
              100 * s.speed_worst);
  return s;
}

TEST(ChipEstimatorTest, TenNoisyDetectionsFromTwoCamerasGiveTheLandingPointAndSpeed) {
  for (const Prior prior : {Prior::kBallFilter, Prior::kBallFilterDirection, Prior::kOwnChip}) {
    SCOPED_TRACE(name_of(prior));
    summarise({kCameraA, kCameraB}, prior, 10, true);
  }
}

TEST(ChipEstimatorTest, OneCameraNeedsMoreDetections) {
  // One camera cannot separate the vertical speed from the speed along its ray early in the flight (see
  // the header): after 10 detections the landing point is off by decimetres (the fits' own covariance says
  // so too, MoreDetectionsTightenTheFit); the kick direction and chip angle help. Reported, loosely bounded.
  const Summary blind = summarise({kCameraA}, Prior::kBallFilter, 10, false);
  const Summary heading = summarise({kCameraA}, Prior::kBallFilterDirection, 10, false);
  const Summary own = summarise({kCameraA}, Prior::kOwnChip, 10, false);
  EXPECT_LT(blind.landing_rms, 1.0);
  EXPECT_LT(heading.landing_rms, 0.5);
  EXPECT_LT(own.landing_rms, 0.25);
  EXPECT_LT(own.speed_worst, 0.10);
  // The requirement (landing < 0.15 m, speed < 10 %) holds for one camera from 30 detections (0.4 s) on.
  for (const Prior prior : {Prior::kBallFilter, Prior::kBallFilterDirection, Prior::kOwnChip}) {
    SCOPED_TRACE(name_of(prior));
    summarise({kCameraA}, prior, 30, true);
  }
}

TEST(ChipEstimatorTest, MoreDetectionsTightenTheFit) {
  for (const Prior prior : {Prior::kBallFilter, Prior::kBallFilterDirection, Prior::kOwnChip}) {
    double previous = 1e9;
    for (const int n : {10, 20, 40}) {
      double sum_landing2 = 0, sum_stddev2 = 0;
      int runs = 0;
      for (const Chip& chip : typical_chips()) {
        for (std::uint32_t seed = 1; seed <= 5; ++seed) {
          const Accuracy a = accuracy_after(chip, {.cameras = {kCameraA}, .noise = 0.003, .seed = seed}, n, prior);
          sum_landing2 += a.landing_error * a.landing_error;
          sum_stddev2 += a.landing_stddev * a.landing_stddev;
          ++runs;
        }
      }
      const double rms = std::sqrt(sum_landing2 / runs);
      const double predicted = std::sqrt(sum_stddev2 / runs);
      std::printf("[Chip] %2d detections, 1 camera, %-26s: landing RMS %.3f m, the fits' own stddev %.3f m\n", n,
                  name_of(prior), rms, predicted);
      // The reported uncertainty has the right size, and the error falls.
      EXPECT_LT(rms, 3 * predicted);
      EXPECT_GT(rms, predicted / 3);
      EXPECT_LT(rms, previous);
      previous = rms;
    }
    EXPECT_LT(previous, 0.05);
  }
}

// ---- classification -------------------------------------------------------------------------------------

// A flat kick as the simulator's ball does it: slides at 3 m/s^2 until 5/7 of the kick speed, then rolls.
Vec3 flat_ball_at(const Vec2& origin, const Vec2& velocity, double tau) {
  const double v0 = velocity.norm();
  const Vec2 dir = velocity / v0;
  const double slide = 3.0, roll = 0.35;
  const double t_slide = (v0 - v0 / 1.4) / slide;
  double distance = 0;
  if (tau <= t_slide) {
    distance = v0 * tau - slide * tau * tau / 2;
  } else {
    const double v1 = v0 / 1.4;
    const double tr = std::min(tau - t_slide, v1 / roll);
    distance = v0 * t_slide - slide * t_slide * t_slide / 2 + v1 * tr - roll * tr * tr / 2;
  }
  const Vec2 p = origin + dir * distance;
  return {p.x(), p.y(), kRadius};
}

TEST(ChipClassifyTest, FlatKicksAreNeverChips) {
  const std::vector<std::pair<Vec2, Vec2>> kicks = {
      {Vec2(-2.0, -1.0), Vec2(4.0, 0.5)},   {Vec2(-4.0, -3.0), Vec2(2.0, 2.0)},
      {Vec2(-1.0, -2.0), Vec2(-5.0, 1.0)},  {Vec2(-1.5, 0.5), Vec2(0.5, -3.5)},
      {Vec2(-5.0, -2.25), Vec2(6.5, 0.0)},  {Vec2(-3.0, 1.0), Vec2(0.0, -6.0)},
      {Vec2(-3.0, -2.25), Vec2(1.0, 1.0)},  {Vec2(0.0, 0.0), Vec2(-3.0, -3.0)},
  };
  // 3 mm noise as assumed (ChipParams::detection_stddev), and 5 mm: noisier than assumed.
  double worst_margin = -1e9;
  for (std::size_t k = 0; k < kicks.size(); ++k) {
    for (const auto& cameras : {std::vector<Vec3>{kCameraA}, std::vector<Vec3>{kCameraA, kCameraB}}) {
      for (const bool with_direction : {false, true}) {
        for (std::uint32_t seed = 1; seed <= 6; ++seed) {
          const double noise = seed <= 3 ? 0.003 : 0.005;
          SCOPED_TRACE("kick " + std::to_string(k) + " seed " + std::to_string(seed) + " cameras " +
                       std::to_string(cameras.size()) + (with_direction ? " with direction" : ""));
          std::mt19937 rng(seed);
          std::normal_distribution<double> normal(0.0, noise);
          ChipEstimator estimator;
          const double step = kFramePeriod / static_cast<double>(cameras.size());
          for (int i = 0; i < 60; ++i) {
            const double tau = 0.004 + i * step;
            const Vec3 ball = flat_ball_at(kicks[k].first, kicks[k].second, tau);
            const Vec2 d = ball.head<2>() + Vec2(normal(rng), normal(rng));
            const time::Timestamp t = kStart + time::duration_from_seconds(tau);
            if (i == 0) {
              // As the ball filter would report it: the first detection after the kick.
              ChipKick kick{.position = d, .time = t};
              if (with_direction) kick.direction = kicks[k].second;
              estimator.reset(kick);
            }
            estimator.add({d, cameras[static_cast<std::size_t>(i) % cameras.size()], t});
            const ChipClassification c = estimator.classify();
            EXPECT_FALSE(c.is_chip) << "after " << i + 1 << " detections, margin " << c.chi2_margin << " vz "
                                    << (c.chip ? c.chip->velocity.z() : 0.0);
            worst_margin = std::max(worst_margin, c.chi2_margin);
          }
        }
      }
    }
  }
  std::printf("[Chip] flat kicks (up to 60 detections, 3 and 5 mm noise): largest chi2(flat) - chi2(chip) %.1f "
              "(threshold %.1f, scaled by the fit's noise estimate)\n",
              worst_margin, ChipParams{}.chip_chi2_margin);
}

struct Classified {
  int first = 0;        // detections until classify() first said chip (0: never)
  bool stayed = true;   // from 8 detections after that on
  std::string pattern;  // per detection: '#' chip, '.' not
};

Classified detections_to_classify(const Chip& chip, const Scenario& scenario, Prior prior, int limit) {
  const ChipFit truth = truth_of(chip, kStart);
  const std::vector<ChipObservation> observations = observe(truth, scenario, limit);
  ChipEstimator estimator;
  estimator.reset(kick_prior(chip, observations, prior));
  Classified result;
  for (int i = 0; i < limit; ++i) {
    estimator.add(observations[static_cast<std::size_t>(i)]);
    const bool chip_now = estimator.is_chip();
    result.pattern += chip_now ? '#' : '.';
    if (chip_now && result.first == 0) result.first = i + 1;
    // Near the threshold the decision may flicker (the caller latches it); then it must hold.
    if (!chip_now && result.first != 0 && i + 1 > result.first + 8) result.stayed = false;
  }
  return result;
}

TEST(ChipClassifyTest, TypicalChipsAreChips) {
  // Two cameras: within 8 detections. One camera: later (the projected track of a chip departs from a
  // decelerating straight line only through perspective effects), within 30.
  struct Case {
    std::vector<Vec3> cameras;
    Prior prior;
    int within;
  };
  const std::vector<Case> cases = {{{kCameraA, kCameraB}, Prior::kBallFilter, 8},
                                   {{kCameraA, kCameraB}, Prior::kBallFilterDirection, 8},
                                   {{kCameraA}, Prior::kBallFilter, 30},
                                   {{kCameraA}, Prior::kBallFilterDirection, 30},
                                   {{kCameraA}, Prior::kOwnChip, 30}};
  for (const Case& c : cases) {
    int worst = 0;
    std::vector<int> firsts;
    for (const Chip& chip : typical_chips()) {
      for (std::uint32_t seed = 1; seed <= 5; ++seed) {
        SCOPED_TRACE(chip.name + " seed " + std::to_string(seed) + " cameras " + std::to_string(c.cameras.size()) +
                     " " + name_of(c.prior));
        const Classified r =
            detections_to_classify(chip, {.cameras = c.cameras, .noise = 0.003, .seed = seed}, c.prior, 40);
        EXPECT_GE(r.first, 1) << r.pattern;
        EXPECT_LE(r.first, c.within) << r.pattern;
        EXPECT_TRUE(r.stayed) << r.pattern;
        worst = std::max(worst, r.first == 0 ? 999 : r.first);
        firsts.push_back(r.first);
      }
    }
    std::sort(firsts.begin(), firsts.end());
    std::printf("[Chip] %zu camera(s), %-26s: chips classified after %d detections (median), %d at worst\n",
                c.cameras.size(), name_of(c.prior), firsts[firsts.size() / 2], worst);
  }
}

// ---- degenerate input -----------------------------------------------------------------------------------

TEST(ChipEstimatorTest, DegenerateInputGivesNothingAndNeverCrashes) {
  const Chip chip = typical_chips()[0];
  const ChipFit truth = truth_of(chip, kStart);
  const std::vector<ChipObservation> good = observe(truth, {.cameras = {kCameraA}}, 12);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();

  ChipEstimator estimator;
  EXPECT_FALSE(estimator.fit().has_value());  // nothing at all
  EXPECT_FALSE(estimator.is_chip());
  estimator.reset(chip.origin.head<2>(), kStart);
  for (int i = 0; i < 2; ++i) estimator.add(good[static_cast<std::size_t>(i)]);
  EXPECT_FALSE(estimator.fit().has_value());  // too few
  EXPECT_FALSE(estimator.classify().is_chip);

  // Non-finite values and a camera at the ball's height are refused.
  ChipObservation bad = good[2];
  bad.detection.x() = nan;
  EXPECT_FALSE(estimator.add(bad));
  bad = good[2];
  bad.camera.z() = inf;
  EXPECT_FALSE(estimator.add(bad));
  bad = good[2];
  bad.camera.z() = kRadius;
  EXPECT_FALSE(estimator.add(bad));
  bad = good[2];
  bad.stddev = nan;
  EXPECT_FALSE(estimator.add(bad));
  EXPECT_EQ(estimator.refused(), 4);
  EXPECT_EQ(estimator.size(), 2);
  EXPECT_FALSE(estimator.fit().has_value());

  // Only cameras at the ball's height: nothing is stored, nothing is fitted.
  ChipEstimator low;
  for (ChipObservation o : good) {
    o.camera.z() = kRadius + 0.01;
    EXPECT_FALSE(low.add(o));
  }
  EXPECT_FALSE(low.fit().has_value());

  // A NaN kick prior is no prior.
  ChipEstimator no_prior;
  no_prior.reset(Vec2(nan, 0.0), kStart);
  EXPECT_FALSE(no_prior.has_prior());

  // Every detection at the same instant, without a prior: the motion is undetermined.
  ChipEstimator same_time;
  for (int i = 0; i < 6; ++i) {
    ChipObservation o = good[static_cast<std::size_t>(i)];
    o.t_capture = kStart + 5ms;
    same_time.add(o);
  }
  EXPECT_FALSE(same_time.fit().has_value());
  EXPECT_FALSE(same_time.is_chip());

  // Detections exactly below the camera carry no height: degenerate without a prior.
  ChipEstimator nadir;
  for (int i = 0; i < 6; ++i) {
    nadir.add({kCameraA.head<2>(), kCameraA, kStart + time::duration_from_seconds(0.01 * i)});
  }
  EXPECT_FALSE(nadir.fit().has_value());

  // Garbage that would put the ball at the camera (detections flying off to infinity) is refused or fails.
  ChipEstimator garbage;
  garbage.reset(Vec2(0, 0), kStart);
  for (int i = 0; i < 8; ++i) {
    garbage.add({Vec2(1e150 * (i % 2 ? 1 : -1), 1e150), kCameraA, kStart + time::duration_from_seconds(0.01 * i)});
  }
  const std::optional<ChipFit> g = garbage.fit();
  if (g) {
    EXPECT_TRUE(g->velocity.allFinite());
  }
  (void)garbage.classify();

  // Full: further detections are refused.
  ChipEstimator full;
  for (int i = 0; i < ChipEstimator::kMaxObservations + 5; ++i) {
    full.add({Vec2(0.01 * i, 0), kCameraA, kStart + time::duration_from_seconds(0.001 * i)});
  }
  EXPECT_EQ(full.size(), ChipEstimator::kMaxObservations);
  EXPECT_EQ(full.refused(), 5);
}

// ---- bounces --------------------------------------------------------------------------------------------

TEST(ChipTrajectoryTest, BouncesUseTheRestitutionThenTheBallRolls) {
  ChipFit fit;
  fit.origin = Vec3(1.0, 2.0, kRadius);
  fit.velocity = Vec3(3.0, 0.0, 4.0);
  fit.t0 = kStart;
  fit.bounce = bounce_model();
  const ChipBounceModel& b = fit.bounce;
  const auto at = [&](double tau) { return fit.state_at(kStart + time::duration_from_seconds(tau)); };

  // Before the kick: at the origin, still.
  EXPECT_EQ(at(-0.1).phase, ChipState::Phase::kBeforeKick);
  EXPECT_TRUE(at(-0.1).velocity.isZero());
  EXPECT_TRUE(at(-0.1).position.isApprox(fit.origin));

  // First flight: the closed-form parabola.
  const double t1 = 2 * 4.0 / kG;
  const ChipState mid = at(0.3);
  EXPECT_EQ(mid.phase, ChipState::Phase::kAirborne);
  EXPECT_EQ(mid.hop, 0);
  EXPECT_NEAR(mid.position.x(), 1.0 + 0.9, 1e-12);
  EXPECT_NEAR(mid.position.z(), kRadius + 4.0 * 0.3 - kG / 2 * 0.09, 1e-12);
  EXPECT_NEAR(mid.velocity.z(), 4.0 - kG * 0.3, 1e-12);
  EXPECT_NEAR(at(t1 - 1e-6).position.z(), kRadius, 1e-4);

  // Second hop: vertical speed times damping_z, horizontal times damping_xy_first_hop.
  const double vz1 = 4.0 * b.damping_z;
  const double vx1 = 3.0 * b.damping_xy_first_hop;
  const ChipState after = at(t1 + 1e-4);
  EXPECT_EQ(after.hop, 1);
  EXPECT_NEAR(after.velocity.z(), vz1 - kG * 1e-4, 1e-7);  // t1 rounds to a nanosecond
  EXPECT_NEAR(after.velocity.x(), vx1, 1e-12);
  const double t_apex1 = t1 + vz1 / kG;
  EXPECT_NEAR(at(t_apex1).position.z(), kRadius + vz1 * vz1 / (2 * kG), 1e-9);
  EXPECT_NEAR(at(t_apex1).position.x(), 1.0 + 3.0 * t1 + vx1 * vz1 / kG, 1e-9);

  // Third hop: damping_xy_other_hops.
  const double t2 = t1 + 2 * vz1 / kG;
  const ChipState third = at(t2 + 1e-4);
  EXPECT_EQ(third.hop, 2);
  EXPECT_NEAR(third.velocity.x(), vx1 * b.damping_xy_other_hops, 1e-12);
  EXPECT_NEAR(third.velocity.z(), vz1 * b.damping_z - kG * 1e-4, 1e-7);

  // Continuity of the position across touchdowns; the hops end and the ball rolls, then stops.
  EXPECT_LT((at(t1 - 1e-7).position - at(t1 + 1e-7).position).norm(), 1e-5);
  EXPECT_LT((at(t2 - 1e-7).position - at(t2 + 1e-7).position).norm(), 1e-5);
  const ChipState rolling = at(3.0);
  EXPECT_EQ(rolling.phase, ChipState::Phase::kRolling);
  EXPECT_DOUBLE_EQ(rolling.position.z(), kRadius);
  EXPECT_DOUBLE_EQ(rolling.velocity.z(), 0.0);
  const ChipState later = at(3.5);
  EXPECT_NEAR(rolling.velocity.x() - later.velocity.x(), b.roll_deceleration * 0.5, 1e-9);
  const ChipState stopped = at(60.0);
  EXPECT_EQ(stopped.phase, ChipState::Phase::kStopped);
  EXPECT_TRUE(stopped.velocity.isZero());
  EXPECT_TRUE(at(61.0).position.isApprox(stopped.position));

  // A flight without vertical speed rolls from the start.
  fit.velocity.z() = 0;
  EXPECT_EQ(at(0.1).phase, ChipState::Phase::kRolling);
}

TEST(ChipTrajectoryTest, TheFitPredictsTheSecondHop) {
  const Chip chip = typical_chips()[2];
  const ChipFit truth = truth_of(chip, kStart);
  ChipEstimator estimator;
  estimator.reset(chip.origin.head<2>(), kStart);
  for (const ChipObservation& o : observe(truth, {.cameras = {kCameraA}}, 15)) estimator.add(o);
  const std::optional<ChipFit> fit = estimator.fit();
  ASSERT_TRUE(fit.has_value());
  for (const double tau : {0.2, 0.9, 1.1, 1.5, 2.5}) {
    const time::Timestamp t = kStart + time::duration_from_seconds(tau);
    EXPECT_LT((fit->position_at(t) - truth.position_at(t)).norm(), 1e-6) << tau;
    EXPECT_LT((fit->velocity_at(t) - truth.velocity_at(t)).norm(), 1e-5) << tau;
  }
}

// ---- the simulator's vision model -----------------------------------------------------------------------

struct SimRun {
  std::vector<ChipObservation> observations;
  std::vector<Vec3> camera_positions;
};

// Feeds the chip (and its bounces) to sim::VisionModel as world snapshots every millisecond and turns the
// ball detections of every camera into observations, with the camera centre the geometry publishes.
SimRun observe_with_simulator_vision(const ChipFit& truth, const sim::RealismConfig& realism, double seconds) {
  sim::VisionConfig config;  // 4 cameras, 4 m high, 75 Hz, staggered
  config.realism = realism;
  sim::VisionModel vision(sim::FieldGeometry::division_a(), config, 11);
  SimRun run;
  std::vector<Vec3> believed;
  for (const auto& calibration : vision.geometry().calibrations) believed.push_back(calibration.derived_world);
  for (const sim::CameraView& camera : vision.cameras()) run.camera_positions.push_back(camera.position);
  for (int ms = 0; ms <= static_cast<int>(seconds * 1000); ++ms) {
    sim::WorldSnapshot snapshot;
    snapshot.time = truth.t0 + std::chrono::milliseconds(ms);
    snapshot.ball.position = truth.position_at(snapshot.time);
    snapshot.ball.velocity = truth.velocity_at(snapshot.time);
    for (const sim::DetectionFrame& frame : vision.update(snapshot).frames) {
      for (const sim::BallDetection& ball : frame.balls) {
        if (frame.capture_time <= truth.t0) continue;  // the ball still lying at the kicker
        run.observations.push_back({Vec2(ball.x, ball.y), believed.at(frame.camera_id), frame.capture_time});
      }
    }
  }
  return run;
}

TEST(ChipSimVisionTest, TheSimulatorsProjectionIsTheMeasurementModel) {
  // Perfect simulated vision: the fit is exact. Chips crossing camera boundaries are seen by 1-2 cameras.
  for (const Chip& chip : typical_chips()) {
    SCOPED_TRACE(chip.name);
    const ChipFit truth = truth_of(chip, kStart);
    const double flight = 2 * chip.velocity.z() / kG;
    const SimRun run = observe_with_simulator_vision(truth, sim::RealismConfig::none(), flight - 0.02);
    ASSERT_GE(run.observations.size(), 15u);
    // The replicated projection formula agrees with the simulator's.
    for (const ChipObservation& o : run.observations) {
      EXPECT_LT((project(o.camera, truth.position_at(o.t_capture)) - o.detection).norm(), 1e-9);
    }
    ChipEstimator estimator;
    estimator.reset(chip.origin.head<2>(), kStart);
    for (const ChipObservation& o : run.observations) ASSERT_TRUE(estimator.add(o));
    const std::optional<ChipFit> fit = estimator.fit();
    ASSERT_TRUE(fit.has_value());
    expect_exact(*fit, chip, kStart);
    // Over (almost) the whole flight even a chip flying straight over a camera's nadir is told from a
    // sliding ball.
    EXPECT_TRUE(estimator.is_chip());
  }
}

struct SimFigures {
  double landing = 0;  // m
  double speed = 0;    // relative
  int classified = 0;  // detections until is_chip (0: not within the run)
  int cameras = 0;     // distinct cameras among the detections used
};

SimFigures sim_figures(const Chip& chip, const std::vector<ChipObservation>& observations, int n) {
  SimFigures f;
  ChipEstimator estimator;
  estimator.reset(observations.front().detection, observations.front().t_capture);
  std::vector<double> camera_x;
  for (int i = 0; i < n && i < static_cast<int>(observations.size()); ++i) {
    const ChipObservation& o = observations[static_cast<std::size_t>(i)];
    estimator.add(o);
    if (f.classified == 0 && estimator.is_chip()) f.classified = i + 1;
    if (std::find(camera_x.begin(), camera_x.end(), o.camera.x() * 100 + o.camera.y()) == camera_x.end()) {
      camera_x.push_back(o.camera.x() * 100 + o.camera.y());
    }
  }
  f.cameras = static_cast<int>(camera_x.size());
  const std::optional<ChipFit> fit = estimator.fit();
  if (!fit) return {1e9, 1e9, 0, f.cameras};
  f.landing = (fit->landing_point - true_landing(chip)).norm();
  f.speed = std::abs(fit->velocity.norm() - chip.velocity.norm()) / chip.velocity.norm();
  return f;
}

TEST(ChipSimVisionTest, RealisticVisionOverlapChipsAfterTenDetections) {
  // The "realistic" profile (3 mm noise, 3 % missed balls; no robots, so no occlusion), 4 cameras. Chips
  // along the tile boundaries are seen by two cameras: the requirement after 10 detections.
  const std::vector<Chip> chips = {
      {"centre_line_up", Vec3(0.05, -3.0, kRadius), Vec3(0.2, 3.0, 3.0)},
      {"centre_line_down", Vec3(-0.1, 2.0, kRadius), Vec3(0.25, -2.5, 3.5)},
      {"half_line_right", Vec3(-4.0, 0.1, kRadius), Vec3(3.5, -0.2, 2.5)},
      {"half_line_left", Vec3(3.0, -0.1, kRadius), Vec3(-2.5, 0.3, 2.0)},
  };
  for (const Chip& chip : chips) {
    SCOPED_TRACE(chip.name);
    const SimRun run = observe_with_simulator_vision(truth_of(chip, kStart), sim::RealismConfig::realistic(), 0.2);
    ASSERT_GE(run.observations.size(), 10u);
    const SimFigures f = sim_figures(chip, run.observations, 10);
    std::printf("[Chip] simulator vision (realistic), %-16s 10 detections from %d cameras: landing error %.3f m, "
                "speed error %.1f%%, classified after %d\n",
                chip.name.c_str(), f.cameras, f.landing, 100 * f.speed, f.classified);
    EXPECT_EQ(f.cameras, 2);
    EXPECT_LT(f.landing, 0.15);
    EXPECT_LT(f.speed, 0.10);
    EXPECT_GE(f.classified, 1);
    EXPECT_LE(f.classified, 8);
  }
}

TEST(ChipSimVisionTest, RealisticVisionOneCameraChipsConverge) {
  // Typical chips inside one camera's tile: decimetres after 10 detections, centimetres after 30.
  for (const Chip& chip : typical_chips()) {
    SCOPED_TRACE(chip.name);
    const SimRun run = observe_with_simulator_vision(truth_of(chip, kStart), sim::RealismConfig::realistic(), 0.45);
    ASSERT_GE(run.observations.size(), 30u);
    const SimFigures f10 = sim_figures(chip, run.observations, 10);
    const SimFigures f30 = sim_figures(chip, run.observations, 30);
    std::printf("[Chip] simulator vision (realistic), %-16s %d camera(s): landing error %.3f m after 10, %.3f m after "
                "30; speed error %.1f%% / %.1f%%; classified after %d\n",
                chip.name.c_str(), f30.cameras, f10.landing, f30.landing, 100 * f10.speed, 100 * f30.speed,
                f30.classified);
    EXPECT_LT(f10.landing, 1.0);
    EXPECT_LT(f30.landing, 0.15);
    EXPECT_LT(f30.speed, 0.10);
    EXPECT_GE(f30.classified, 1);
  }
}

}  // namespace
}  // namespace ssl::wm
