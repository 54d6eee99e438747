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

/// Which obstacles the robot stands in at the start (in the order circles, paths, rectangles, stadiums,
/// bounds): those count only once the path has left them.
struct StartInside {
  std::vector<char> inside;
};

StartInside inside_at_start(const Vec2& p, const PathObstacles& obstacles) {
  StartInside start;
  start.inside.reserve(obstacles.circles.size() + obstacles.paths.size() + obstacles.rectangles.size() +
                       obstacles.stadiums.size() + 1);
  for (const MovingCircle& c : obstacles.circles) start.inside.push_back((p - c.position).norm() < c.radius);
  for (const PathCircle& c : obstacles.paths) start.inside.push_back((p - c.path.position(0)).norm() < c.radius);
  for (const geom::Rectangle& r : obstacles.rectangles) start.inside.push_back(r.contains(p));
  for (const geom::Stadium& s : obstacles.stadiums) start.inside.push_back(geom::contains(s, p));
  start.inside.push_back(obstacles.bounds && !obstacles.bounds->contains(p));
  return start;
}

/// The sweep of one candidate; `inside` is consumed (cleared per obstacle once the path has left it).
std::optional<double> sweep(const TrajectoryPath& path, const PathObstacles& obstacles, double step,
                            double horizon, double margin, std::vector<char>& inside) {
  const double end = std::min(horizon, path.duration());
  Vec2 p0 = path.position(0);
  for (double t0 = 0; t0 < end; t0 += step) {
    const double t1 = std::min(t0 + step, end);
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
    for (const PathCircle& c : obstacles.paths) {
      const Vec2 a = p0 - c.path.position(t0);
      const Vec2 b = p1 - c.path.position(t1);
      if (check(geom::intersects(geom::Segment{a, b}, geom::Circle{Vec2::Zero(), c.radius + margin}),
                b.norm() >= c.radius)) {
        return t0;
      }
    }
    const geom::Segment moved{p0, p1};
    for (const geom::Rectangle& r : obstacles.rectangles) {
      if (check(geom::intersects(moved, r.expanded(margin)), !r.contains(p1))) return t0;
    }
    for (const geom::Stadium& s : obstacles.stadiums) {
      if (check(geom::intersects(moved, geom::Stadium{s.spine, s.radius + margin}), !geom::contains(s, p1))) return t0;
    }
    if (obstacles.bounds) {
      const bool in_bounds = obstacles.bounds->contains(p1);
      if (check(!in_bounds, in_bounds)) return t0;
    }
    p0 = p1;
  }
  return std::nullopt;
}

double score_of(double duration, const std::optional<double>& collision, const PathSearchParams& params) {
  if (!collision) return duration;
  return duration + params.collision_penalty + params.early_collision_weight * (params.horizon - *collision);
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
  StartInside start = inside_at_start(path.position(0), obstacles);
  return sweep(path, obstacles, step, horizon, margin, start.inside);
}

PathResult search_path(const Vec2& position, const Vec2& velocity, const Vec2& destination,
                       const TrajectoryLimits& limits, const PathObstacles& obstacles,
                       const PathSearchParams& params, const TrajectoryPath* previous) {
  const StartInside start = inside_at_start(position, obstacles);
  // Between two checks the robot's curve stays within a * step^2 / 8 of the chord that is checked.
  const double chord_margin = limits.max_acceleration * params.step * params.step / 8;
  std::vector<char> inside;
  PathResult best;
  bool have_best = false;
  double best_rank = 0;  // the score, less keep_previous_margin for last tick's path
  const auto consider = [&](const TrajectoryPath& candidate, bool is_previous) {
    ++best.candidates;
    const double bonus = is_previous ? params.keep_previous_margin : 0.0;
    // Arrival time is a lower bound of the score: no sweep needed for a path that cannot win.
    if (have_best && candidate.duration() - bonus >= best_rank) return;
    inside = start.inside;
    const std::optional<double> collision =
        sweep(candidate, obstacles, params.step, params.horizon, chord_margin, inside);
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
