#include "services/planner/core/path_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "libs/geometry/circle.h"
#include "libs/geometry/contains.h"
#include "libs/geometry/intersect.h"
#include "libs/geometry/segment.h"

namespace ssl::planner {
namespace {

using geom::Vec2;

/// m a destination may lie inside a zone's edge (where a target pushed out of the zone lands).
constexpr double kEdgeTolerance = 0.001;
/// m a robot starting inside a robot obstacle may come closer to it (numerical slack of a tangential move).
constexpr double kNoDeeperTolerance = 0.001;

/// The obstacles as the sweep uses them, prepared once per search: static shapes grown by the chord
/// margin, and our planned robots' positions on the step grid (every candidate is swept on the same grid).
struct Prepared {
  const PathObstacles* obstacles = nullptr;
  double step = 0;
  double horizon = 0;
  double margin = 0;
  std::vector<geom::Rectangle> rectangles;
  std::vector<geom::Stadium> stadiums;
  std::vector<std::shared_ptr<const PathSamples>> path_samples;  // [obstacle]: the sweep's grid
  std::vector<char> inside_at_start;              // rectangles, stadiums, bounds
  // Circles, then paths: the radius a step must not come inside. A robot that starts inside a robot
  // obstacle's radius (its margin grew with our speed, or it was pushed) must not come any deeper: the
  // obstacle shrinks to just below the starting distance, so leaving or passing at the same distance is free.
  std::vector<double> robot_reach;

