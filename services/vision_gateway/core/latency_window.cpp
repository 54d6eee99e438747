#include "services/vision_gateway/core/latency_window.h"

#include <algorithm>
#include <cmath>

namespace ssl::vision_gateway {

LatencyWindow::LatencyWindow(std::size_t max_samples) : max_samples_(std::max<std::size_t>(max_samples, 1)) {
  samples_.reserve(std::min<std::size_t>(max_samples_, 4096));
}

void LatencyWindow::add(time::Duration sample) {
  ++count_;
  if (samples_.size() < max_samples_) samples_.push_back(sample);
}

LatencySummary LatencyWindow::take() {
  LatencySummary summary;
  summary.count = count_;
  if (!samples_.empty()) {
    // Nearest rank: the smallest sample with at least p% of the samples at or below it.
    auto rank = [&](double p) {
      const auto n = samples_.size();
      const auto index = static_cast<std::size_t>(std::ceil(p * static_cast<double>(n)));
      return std::clamp<std::size_t>(index, 1, n) - 1;
    };
    const std::size_t i50 = rank(0.50);
    const std::size_t i99 = rank(0.99);
    std::nth_element(samples_.begin(), samples_.begin() + static_cast<std::ptrdiff_t>(i50), samples_.end());
    summary.p50 = samples_[i50];
    std::nth_element(samples_.begin(), samples_.begin() + static_cast<std::ptrdiff_t>(i99), samples_.end());
    summary.p99 = samples_[i99];
    summary.max = *std::max_element(samples_.begin(), samples_.end());
  }
  count_ = 0;
  samples_.clear();
  return summary;
}

}  // namespace ssl::vision_gateway
