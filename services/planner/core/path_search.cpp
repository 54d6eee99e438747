#include "services/planner/core/path_search.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "libs/geometry/circle.h"
#include "libs/geometry/contains.h"
#include "libs/geometry/intersect.h"
#include "libs/geometry/segment.h"

namespace ssl::planner {
namespace {

using geom::Vec2;

/// The obstacles as the sweep uses them, prepared once per search: static shapes grown by the chord
/// margin, and our planned robots' positions on the step grid (every candidate is swept on the same grid).
struct Prepared {
  const PathObstacles* obstacles = nullptr;
  double step = 0;
  double horizon = 0;
  double margin = 0;
  std::vector<geom::Rectangle> rectangles;
  std::vector<geom::Stadium> stadiums;
  std::vector<std::vector<Vec2>> path_positions;  // [obstacle][k]: at k * step
  std::vector<char> inside_at_start;              // circles, paths, rectangles, stadiums, bounds

  Vec2 path_position(std::size_t obstacle, double t) const {
    const auto k = static_cast<std::size_t>(std::lround(t / step));
    const std::vector<Vec2>& grid = path_positions[obstacle];
    if (k < grid.size() && std::abs(t - k * step) < 1e-9) return grid[k];
    return obstacles->paths[obstacle].path.position(t);
  }
};

Prepared prepare(const Vec2& start, const PathObstacles& obstacles, double step, double horizon, double margin) {
  Prepared prepared{.obstacles = &obstacles, .step = step, .horizon = horizon, .margin = margin};
  for (const geom::Rectangle& r : obstacles.rectangles) prepared.rectangles.push_back(r.expanded(margin));
  for (const geom::Stadium& s : obstacles.stadiums) prepared.stadiums.push_back({s.spine, s.radius + margin});
  const auto steps = static_cast<std::size_t>(std::ceil(horizon / step)) + 1;
  for (const PathCircle& c : obstacles.paths) {
    std::vector<Vec2>& grid = prepared.path_positions.emplace_back();
    grid.reserve(steps);
    for (std::size_t k = 0; k < steps; ++k) grid.push_back(c.path.position(k * step));
  }
  std::vector<char>& inside = prepared.inside_at_start;
  inside.reserve(obstacles.circles.size() + obstacles.paths.size() + obstacles.rectangles.size() +
                 obstacles.stadiums.size() + 1);
  for (const MovingCircle& c : obstacles.circles) inside.push_back((start - c.position).norm() < c.radius);
  for (const PathCircle& c : obstacles.paths) inside.push_back((start - c.path.position(0)).norm() < c.radius);
  for (const geom::Rectangle& r : obstacles.rectangles) inside.push_back(r.contains(start));
  for (const geom::Stadium& st : obstacles.stadiums) inside.push_back(geom::contains(st, start));
  inside.push_back(obstacles.bounds && !obstacles.bounds->contains(start));
  return prepared;
}

/// Whether the boxes around a short segment and a rectangle overlap (cheap; the exact test follows).
bool boxes_overlap(const Vec2& a, const Vec2& b, const geom::Rectangle& r) {
  return std::max(a.x(), b.x()) >= r.min().x() && std::min(a.x(), b.x()) <= r.max().x() &&
         std::max(a.y(), b.y()) >= r.min().y() && std::min(a.y(), b.y()) <= r.max().y();
}

/// The sweep of one candidate; `inside` (a copy of inside_at_start) is cleared per obstacle once the path
/// has left it.
std::optional<double> sweep(const TrajectoryPath& path, const Prepared& prepared, std::vector<char>& inside) {
  const PathObstacles& obstacles = *prepared.obstacles;
  const double end = std::min(prepared.horizon, path.duration());
  const double margin = prepared.margin;
  Vec2 p0 = path.position(0);
  for (double t0 = 0; t0 < end; t0 += prepared.step) {
    const double t1 = std::min(t0 + prepared.step, end);
    const Vec2 p1 = path.position(t1);
    std::size_t index = 0;
    // Each obstacle: while the robot is still in the one it started in, only watch for it leaving.
    const auto check = [&](bool hit_now, bool outside_at_end) {
      char& escaping = inside[index++];
      if (escaping) {
        if (outside_at_end) escaping = 0;
        return false;
      }
      return hit_now;
    };
    for (const MovingCircle& c : obstacles.circles) {
      const Vec2 a = p0 - (c.position + c.velocity * t0);
      const Vec2 b = p1 - (c.position + c.velocity * t1);
      if (check(geom::intersects(geom::Segment{a, b}, geom::Circle{Vec2::Zero(), c.radius + margin}),
                b.norm() >= c.radius)) {
        return t0;
      }
    }
    for (std::size_t i = 0; i < obstacles.paths.size(); ++i) {
      const double radius = obstacles.paths[i].radius;
      const Vec2 a = p0 - prepared.path_position(i, t0);
      const Vec2 b = p1 - prepared.path_position(i, t1);
      if (check(geom::intersects(geom::Segment{a, b}, geom::Circle{Vec2::Zero(), radius + margin}),
                b.norm() >= radius)) {
        return t0;
      }
    }
    const geom::Segment moved{p0, p1};
    for (std::size_t i = 0; i < prepared.rectangles.size(); ++i) {
      const geom::Rectangle& grown = prepared.rectangles[i];
      const bool hit = boxes_overlap(p0, p1, grown) && geom::intersects(moved, grown);
      if (check(hit, !obstacles.rectangles[i].contains(p1))) return t0;
    }
    for (std::size_t i = 0; i < prepared.stadiums.size(); ++i) {
      if (check(geom::intersects(moved, prepared.stadiums[i]), !geom::contains(obstacles.stadiums[i], p1))) {
        return t0;
      }
    }
    if (obstacles.bounds) {
      const bool in_bounds = obstacles.bounds->contains(p1);
      if (check(!in_bounds, in_bounds)) return t0;
    }
    p0 = p1;
  }
  return std::nullopt;
}

/// Sub-destinations closer to the robot than this (m) are not tried.
constexpr double kMinViaDistance = 0.15;

double score_of(double duration, const std::optional<double>& collision, const PathSearchParams& params) {
  if (!collision) return duration;
  return duration + params.collision_penalty +
         params.early_collision_weight * std::max(0.0, params.near_collision - *collision);
}

}  // namespace

Vec2 TrajectoryPath::position(double t) const {
  if (!second_ || t < switch_time_) return first_.position(t);
  return second_->position(t - switch_time_);
}

Vec2 TrajectoryPath::velocity(double t) const {
  if (!second_ || t < switch_time_) return first_.velocity(t);
  return second_->velocity(t - switch_time_);
}

std::optional<double> first_collision(const TrajectoryPath& path, const PathObstacles& obstacles, double step,
                                      double horizon, double margin) {
  const Prepared prepared = prepare(path.position(0), obstacles, step, horizon, margin);
  std::vector<char> inside = prepared.inside_at_start;
  return sweep(path, prepared, inside);
}

PathResult search_path(const Vec2& position, const Vec2& velocity, const Vec2& destination,
                       const TrajectoryLimits& limits, const PathObstacles& obstacles,
                       const PathSearchParams& params, const TrajectoryPath* previous) {
  // Between two checks the robot's curve stays within a * step^2 / 8 of the chord that is checked.
  const double chord_margin = limits.max_acceleration * params.step * params.step / 8;
  const Prepared prepared = prepare(position, obstacles, params.step, params.horizon, chord_margin);
  std::vector<char> inside;
  PathResult best;
  bool have_best = false;
  double best_rank = 0;  // the score, less keep_previous_margin for last tick's path
  const auto consider = [&](const TrajectoryPath& candidate, bool is_previous) {
    ++best.candidates;
    const double bonus = is_previous ? params.keep_previous_margin : 0.0;
    // Arrival time is a lower bound of the score: no sweep needed for a path that cannot win.
    if (have_best && candidate.duration() - bonus >= best_rank) return;
    inside = prepared.inside_at_start;
    const std::optional<double> collision = sweep(candidate, prepared, inside);
    const double score = score_of(candidate.duration(), collision, params);
    if (!have_best || score - bonus < best_rank) {
      best.path = candidate;
      best.score = score;
      best.first_collision = collision;
      best_rank = score - bonus;
      have_best = true;
    }
  };
  const auto through = [&](const Vec2& via, bool is_previous) {
    if (obstacles.bounds && !obstacles.bounds->contains(via)) return;
    // A sub-destination the robot is already at is no detour: the path would stop there first, and kept
    // from tick to tick it would never leave.
    if ((via - position).norm() < kMinViaDistance) return;
    const Trajectory2D first = Trajectory2D::plan(position, velocity, via, limits);
    for (const double switch_time : params.switch_times) {
      if (switch_time >= first.duration()) {
        consider(TrajectoryPath(first, first.duration(), Trajectory2D::plan(via, Vec2::Zero(), destination, limits)),
                 is_previous);
        break;
      }
      consider(TrajectoryPath(first, switch_time, Trajectory2D::plan(first.position(switch_time),
                                                                      first.velocity(switch_time), destination,
                                                                      limits)),
               is_previous);
    }
  };

  consider(TrajectoryPath(Trajectory2D::plan(position, velocity, destination, limits)),
           previous && previous->is_direct());
  if (previous && !previous->is_direct()) through(previous->via(), true);
  if (best.first_collision) {
    for (const double radius : params.radii) {
      for (int i = 0; i < params.directions; ++i) {
        const double angle = 2 * std::numbers::pi * i / params.directions;
        through(position + radius * Vec2(std::cos(angle), std::sin(angle)), false);
      }
    }
  }
  return best;
}

}  // namespace ssl::planner