  /// Our planned robot `obstacle` at step k of a sweep (time t: k * step, or the path's end).
  Vec2 path_position(std::size_t obstacle, std::size_t k, double t) const {
    const std::vector<Vec2>& grid = path_samples[obstacle]->positions;
    if (k < grid.size() && std::abs(t - static_cast<double>(k) * step) < 1e-9) return grid[k];
    return obstacles->paths[obstacle].position(t);
  }
};

Prepared prepare(const Vec2& start, const Vec2& destination, const PathObstacles& obstacles, double step,
                 double horizon, double margin) {
  Prepared prepared{.obstacles = &obstacles, .step = step, .horizon = horizon, .margin = margin};
  // A destination on the edge of a zone (a target pushed out of it stops right there) lies inside the grown
  // zone: that zone is checked without the chord margin, less kEdgeTolerance (the robot brakes into the
  // destination, its curve hardly leaves the chords there).
  for (const geom::Rectangle& r : obstacles.rectangles) {
    const geom::Rectangle grown = r.expanded(margin);
    prepared.rectangles.push_back(grown.contains(destination) ? r.expanded(-kEdgeTolerance) : grown);
  }
  for (const geom::Stadium& s : obstacles.stadiums) {
    const geom::Stadium grown{s.spine, s.radius + margin};
    prepared.stadiums.push_back(geom::contains(grown, destination) ? geom::Stadium{s.spine, s.radius - kEdgeTolerance}
                                                                   : grown);
  }
  const auto steps = static_cast<std::size_t>(std::ceil(horizon / step)) + 1;
  for (const PathCircle& c : obstacles.paths) {
    const bool usable = c.samples && std::abs(c.samples->step - step) < 1e-12 && c.samples->positions.size() >= steps;
    prepared.path_samples.push_back(usable ? c.samples : sample_path(c, step, horizon));
  }
  std::vector<double>& reach = prepared.robot_reach;
  reach.reserve(obstacles.circles.size() + obstacles.paths.size());
  const auto reach_of = [&](double distance, double radius) {
    return distance < radius + margin ? std::max(0.0, distance - kNoDeeperTolerance) : radius + margin;
  };
  for (const MovingCircle& c : obstacles.circles) reach.push_back(reach_of((start - c.position).norm(), c.radius));
  for (const PathCircle& c : obstacles.paths) reach.push_back(reach_of((start - c.position(0)).norm(), c.radius));
  std::vector<char>& inside = prepared.inside_at_start;
  inside.reserve(obstacles.rectangles.size() + obstacles.stadiums.size() + 1);
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

/// Whether the segment from `a` to `b` comes within `radius` (m) of the origin: most segments of a sweep are
/// far from a robot obstacle, and their box tells so without the exact distance.
bool reaches_origin(const Vec2& a, const Vec2& b, double radius) {
  if (std::min(a.x(), b.x()) > radius || std::max(a.x(), b.x()) < -radius || std::min(a.y(), b.y()) > radius ||
      std::max(a.y(), b.y()) < -radius) {
    return false;
  }
  return geom::intersects(geom::Segment{a, b}, geom::Circle{Vec2::Zero(), radius});
}

/// The first step (its start time) at which `hit(k)` holds, for steps k = 0.. whose start lies before
/// `before`; `escaping`: the robot starts inside, so steps count only once `left(k)` said it is out.
template <typename Hit, typename Left>
std::optional<double> first_hit(std::size_t steps, const std::vector<double>& times, double before, char escaping,
                                const Hit& hit, const Left& left) {
  for (std::size_t k = 0; k < steps && times[k] < before; ++k) {
    if (escaping) {
      if (left(k)) escaping = 0;
      continue;
    }
    if (hit(k)) return times[k];
  }
  return std::nullopt;
}

/// The sweep of one candidate: for each obstacle the first step at which the robot's chord comes into it
/// (obstacles it starts in count once it has left them); the earliest over all obstacles. Obstacles whose
/// box over the horizon misses the box of the whole path are skipped. `settled(t)`: whether a collision at
/// t s already answers the caller (its candidate loses, whatever else there is): the sweep then stops and
/// returns that collision, which need not be the earliest.
template <typename Settled>
std::optional<double> sweep(const TrajectoryPath& path, const Prepared& prepared, std::vector<Vec2>& points,
                            std::vector<double>& times, const Settled& settled) {
  const PathObstacles& obstacles = *prepared.obstacles;
  const double end = std::min(prepared.horizon, path.duration());
  const double margin = prepared.margin;
  points.clear();
  times.clear();
  for (double t = 0;; t += prepared.step) {
    const double at = std::min(t, end);
    times.push_back(at);
    points.push_back(path.position(at));
    if (at >= end) break;
  }
  const std::size_t steps = points.size() - 1;  // step k goes from points[k] to points[k + 1]
  if (steps == 0) return std::nullopt;
  Vec2 low = points.front();
  Vec2 high = points.front();
  for (const Vec2& p : points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const auto misses_box = [&](const Vec2& a, const Vec2& b, double reach) {
    return std::max(a.x(), b.x()) + reach < low.x() || std::min(a.x(), b.x()) - reach > high.x() ||
           std::max(a.y(), b.y()) + reach < low.y() || std::min(a.y(), b.y()) - reach > high.y();
  };

  double earliest = std::numeric_limits<double>::infinity();
  // Keeps `hit`; true when the sweep can stop.
  const auto keep = [&](const std::optional<double>& hit) {
    if (!hit) return false;
    earliest = std::min(earliest, *hit);
    return settled(earliest);
  };
  const auto never_left = [](std::size_t) { return false; };
  std::size_t robot = 0;
  for (const MovingCircle& c : obstacles.circles) {
    const double reach = prepared.robot_reach[robot++];
    if (misses_box(c.position, c.position_at(end), reach)) continue;
    const auto relative = [&](std::size_t k) { return Vec2(points[k] - c.position_at(times[k])); };
    if (keep(first_hit(
        steps, times, earliest, 0,
        [&](std::size_t k) { return reaches_origin(relative(k), relative(k + 1), reach); },
        never_left))) {
      return earliest;
    }
  }
  for (std::size_t i = 0; i < obstacles.paths.size(); ++i) {
    const double reach = prepared.robot_reach[robot++];
    const PathSamples& samples = *prepared.path_samples[i];
    if (misses_box(samples.low, samples.high, reach + margin)) continue;
    const auto relative = [&](std::size_t k) { return Vec2(points[k] - prepared.path_position(i, k, times[k])); };
    if (keep(first_hit(
        steps, times, earliest, 0,
        [&](std::size_t k) { return reaches_origin(relative(k), relative(k + 1), reach); },
        never_left))) {
      return earliest;
    }
  }
  std::size_t index = 0;
  for (std::size_t i = 0; i < prepared.rectangles.size(); ++i) {
    const char escaping = prepared.inside_at_start[index++];
    const geom::Rectangle& grown = prepared.rectangles[i];
    if (!escaping && misses_box(grown.min(), grown.max(), 0)) continue;
    if (keep(first_hit(
        steps, times, earliest, escaping,
        [&](std::size_t k) {
          return boxes_overlap(points[k], points[k + 1], grown) &&
                 geom::intersects(geom::Segment{points[k], points[k + 1]}, grown);
        },
        [&](std::size_t k) { return !obstacles.rectangles[i].contains(points[k + 1]); }))) {
      return earliest;
    }
  }
  for (std::size_t i = 0; i < prepared.stadiums.size(); ++i) {
    const char escaping = prepared.inside_at_start[index++];
    if (keep(first_hit(
        steps, times, earliest, escaping,
        [&](std::size_t k) { return geom::intersects(geom::Segment{points[k], points[k + 1]}, prepared.stadiums[i]); },
        [&](std::size_t k) { return !geom::contains(obstacles.stadiums[i], points[k + 1]); }))) {
      return earliest;
    }
  }
  if (obstacles.bounds) {
    const char escaping = prepared.inside_at_start[index++];
    const geom::Rectangle& bounds = *obstacles.bounds;
    keep(first_hit(
        steps, times, earliest, escaping, [&](std::size_t k) { return !bounds.contains(points[k + 1]); },
        [&](std::size_t k) { return bounds.contains(points[k + 1]); }));
  }
  if (earliest == std::numeric_limits<double>::infinity()) return std::nullopt;
  return earliest;
}

/// Sub-destinations closer to the robot than this (m) are not tried.
constexpr double kMinViaDistance = 0.15;
/// s: a previous path whose switch is nearer than this is continued as the direct path.
constexpr double kMinSwitchAhead = 0.02;
/// s the duration bound of a candidate is lowered by against rounding, so that one left unplanned would
/// certainly have lost.
constexpr double kBoundSlack = 1e-9;

double score_of(double duration, const std::optional<double>& collision, const PathSearchParams& params) {
  if (!collision) return duration;
  return duration + params.collision_penalty +
         params.early_collision_weight * std::max(0.0, params.near_collision - *collision);
}

}  // namespace

std::shared_ptr<const PathSamples> sample_path(const PathCircle& circle, double step, double horizon) {
  auto samples = std::make_shared<PathSamples>();
  samples->step = step;
  const auto steps = static_cast<std::size_t>(std::ceil(horizon / step)) + 1;
  samples->positions.reserve(steps);
  // At rest at its destination after the path's end: no need to evaluate the trajectories there.
  const double end = circle.path.duration() - circle.elapsed;
  const Vec2 destination = circle.path.destination();
  for (std::size_t k = 0; k < steps; ++k) {
    const double t = static_cast<double>(k) * step;
    samples->positions.push_back(t >= end ? destination : circle.position(t));
  }
  samples->low = samples->positions.front();
  samples->high = samples->positions.front();
  for (const Vec2& p : samples->positions) {
    samples->low = samples->low.cwiseMin(p);
    samples->high = samples->high.cwiseMax(p);
  }
  return samples;
}

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
  const Prepared prepared = prepare(path.position(0), path.destination(), obstacles, step, horizon, margin);
  std::vector<Vec2> points;
  std::vector<double> times;
  return sweep(path, prepared, points, times, [](double) { return false; });
}

PathResult search_path(const Vec2& position, const Vec2& velocity, const Vec2& destination,
                       const TrajectoryLimits& limits, const PathObstacles& obstacles,
                       const PathSearchParams& params, const TrajectoryPath* previous, double previous_age) {
  // Between two checks the robot's curve stays within a * step^2 / 8 of the chord that is checked.
  const double chord_margin = limits.max_acceleration * params.step * params.step / 8;
  const Prepared prepared = prepare(position, destination, obstacles, params.step, params.horizon, chord_margin);
  std::vector<Vec2> points;
  std::vector<double> times;
  PathResult best;
  // The best path's rank (its score, less keep_previous_margin for last tick's path), then its index in the
  // order the candidates are generated in: of equally ranked paths the first generated wins, whatever order
  // they are evaluated in.
  std::optional<std::pair<double, int>> best_rank;
  // Whether candidate `index`, ranked no better than `rank`, may still win.
  const auto may_win = [&](double rank, int index) { return !best_rank || std::pair(rank, index) < *best_rank; };
  const auto bonus_of = [&](bool is_previous) { return is_previous ? params.keep_previous_margin : 0.0; };
  const auto consider = [&](const TrajectoryPath& candidate, int index, bool is_previous) {
    const double bonus = bonus_of(is_previous);
    const double duration = candidate.duration();
    // Arrival time is a lower bound of the score: no sweep needed for a path that cannot win.
    if (!may_win(duration - bonus, index)) return;
    // A collision that leaves the path ranked no better than the best: no need to sweep on.
    const auto loses = [&](double collision) { return !may_win(score_of(duration, collision, params) - bonus, index); };
    const std::optional<double> collision = sweep(candidate, prepared, points, times, loses);
    const double score = score_of(duration, collision, params);
    if (may_win(score - bonus, index)) {
      best.path = candidate;
      best.score = score;
      best.first_collision = collision;
      best_rank = {score - bonus, index};
    }
  };

  // The first trajectories towards the sub-destinations, and the candidates that leave one of them at a
  // switch time, before their second trajectory is planned: `bound` (s) is a lower bound of the duration.
  std::vector<Trajectory2D> firsts;
  struct ViaCandidate {
    double bound = 0;
    int index = 0;
    std::size_t first = 0;  // in firsts
    double switch_at = 0;   // s
    Vec2 from = Vec2::Zero();
    Vec2 speed = Vec2::Zero();
    bool is_previous = false;
  };
  // firsts[`first`] towards `via`, left at `switch_time` (or on arrival) for the destination; counted.
  const auto via_candidate = [&](std::size_t first, const Vec2& via, double switch_time, bool is_previous) {
    const Trajectory2D& trajectory = firsts[first];
    const bool on_arrival = switch_time >= trajectory.duration();
    ViaCandidate c{.index = best.candidates++,
                   .first = first,
                   .switch_at = on_arrival ? trajectory.duration() : switch_time,
                   .from = on_arrival ? via : trajectory.position(switch_time),
                   .speed = on_arrival ? Vec2::Zero() : trajectory.velocity(switch_time),
                   .is_previous = is_previous};
    c.bound = c.switch_at + Trajectory2D::duration_bound(c.from, c.speed, destination, limits) - kBoundSlack;
    return c;
  };
  // Plans and considers `c` unless its bound shows that it cannot win; whether it did.
  const auto consider_via = [&](const ViaCandidate& c) {
    if (!may_win(c.bound - bonus_of(c.is_previous), c.index)) return false;
    consider(TrajectoryPath(firsts[c.first], c.switch_at, Trajectory2D::plan(c.from, c.speed, destination, limits)),
             c.index, c.is_previous);
    return true;
  };
  const auto usable_via = [&](const Vec2& via) {
    // A sub-destination the robot is already at is no detour: the path would stop there first.
    return (!obstacles.bounds || obstacles.bounds->contains(via)) && (via - position).norm() >= kMinViaDistance;
  };

  // Last tick's path as it goes on: through its sub-destination until its switch, which comes closer every
  // tick; once passed, it is the direct path.
  const bool previous_switch_ahead =
      previous && !previous->is_direct() && previous->switch_time() - previous_age > kMinSwitchAhead;
  const int direct = best.candidates++;
  consider(TrajectoryPath(Trajectory2D::plan(position, velocity, destination, limits)), direct,
           previous && !previous_switch_ahead);
  if (previous_switch_ahead && usable_via(previous->via())) {
    firsts.push_back(Trajectory2D::plan(position, velocity, previous->via(), limits));
    consider_via(via_candidate(0, previous->via(), previous->switch_time() - previous_age, true));
  }
  if (best.first_collision && *best.first_collision < params.sample_below) {
    const int around_destination = std::max(1, params.directions / 2);
    const std::size_t vias = params.radii.size() * static_cast<std::size_t>(params.directions) +
                             params.destination_radii.size() * static_cast<std::size_t>(around_destination);
    firsts.reserve(firsts.size() + vias);
    std::vector<ViaCandidate> sampled;
    sampled.reserve(vias * params.switch_times.size());
    std::vector<std::pair<std::size_t, Vec2>> sampled_vias;  // (index in firsts, sub-destination)
    sampled_vias.reserve(vias);
    const auto through = [&](const Vec2& via) {
      if (!usable_via(via)) return;
      firsts.push_back(Trajectory2D::plan(position, velocity, via, limits));
      sampled_vias.emplace_back(firsts.size() - 1, via);
      for (const double switch_time : params.switch_times) {
        sampled.push_back(via_candidate(firsts.size() - 1, via, switch_time, false));
        if (switch_time >= firsts.back().duration()) break;
      }
    };
    for (const double radius : params.radii) {
      for (int i = 0; i < params.directions; ++i) {
        const double angle = params.direction_offset + 2 * std::numbers::pi * i / params.directions;
        through(position + radius * Vec2(std::cos(angle), std::sin(angle)));
      }
    }
    for (const double radius : params.destination_radii) {
      for (int i = 0; i < around_destination; ++i) {
        const double angle = params.direction_offset + 2 * std::numbers::pi * i / around_destination;
        through(destination + radius * Vec2(std::cos(angle), std::sin(angle)));
      }
    }
    const auto consider_in_order = [&](std::vector<ViaCandidate>& candidates) {
      // Best bound first: a good path found early leaves the others unplanned, and once one cannot win,
      // none after it can.
      std::sort(candidates.begin(), candidates.end(), [](const ViaCandidate& a, const ViaCandidate& b) {
        return std::pair(a.bound, a.index) < std::pair(b.bound, b.index);
      });
      for (const ViaCandidate& c : candidates) {
        if (!consider_via(c)) break;
      }
    };
    consider_in_order(sampled);
    if (best.first_collision && !params.late_switch_times.empty()) {
      sampled.clear();
      for (const auto& [first, via] : sampled_vias) {
        for (const double switch_time : params.late_switch_times) {
          // Late switches branch off a first trajectory still under way (on arrival was tried, if at all,
          // with the first switches).
          if (switch_time >= firsts[first].duration()) break;
          sampled.push_back(via_candidate(first, via, switch_time, false));
        }
      }
      consider_in_order(sampled);
    }
  }
  return best;
}

}  // namespace ssl::planner
