#include "services/planner/core/assignment.h"

#include <algorithm>
#include <limits>

namespace ssl::planner {

std::array<int, kMaxSlots> optimal_assignment(const CostMatrix& cost, std::size_t rows, std::size_t cols) {
  // Hungarian method with potentials (rows <= cols), 1-based internally; column 0 is the virtual start.
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::array<double, kMaxSlots + 1> u{}, v{}, min_to{};
  std::array<int, kMaxSlots + 1> match{}, way{};  // match[col] = row (1-based), 0: free
  std::array<bool, kMaxSlots + 1> used{};
  for (std::size_t i = 1; i <= rows; ++i) {
    match[0] = static_cast<int>(i);
    std::size_t j0 = 0;
    min_to.fill(kInf);
    used.fill(false);
    do {
      used[j0] = true;
      const std::size_t i0 = static_cast<std::size_t>(match[j0]);
      double delta = kInf;
      std::size_t j1 = 0;
      for (std::size_t j = 1; j <= cols; ++j) {
        if (used[j]) continue;
        const double reduced = cost[i0 - 1][j - 1] - u[i0] - v[j];
        if (reduced < min_to[j]) {
          min_to[j] = reduced;
          way[j] = static_cast<int>(j0);
        }
        if (min_to[j] < delta) {  // strict: the lowest index wins ties (deterministic)
          delta = min_to[j];
          j1 = j;
        }
      }
      for (std::size_t j = 0; j <= cols; ++j) {
        if (used[j]) {
          u[static_cast<std::size_t>(match[j])] += delta;
          v[j] -= delta;
        } else {
          min_to[j] -= delta;
        }
      }
      j0 = j1;
    } while (match[j0] != 0);
    do {
      const std::size_t j1 = static_cast<std::size_t>(way[j0]);
      match[j0] = match[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::array<int, kMaxSlots> result;
  result.fill(-1);
  for (std::size_t j = 1; j <= cols; ++j) {
    if (match[j] != 0) result[static_cast<std::size_t>(match[j]) - 1] = static_cast<int>(j) - 1;
  }
  return result;
}

std::span<const int> StableAssigner::assign(std::uint32_t key, std::span<const std::uint32_t> ids,
                                            std::span<const wm::Vec2> robots,
                                            std::span<const wm::Vec2> slots) {
  const std::size_t n = std::min({ids.size(), robots.size(), kMaxSlots});
  const std::size_t m = std::min(slots.size(), kMaxSlots);
  CostMatrix cost{};
  for (std::size_t r = 0; r < n; ++r) {
    for (std::size_t s = 0; s < m; ++s) cost[r][s] = (robots[r] - slots[s]).norm();
  }
  return assign_costs(key, ids.first(n), cost, m);
}

std::span<const int> StableAssigner::assign_costs(std::uint32_t key, std::span<const std::uint32_t> ids,
                                                  const CostMatrix& given, std::size_t slots) {
  const std::size_t n = std::min(ids.size(), kMaxSlots);
  const std::size_t m = std::min(slots, kMaxSlots);
  const std::size_t cols = std::max(n, m);
  CostMatrix cost{};
  for (std::size_t r = 0; r < n; ++r) {
    for (std::size_t s = 0; s < cols; ++s) cost[r][s] = s < m ? given[r][s] : 0.0;
  }
  std::array<int, kMaxSlots> best = optimal_assignment(cost, n, cols);
  for (std::size_t r = 0; r < n; ++r) {
    if (best[r] >= static_cast<int>(m)) best[r] = -1;
  }

  const bool same = valid_ && key_ == key && slot_count_ == m && id_count_ == n &&
                    std::equal(ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(n), ids_.begin());
  if (same) {
    const auto total = [&](const std::array<int, kMaxSlots>& a) {
      double sum = 0;
      for (std::size_t r = 0; r < n; ++r) {
        if (a[r] >= 0) sum += cost[r][static_cast<std::size_t>(a[r])];
      }
      return sum;
    };
    const double old_cost = total(result_);
    const double new_cost = total(best);
    if (new_cost < old_cost - hysteresis_ && new_cost < 0.9 * old_cost) result_ = best;
  } else {
    result_ = best;
  }
  valid_ = true;
  key_ = key;
  slot_count_ = m;
  id_count_ = n;
  std::copy_n(ids.begin(), n, ids_.begin());
  return {result_.data(), n};
}

std::optional<std::uint32_t> StableChoice::choose(std::span<const std::uint32_t> ids,
                                                  std::span<const double> scores) {
  const std::size_t n = std::min(ids.size(), scores.size());
  if (n == 0) {
    current_.reset();
    return std::nullopt;
  }
  std::size_t best = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (scores[i] < scores[best]) best = i;
  }
  if (current_) {
    for (std::size_t i = 0; i < n; ++i) {
      if (ids[i] == *current_ && scores[i] <= scores[best] + hysteresis_) return current_;
    }
  }
  current_ = ids[best];
  return current_;
}

}  // namespace ssl::planner
