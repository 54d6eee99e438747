// LatencyWindow: collects durations (e.g. packet receive -> after DDS write) between two health reports
// and summarises them as median and 99th percentile. Pure and single-threaded; the caller decides the
// window (the gateway takes one summary per second, so p50/p99 are "over the last second").
//
// Percentiles are nearest-rank over the collected samples (p99 of fewer than 100 samples is their
// maximum). The number of samples kept per window is capped (`max_samples`, default 100000, i.e. more
// than 1 s of packets of 8 cameras at 1 kHz); beyond it, samples are counted but not kept.
//
//   LatencyWindow window;
//   window.add(std::chrono::microseconds(80));
//   LatencySummary s = window.take();   // s.p50, s.p99 (Duration), s.count; the window is empty again
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "libs/time/time.h"

namespace ssl::vision_gateway {

struct LatencySummary {
  std::uint64_t count = 0;  // samples added in the window (kept or not)
  time::Duration p50{0};    // zero when count == 0
  time::Duration p99{0};
  time::Duration max{0};
};

class LatencyWindow {
 public:
  explicit LatencyWindow(std::size_t max_samples = 100000);

  void add(time::Duration sample);

  /// Summarises the samples since the last take() and starts a new window.
  LatencySummary take();

 private:
  std::size_t max_samples_;
  std::uint64_t count_ = 0;
  std::vector<time::Duration> samples_;
};

}  // namespace ssl::vision_gateway
