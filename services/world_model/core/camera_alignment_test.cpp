// CameraAlignment on a synthetic 2 x 2 camera field: robots drive through the overlaps, each camera reports
// them shifted by its own (known) error field plus Gaussian noise, staggered in time as SSL-Vision's cameras.
#include "services/world_model/core/camera_alignment.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

namespace ssl::wm {
namespace {

using namespace std::chrono_literals;

constexpr double kRate = 75.0;
constexpr int kCameras = 4;

struct CameraTruth {
  Vec2 center = Vec2::Zero();
  Vec2 view_min = Vec2::Zero();
  Vec2 view_max = Vec2::Zero();
  Vec2 t = Vec2::Zero();  // error at the centre
  double s = 0;           // scale about the centre
  double r = 0;           // rotation about the centre

  Vec2 error(const Vec2& p) const {
    const Vec2 l = p - center;
    return t + s * l + r * Vec2(-l.y(), l.x());
  }
  bool sees(const Vec2& p) const {
    return p.x() >= view_min.x() && p.x() <= view_max.x() && p.y() >= view_min.y() && p.y() <= view_max.y();
  }
};

// Division A incl. boundary (12.6 x 9.6 m) in 2 x 2 tiles; camera ids along x first, as the simulator.
std::array<CameraTruth, kCameras> layout(double overlap) {
  std::array<CameraTruth, kCameras> cams;
  for (int i = 0; i < kCameras; ++i) {
    const double sx = (i % 2 == 0) ? -1 : 1;
    const double sy = (i / 2 == 0) ? -1 : 1;
    CameraTruth& c = cams[static_cast<std::size_t>(i)];
    c.center = Vec2(sx * 3.15, sy * 2.4);
    const Vec2 a(sx < 0 ? -6.3 : 0.0, sy < 0 ? -4.8 : 0.0);
    const Vec2 b = a + Vec2(6.3, 4.8);
    c.view_min = a - Vec2(overlap, overlap);
    c.view_max = b + Vec2(overlap, overlap);
  }
  return cams;
}

// Eight robots: four on circles about the field centre, four walking along the two overlap strips.
Vec2 robot_position(int id, double t) {
  switch (id) {
    case 0: return 1.0 * Vec2(std::cos(1.5 * t), std::sin(1.5 * t));
    case 1: return 2.0 * Vec2(std::cos(-0.8 * t + 1), std::sin(-0.8 * t + 1));
    case 2: return 3.5 * Vec2(std::cos(0.45 * t + 2), std::sin(0.45 * t + 2));
    case 3: return Vec2(-4.0 + 0.5 * std::cos(t), 0.1 * std::sin(2 * t));
    case 4: return Vec2(0.1, 4.4 * std::sin(0.35 * t));
    case 5: return Vec2(-0.15 + 0.1 * std::sin(t), -4.0 * std::sin(0.3 * t + 1));
    case 6: return Vec2(5.5 * std::sin(0.25 * t + 0.5), -0.1);
    default: return Vec2(4.5 * std::sin(0.3 * t + 2), 0.2 * std::sin(0.7 * t));
  }
}
constexpr int kRobots = 8;

class SyntheticField {
 public:
  SyntheticField(std::array<CameraTruth, kCameras> cams, double noise, std::uint32_t seed)
      : cams_(cams), noise_(noise), rng_(seed) {}

  std::array<CameraTruth, kCameras>& cameras() { return cams_; }

  /// Runs `seconds` more of 4 staggered cameras at 75 Hz; calls sink(camera, robot, detection, truth, t).
  template <typename Sink>
  void run(double seconds, Sink&& sink) {
    std::normal_distribution<double> n(0.0, noise_);
    const int slots = static_cast<int>(std::lround(seconds * kRate * kCameras));
    for (int k = 0; k < slots; ++k, ++slot_) {
      const int cam = static_cast<int>(slot_ % kCameras);
      const double t = static_cast<double>(slot_) / (kRate * kCameras);
      const time::Timestamp stamp = time::Timestamp::from_seconds(1000.0 + t);
      for (int id = 0; id < kRobots; ++id) {
        const Vec2 truth = robot_position(id, t);
        const CameraTruth& c = cams_[static_cast<std::size_t>(cam)];
        if (!c.sees(truth)) continue;
        const Vec2 detection = truth + c.error(truth) + Vec2(n(rng_), n(rng_));
        sink(static_cast<std::uint32_t>(cam), static_cast<std::uint32_t>(id), detection, truth, stamp);
      }
    }
  }

