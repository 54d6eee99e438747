#include "services/world_model/core/command_delay.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "libs/domain/robot_motion.h"

namespace ssl::wm {
namespace {

using geom::Vec2;

constexpr double kSampleStep = 0.01;  // s between compared instants
constexpr double kReplayStep = 0.005;  // s, the replayed ramp's step

}  // namespace

CommandDelayEstimator::CommandDelayEstimator(const CommandDelayParams& params) : params_(params) {
  if (!(params.resolution > 0) || !(params.max_delay >= params.min_delay) || !(params.min_delay >= 0) ||
      !(params.window > 0) || !(params.memory > 0) || !(params.velocity_span > 0) || !(params.max_acceleration > 0) ||
      !(params.max_deceleration > 0)) {
    throw std::invalid_argument("command delay: resolution, window, memory, velocity_span, max_acceleration and max_deceleration "
                                "must be > 0 and 0 <= min_delay <= max_delay");
  }
  const auto candidates =
      static_cast<std::size_t>(std::floor((params.max_delay - params.min_delay) / params.resolution + 1e-9)) + 1;
  cost_.assign(candidates, 0.0);
}

void CommandDelayEstimator::on_command(std::uint32_t id, const Vec2& local_velocity, time::Timestamp t) {
  if (!params_.estimate || id >= robots_.size() || !local_velocity.allFinite()) return;
  auto& commands = robots_[id].commands;
  if (!commands.empty() && t < commands.back().at) return;  // out of order: the older one is late
  commands.push_back({t, local_velocity});
}

void CommandDelayEstimator::on_position(std::uint32_t id, const Vec2& position, double heading, time::Timestamp t) {
  if (!params_.estimate || id >= robots_.size() || !position.allFinite() || !std::isfinite(heading)) return;
  auto& positions = robots_[id].positions;
  // Cameras' frames interleave: keep the buffer sorted by capture time.
  auto at = positions.end();
  while (at != positions.begin() && std::prev(at)->at > t) --at;
  positions.insert(at, {t, position, heading});
}

void CommandDelayEstimator::forget_before(Robot& robot, time::Timestamp t) const {
  while (robot.positions.size() > 1 && robot.positions.front().at < t) robot.positions.pop_front();
  // Keep the last command before t: it is in force at t.
  while (robot.commands.size() > 1 && robot.commands[1].at <= t) robot.commands.pop_front();
}

std::optional<CommandDelayEstimator::Measured> CommandDelayEstimator::measured(const Robot& robot,
                                                                              time::Timestamp t) const {
  const time::Duration half = time::duration_from_seconds(params_.velocity_span / 2);
  double n = 0, st = 0, stt = 0;
  Vec2 sp = Vec2::Zero(), stp = Vec2::Zero();
  double heading = 0, nearest = 1e9;
  for (const Position& p : robot.positions) {
    if (p.at < t - half) continue;
    if (p.at > t + half) break;
    const double dt = time::to_seconds(p.at - t);
    if (std::abs(dt) < nearest) {
      nearest = std::abs(dt);
      heading = p.heading;
    }
    n += 1;
    st += dt;
    stt += dt * dt;
    sp += p.position;
    stp += dt * p.position;
  }
  const double denominator = n * stt - st * st;
  if (n < 3 || denominator < 1e-12) return std::nullopt;
  return Measured{Vec2((n * stp - st * sp) / denominator), heading};
}

Vec2 CommandDelayEstimator::commanded(const Robot& robot, time::Timestamp t, std::size_t& next) const {
  // `next`: the first command after the previous (earlier or equal) t asked for.
  while (next < robot.commands.size() && robot.commands[next].at <= t) ++next;
  if (next == 0) return Vec2::Zero();
  const Command& in_force = robot.commands[next - 1];
  if (time::to_seconds(t - in_force.at) > params_.command_timeout) return Vec2::Zero();
  return in_force.velocity;
}

std::size_t CommandDelayEstimator::evaluate(const Robot& robot, time::Timestamp end,
                                            std::vector<double>& window_cost) const {
  const time::Timestamp start = end - time::duration_from_seconds(params_.window);
  std::vector<std::pair<double, Measured>> samples;  // s after start, what vision measured
  for (double s = 0; s <= params_.window + 1e-9; s += kSampleStep) {
    if (auto m = measured(robot, start + time::duration_from_seconds(s))) samples.emplace_back(s, *m);
  }
  if (samples.size() < params_.window / kSampleStep / 2 || samples.front().first > kSampleStep * 1.5) return 0;
  // Motion that hardly changed tells the delays apart no better than noise does.
  Vec2 low = samples.front().second.velocity, high = low;
  for (const auto& [s, m] : samples) {
    low = low.cwiseMin(m.velocity);
    high = high.cwiseMax(m.velocity);
  }
  if ((high - low).maxCoeff() < params_.min_excitation) return 0;

  const double outlier = params_.outlier_velocity * params_.outlier_velocity;
  for (std::size_t i = 0; i < window_cost.size(); ++i) {
    const time::Duration delay = time::duration_from_seconds(candidate(i));
    Vec2 v = samples.front().second.velocity;
    double s = 0;
    double cost = 0;
    std::size_t command = 0;
    for (std::size_t k = 1; k < samples.size(); ++k) {
      const geom::Angle heading = geom::Angle::from_radians(samples[k - 1].second.heading);
      while (s + kReplayStep <= samples[k].first + 1e-9) {
        // The command at the step's middle: a change within the step acts on average half way through.
        const time::Timestamp middle = start + time::duration_from_seconds(s + kReplayStep / 2);
        const Vec2 aim = geom::rotate(commanded(robot, middle - delay, command), heading);
        v = ramp_velocity(v, aim, params_.max_acceleration, params_.max_deceleration, kReplayStep);
        s += kReplayStep;
      }
      cost += std::min((samples[k].second.velocity - v).squaredNorm(), outlier);
    }
    window_cost[i] += cost;
  }
  return samples.size() - 1;
}

void CommandDelayEstimator::update(time::Timestamp t) {
  if (!params_.estimate) return;
  if (last_evaluation_ && time::to_seconds(t - *last_evaluation_) < params_.evaluation_period) return;
  const double elapsed = last_evaluation_ ? time::to_seconds(t - *last_evaluation_) : params_.evaluation_period;
  last_evaluation_ = t;
  // The window ends where every instant still has its velocity_span of detections around it.
  const time::Timestamp end = t - time::duration_from_seconds(params_.velocity_span / 2);
  const time::Timestamp keep_from =
      end - time::duration_from_seconds(params_.window + params_.max_delay + params_.velocity_span);
  std::vector<double> window_cost(cost_.size(), 0.0);
  std::size_t samples = 0;
  for (Robot& robot : robots_) {
    forget_before(robot, keep_from);
    samples += evaluate(robot, end, window_cost);
  }
  // Overlapping windows each count: the memory weighs them by how much new time each adds.
  const double decay = std::exp(-elapsed / params_.memory);
  const double share = std::min(1.0, elapsed / params_.window);
  for (std::size_t i = 0; i < cost_.size(); ++i) cost_[i] = decay * cost_[i] + share * window_cost[i];
  weight_ = decay * weight_ + share * static_cast<double>(samples);
  if (weight_ < params_.min_weight) return;
  const auto best = static_cast<std::size_t>(std::min_element(cost_.begin(), cost_.end()) - cost_.begin());
  double refined = candidate(best);
  if (best > 0 && best + 1 < cost_.size()) {
    const double left = cost_[best - 1], middle = cost_[best], right = cost_[best + 1];
    const double curvature = left - 2 * middle + right;
    if (curvature > 0) refined += params_.resolution * 0.5 * (left - right) / curvature;
  }
  delay_ = refined;
}

}  // namespace ssl::wm
