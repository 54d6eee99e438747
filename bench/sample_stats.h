// SampleStats: the median, p99 and maximum of one bench's samples, in the samples' own unit (the caller's
// names say which: ms or us). p99 is the sample at rank floor(0.99 n) (the last at most), no interpolation.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace ssl::bench {

struct SampleStats {
  double median = 0;
  double p99 = 0;
  double max = 0;
  std::size_t count = 0;
};

inline SampleStats summarize(std::vector<double> samples) {
  SampleStats stats;
  stats.count = samples.size();
  if (samples.empty()) return stats;
  std::sort(samples.begin(), samples.end());
  stats.median = samples[samples.size() / 2];
  stats.p99 = samples[std::min(samples.size() - 1, samples.size() * 99 / 100)];
  stats.max = samples.back();
  return stats;
}

}  // namespace ssl::bench
