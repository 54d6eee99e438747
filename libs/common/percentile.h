// percentile: the q-quantile of a set of samples by partial sort (nearest rank below, no interpolation),
// for health reports (p50 / p99 of per-period timings). Reorders `values`; 0 for an empty set.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace ssl {

/// q in [0, 1]; values are reordered (std::nth_element), O(n).
inline double percentile(std::vector<double>& values, double q) {
  if (values.empty()) return 0;
  const auto index = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index), values.end());
  return values[index];
}

}  // namespace ssl