  void feed(CameraAlignment& align, double seconds) {
    run(seconds, [&](std::uint32_t cam, std::uint32_t id, const Vec2& d, const Vec2&, time::Timestamp t) {
      align.observe(cam, ObjectKey::robot(TeamColor::kBlue, id), d, t);
    });
  }

  time::Timestamp now() const {
    return time::Timestamp::from_seconds(1000.0 + static_cast<double>(slot_) / (kRate * kCameras));
  }

 private:
  std::array<CameraTruth, kCameras> cams_;
  double noise_;
  std::mt19937 rng_;
  std::uint64_t slot_ = 0;
};

void set_centers(CameraAlignment& align, const std::array<CameraTruth, kCameras>& cams) {
  std::vector<CameraInfo> infos;
  for (std::uint32_t i = 0; i < kCameras; ++i) {
    infos.push_back({i, Vec3(cams[i].center.x(), cams[i].center.y(), 4.0)});
  }
  align.set_camera_centers(infos);
}

// Fixed 2 cm errors in four directions (their mean is not zero: the consensus removes it).
std::array<CameraTruth, kCameras> shifted_cameras() {
  auto cams = layout(0.3);
  const std::array<double, kCameras> angles{0.3, 1.9, 3.4, 5.0};
  for (std::size_t i = 0; i < kCameras; ++i) cams[i].t = 0.02 * Vec2(std::cos(angles[i]), std::sin(angles[i]));
  return cams;
}

Vec2 mean_translation(const std::array<CameraTruth, kCameras>& cams) {
  Vec2 mean = Vec2::Zero();
  for (const auto& c : cams) mean += c.t / kCameras;
  return mean;
}

// Largest |estimated - (true - mean)| translation over the cameras.
double worst_translation_error(const CameraAlignment& align, const std::array<CameraTruth, kCameras>& cams) {
  const Vec2 mean = mean_translation(cams);
  double worst = 0;
  for (std::uint32_t i = 0; i < kCameras; ++i) {
    worst = std::max(worst, (align.offset(i).translation - (cams[i].t - mean)).norm());
  }
  return worst;
}

// Largest disagreement of two cameras' corrected noise-free detections over a grid in every overlap.
double worst_overlap_disagreement(const CameraAlignment& align, const std::array<CameraTruth, kCameras>& cams,
                                  bool corrected) {
  double worst = 0;
  for (double x = -6.6; x <= 6.6; x += 0.1) {
    for (double y = -5.1; y <= 5.1; y += 0.1) {
      const Vec2 p(x, y);
      for (std::uint32_t a = 0; a < kCameras; ++a) {
        for (std::uint32_t b = a + 1; b < kCameras; ++b) {
          if (!cams[a].sees(p) || !cams[b].sees(p)) continue;
          Vec2 da = p + cams[a].error(p);
          Vec2 db = p + cams[b].error(p);
          if (corrected) {
            da = align.correct(a, da);
            db = align.correct(b, db);
          }
          worst = std::max(worst, (da - db).norm());
        }
      }
    }
  }
  return worst;
}

TEST(CameraAlignment, TranslationsConvergeToTruthRelativeToTheMean) {
  SyntheticField field(shifted_cameras(), 0.002, 1);
  CameraAlignment align({});
  set_centers(align, field.cameras());
  double converged_at = -1;
  for (int step = 1; step <= 150; ++step) {  // 15 s in 0.1 s steps
    field.feed(align, 0.1);
    const bool all = [&] {
      for (std::uint32_t i = 0; i < kCameras; ++i) {
        if (!align.calibrated(i)) return false;
      }
      return worst_translation_error(align, field.cameras()) < 0.002;
    }();
    if (all && converged_at < 0) converged_at = 0.1 * step;
    if (!all) converged_at = -1;
  }
  const Vec2 mean = mean_translation(field.cameras());
  for (std::uint32_t i = 0; i < kCameras; ++i) {
    const CameraOffset o = align.offset(i);
    const Vec2 truth = field.cameras()[i].t - mean;
    std::printf("[CameraAlignment] camera %u: true %+.2f %+.2f mm, estimated %+.2f %+.2f mm (stddev %.2f mm), "
                "scale %+.1e, rotation %+.1e rad, %llu pairs\n",
                i, truth.x() * 1e3, truth.y() * 1e3, o.translation.x() * 1e3, o.translation.y() * 1e3,
                o.translation_stddev * 1e3, o.scale, o.rotation, static_cast<unsigned long long>(o.pairs));
    EXPECT_TRUE(o.calibrated);
    EXPECT_LT((o.translation - truth).norm(), 0.002);
    EXPECT_LT(o.translation_stddev, 0.002);
    EXPECT_GT(o.translation_stddev, 0.0);
    EXPECT_LT(std::abs(o.scale), 1e-3);
    EXPECT_LT(std::abs(o.rotation), 1e-3);
  }
  const auto& c = align.counters();
  std::printf("[CameraAlignment] within 2 mm (and staying) after %.1f s at 75 Hz x 4 cameras, 2 mm noise; "
              "worst error at 15 s %.2f mm; pairs accepted %llu, rejected %llu\n",
              converged_at, worst_translation_error(align, field.cameras()) * 1e3,
              static_cast<unsigned long long>(c.pairs_accepted), static_cast<unsigned long long>(c.pairs_rejected));
  EXPECT_GT(converged_at, 0);
  EXPECT_LE(converged_at, 5.0);
  EXPECT_EQ(c.camera_restarts, 0u);
  EXPECT_LT(c.pairs_rejected, c.pairs_accepted / 1000 + 1);
}

TEST(CameraAlignment, CorrectedDetectionsOfTwoCamerasAgree) {
  SyntheticField field(shifted_cameras(), 0.002, 2);
  CameraAlignment align({});
  set_centers(align, field.cameras());
  field.feed(align, 10.0);
  const double raw = worst_overlap_disagreement(align, field.cameras(), false);
  const double fixed = worst_overlap_disagreement(align, field.cameras(), true);
  std::printf("[CameraAlignment] worst disagreement in overlaps (noise-free detections): raw %.1f mm, corrected "
              "%.2f mm\n", raw * 1e3, fixed * 1e3);
  EXPECT_GT(raw, 0.02);
  EXPECT_LT(fixed, 0.003);

  // And the noisy detections of one robot by two cameras (interpolated to a common time by the truth):
  // their systematic part agrees; what is left is the noise.
  Vec2 fixed_sum = Vec2::Zero();
  std::array<std::array<Vec2, kRobots>, kCameras> last_err{};
  std::array<std::array<int, kRobots>, kCameras> last_slot{};
  for (auto& row : last_slot) row.fill(-10);
  int slot = 0, n = 0;
  time::Timestamp last_t;
  field.run(3.0, [&](std::uint32_t cam, std::uint32_t id, const Vec2& d, const Vec2& truth, time::Timestamp t) {
    if (t != last_t) ++slot;
    last_t = t;
    align.observe(cam, ObjectKey::robot(TeamColor::kBlue, id), d, t);
    const Vec2 err = align.correct(cam, d) - truth;
    last_err[cam][id] = err;
    last_slot[cam][id] = slot;
    // Camera 0 and 1 share the x = 0 strip: compare errors of frames at most 3 slots apart.
    if (cam == 1 && slot - last_slot[0][id] <= 3) {
      fixed_sum += err - last_err[0][id];
      ++n;
    }
  });
  ASSERT_GT(n, 50);
  std::printf("[CameraAlignment] cameras 0/1, %d near-simultaneous pairs: mean corrected difference %.2f mm\n", n,
              (fixed_sum / n).norm() * 1e3);
  EXPECT_LT((fixed_sum / n).norm(), 0.001);
}

TEST(CameraAlignment, ScaleAndRotationErrorsAreModelled) {
  // Calibration height errors scale a camera's detections about its centre; a yaw error rotates them.
  auto cams = shifted_cameras();
  const std::array<double, kCameras> scales{0.004, -0.003, 0.001, -0.0045};
  const std::array<double, kCameras> rotations{0.002, 0.0, -0.001, 0.0};
  for (std::size_t i = 0; i < kCameras; ++i) {
    cams[i].s = scales[i];
    cams[i].r = rotations[i];
  }
  SyntheticField field(cams, 0.002, 3);
  CameraAlignment align({});
  set_centers(align, field.cameras());
  field.feed(align, 20.0);
  const double raw = worst_overlap_disagreement(align, field.cameras(), false);
  const double fixed = worst_overlap_disagreement(align, field.cameras(), true);
  std::printf("[CameraAlignment] with scale / rotation errors: worst overlap disagreement raw %.1f mm, corrected "
              "%.2f mm\n", raw * 1e3, fixed * 1e3);
  EXPECT_LT(fixed, 0.003);

  // Translation only (no camera centres) cannot explain the scale: worse, but still better than raw.
  CameraAlignmentParams params;
  params.estimate_scale = false;
  params.estimate_rotation = false;
  CameraAlignment translation_only(params);
  SyntheticField again(cams, 0.002, 3);
  again.feed(translation_only, 20.0);
  const double partial = worst_overlap_disagreement(translation_only, again.cameras(), true);
  std::printf("[CameraAlignment] translation-only model: corrected %.2f mm\n", partial * 1e3);
  EXPECT_GT(partial, fixed);
  EXPECT_LT(partial, raw);
}

TEST(CameraAlignment, WorksWithoutCameraCentresForTranslations) {
  SyntheticField field(shifted_cameras(), 0.002, 4);
  CameraAlignment align({});  // no set_camera_centers: translations only
  field.feed(align, 10.0);
  EXPECT_LT(worst_translation_error(align, field.cameras()), 0.002);
  EXPECT_FALSE(align.offset(0).has_center);
  EXPECT_EQ(align.offset(0).scale, 0.0);
}

TEST(CameraAlignment, NoOverlapMeansNoCorrection) {
  auto cams = shifted_cameras();
  for (auto& c : cams) {  // views shrunk to their tiles minus a margin: nothing is seen twice
    const Vec2 mid = 0.5 * (c.view_min + c.view_max);
    c.view_min = mid - Vec2(3.0, 2.2);
    c.view_max = mid + Vec2(3.0, 2.2);
  }
  SyntheticField field(cams, 0.002, 5);
  CameraAlignment align({});
  set_centers(align, cams);
  field.feed(align, 5.0);
  EXPECT_GT(align.counters().observations, 1000u);
  EXPECT_EQ(align.counters().pairs_accepted, 0u);
  for (std::uint32_t i = 0; i < kCameras; ++i) {
    EXPECT_FALSE(align.calibrated(i));
    const Vec2 p(1.0 * i, -2.0);
    EXPECT_EQ(align.correct(i, p), p);
    EXPECT_EQ(align.offset(i).translation, Vec2::Zero());
  }
}

TEST(CameraAlignment, CameraWhoseOffsetJumpsIsReestimated) {
  for (const double jump : {0.015, 0.05}) {  // small: followed by the filter; large: gated, then restarted
    SyntheticField field(shifted_cameras(), 0.002, 6);
    CameraAlignment align({});
    set_centers(align, field.cameras());
    field.feed(align, 8.0);
    ASSERT_LT(worst_translation_error(align, field.cameras()), 0.002);
    field.cameras()[1].t += jump * Vec2(std::cos(4.0), std::sin(4.0));  // camera 1 bumped
    double recovered_at = -1;
    for (int step = 1; step <= 100; ++step) {
      field.feed(align, 0.1);
      const bool ok = align.calibrated(1) && worst_translation_error(align, field.cameras()) < 0.002;
      if (ok && recovered_at < 0) recovered_at = 0.1 * step;
      if (!ok) recovered_at = -1;
    }
    std::printf("[CameraAlignment] camera 1 jumped by %.0f mm: within 2 mm again (and staying) after %.1f s; "
                "restarts %llu\n", jump * 1e3, recovered_at,
                static_cast<unsigned long long>(align.counters().camera_restarts));
    EXPECT_GT(recovered_at, 0);
    EXPECT_LE(recovered_at, 6.0);
    if (jump > 0.03) {
      EXPECT_GE(align.counters().camera_restarts, 1u);
    }
  }
}

TEST(CameraAlignment, SlowDriftIsFollowed) {
  SyntheticField field(shifted_cameras(), 0.002, 7);
  CameraAlignment align({});
  set_centers(align, field.cameras());
  field.feed(align, 5.0);
  double worst = 0;
  for (int step = 0; step < 200; ++step) {  // camera 2 drifts 1 mm/s for 20 s
    field.cameras()[2].t += Vec2(0.0001, 0.0);
    field.feed(align, 0.1);
    if (step > 20) worst = std::max(worst, worst_translation_error(align, field.cameras()));
  }
  std::printf("[CameraAlignment] camera 2 drifting 1 mm/s: worst error while drifting %.2f mm\n", worst * 1e3);
  EXPECT_LT(worst, 0.002);
}

TEST(CameraAlignment, BadInputIsCountedAndIgnored) {
  SyntheticField field(shifted_cameras(), 0.002, 8);
  CameraAlignment align({});
  set_centers(align, field.cameras());
  field.feed(align, 5.0);
  const CameraOffset before = align.offset(0);
  const CameraAlignmentCounters c0 = align.counters();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const time::Timestamp t = field.now();
  align.observe(0, ObjectKey::robot(TeamColor::kBlue, 0), Vec2(nan, 0.0), t);
  align.observe(1, ObjectKey::robot(TeamColor::kBlue, 0), Vec2(0.0, std::numeric_limits<double>::infinity()), t);
  align.observe(9, ObjectKey::robot(TeamColor::kBlue, 0), Vec2(0.0, 0.0), t);
  align.observe(0, ObjectKey::robot(TeamColor::kYellow, 16), Vec2(0.0, 0.0), t);
  align.observe(0, ObjectKey::robot(TeamColor::kBlue, 0), Vec2(0.0, 0.0), t - 10s);  // older than its last
  align.observe(3, ObjectKey::ball(), Vec2(0.1, 0.0), t);
  align.observe(3, ObjectKey::ball(), Vec2(0.5, 0.0), t);  // two balls in one frame
  const CameraAlignmentCounters& c = align.counters();
  EXPECT_EQ(c.non_finite, c0.non_finite + 2);
  EXPECT_EQ(c.ignored_camera, c0.ignored_camera + 1);
  EXPECT_EQ(c.ignored_key, c0.ignored_key + 1);
  EXPECT_EQ(c.out_of_order, c0.out_of_order + 1);
  EXPECT_EQ(c.duplicates, c0.duplicates + 1);
  EXPECT_EQ(c.observations, c0.observations + 7);
  EXPECT_EQ(c.pairs_accepted, c0.pairs_accepted);
  EXPECT_EQ(align.offset(0).translation, before.translation);
  EXPECT_EQ(align.correct(9, Vec2(1, 2)), Vec2(1, 2));
  const Vec2 corrected = align.correct(0, Vec2(nan, 1.0));
  EXPECT_TRUE(std::isnan(corrected.x()));
  EXPECT_TRUE(std::isfinite(align.correct(0, Vec2(1, 1)).x()));
  EXPECT_FALSE(align.offset(9).calibrated);
}

TEST(CameraAlignment, OutOfOrderCamerasAndFastObjects) {
  // Frames of different cameras delivered late relative to each other still pair (b's frame first).
  CameraAlignment align({});
  const auto key = ObjectKey::robot(TeamColor::kYellow, 3);
  const auto at = [](double s) { return time::Timestamp::from_seconds(50.0 + s); };
  align.observe(1, key, Vec2(0.00, 0.0), at(0.000));
  align.observe(1, key, Vec2(0.01, 0.0), at(0.010));
  align.observe(0, key, Vec2(0.005 + 0.02, 0.0), at(0.005));  // between camera 1's two: interpolated
  EXPECT_EQ(align.counters().pairs_accepted, 1u);
  EXPECT_FALSE(align.calibrated(0));  // one pair is not enough (min_pairs)
  EXPECT_EQ(align.correct(0, Vec2(1, 1)), Vec2(1, 1));
  align.observe(0, key, Vec2(5.0, 0.0), at(0.015));  // 500 m/s: not paired
  EXPECT_EQ(align.counters().pairs_too_fast, 1u);
  align.reset();
  EXPECT_EQ(align.counters().observations, 0u);
}

TEST(CameraAlignment, RecalibratedCameraRestarts) {
  SyntheticField field(shifted_cameras(), 0.002, 9);
  CameraAlignment align({});
  set_centers(align, field.cameras());
  field.feed(align, 5.0);
  ASSERT_TRUE(align.calibrated(2));
  align.set_camera_center(2, field.cameras()[2].center);  // same centre (geometry resent): nothing
  EXPECT_TRUE(align.calibrated(2));
  align.set_camera_center(2, field.cameras()[2].center + Vec2(0.05, 0));  // moved: restart
  EXPECT_FALSE(align.calibrated(2));
  EXPECT_EQ(align.counters().camera_restarts, 1u);
}

}  // namespace
}  // namespace ssl::wm
