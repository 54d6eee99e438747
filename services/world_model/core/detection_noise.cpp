#include "services/world_model/core/detection_noise.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "libs/geometry/angle.h"

namespace ssl::wm {
namespace {

// E|u| = sigma sqrt(2 / pi) for u ~ N(0, sigma^2).
const double kSigmaPerMeanAbs = std::sqrt(std::numbers::pi / 2);

double wrap(double radians) { return geom::Angle::from_radians(radians).radians(); }

}  // namespace

double DetectionNoiseEstimator::Average::sigma(double fallback) const {
  return weight > 0 ? weighted_sum / weight * kSigmaPerMeanAbs : fallback;
}

void DetectionNoiseEstimator::Average::add(double normalised, double memory, double clip_sigmas,
                                           double fallback) {
  const double clipped = std::min(std::abs(normalised), clip_sigmas * sigma(fallback));
  weighted_sum = memory * weighted_sum + clipped;
  weight = memory * weight + 1;
  ++samples;
}

DetectionNoiseEstimator::DetectionNoiseEstimator(const DetectionNoiseParams& params,
                                                 const DetectionNoise& configured)
    : params_(params), configured_(configured) {}

void DetectionNoiseEstimator::observe(std::uint32_t camera_id, TeamColor team, const RobotDetection& detection,
                                      time::Timestamp t) {
  if (!params_.estimate || detection.id >= kMaxRobotsPerTeam) return;
  Camera& cam = cameras_[camera_id];
  History& history = cam.robots[(team == TeamColor::kBlue ? 0 : kMaxRobotsPerTeam) + detection.id];
  const Sample now{t, detection.position, detection.orientation, detection.has_orientation};
  if (history.count > 0 && t <= history.samples[1].t) {
    history.count = 0;  // a camera's frames come in order: a restart (or a repeated frame) starts over
  }
  if (history.count >= 2) {
    const Sample& first = history.samples[0];
    const Sample& middle = history.samples[1];
    const double span = time::to_seconds(t - first.t);
    if (span <= params_.max_span) {
      const double f = time::to_seconds(middle.t - first.t) / span;
      const double scale = 1 / std::sqrt(1 + (1 - f) * (1 - f) + f * f);
      const Vec2 r = middle.position - ((1 - f) * first.position + f * now.position);
      const double configured = configured_.position_stddev;
      cam.position.add(scale * r.x(), params_.memory, params_.clip_sigmas, configured);
      cam.position.add(scale * r.y(), params_.memory, params_.clip_sigmas, configured);
      if (first.has_orientation && middle.has_orientation && now.has_orientation) {
        const double line = first.orientation + f * wrap(now.orientation - first.orientation);
        cam.orientation.add(scale * wrap(middle.orientation - line), params_.memory, params_.clip_sigmas,
                            configured_.orientation_stddev);
      }
    }
  }
  history.samples[0] = history.samples[1];
  history.samples[1] = now;
  history.count = std::min<std::uint32_t>(history.count + 1, 2);
}

DetectionNoise DetectionNoiseEstimator::noise(std::uint32_t camera_id) const {
  if (!params_.estimate) return configured_;
  const auto it = cameras_.find(camera_id);
  if (it == cameras_.end()) return configured_;
  // Two position samples (x and y) per residual.
  auto bounded = [&](const Average& average, std::uint64_t needed, double configured) {
    if (average.samples < needed) return configured;
    return std::clamp(average.sigma(configured), params_.min_factor * configured,
                      params_.max_factor * configured);
  };
  return {bounded(it->second.position, 2 * std::uint64_t{params_.min_samples}, configured_.position_stddev),
          bounded(it->second.orientation, params_.min_samples, configured_.orientation_stddev)};
}

std::vector<DetectionNoiseEstimator::CameraEstimate> DetectionNoiseEstimator::estimates() const {
  std::vector<CameraEstimate> out;
  for (const auto& [id, cam] : cameras_) out.push_back({id, cam.position.samples / 2, noise(id)});
  return out;
}

}  // namespace ssl::wm
