#include "services/robot_link/core/robot_link_core.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ssl::robot_link {
namespace {

/// Replaces a non-finite value by 0 and clamps a finite one to [lowest, highest]; counts changes.
double clamp_value(double value, double lowest, double highest, CoreCounters& counters) {
  if (!std::isfinite(value)) {
    ++counters.non_finite_values;
    ++counters.clamped_values;
    return 0;
  }
  if (value < lowest || value > highest) {
    ++counters.clamped_values;
    return std::clamp(value, lowest, highest);
  }
  return value;
}

/// Replaces a non-finite value by 0 (counted).
double finite_or_zero(double value, CoreCounters& counters) {
  if (std::isfinite(value)) return value;
  ++counters.non_finite_values;
  ++counters.clamped_values;
  return 0;
}

/// Moves `from` towards `to` by at most `max_step` (a scalar); true when limited.
bool limit_step(double from, double& to, double max_step) {
  const double delta = to - from;
  if (std::abs(delta) <= max_step) return false;
  to = from + std::copysign(max_step, delta);
  return true;
}

}  // namespace

Status validate(const CoreConfig& config) {
  const RobotLimits& l = config.limits;
  const std::pair<const char*, double> positive[] = {
      {"vel_absolute_max", l.vel_absolute_max},
      {"vel_angular_max", l.vel_angular_max},
      {"acc_speedup_absolute_max", l.acc_speedup_absolute_max},
      {"acc_brake_absolute_max", l.acc_brake_absolute_max},
      {"acc_speedup_angular_max", l.acc_speedup_angular_max},
      {"acc_brake_angular_max", l.acc_brake_angular_max},
  };
  for (const auto& [name, value] : positive) {
    if (!(std::isfinite(value) && value > 0)) {
      return Error{std::string("robot limit ") + name + " must be a positive number"};
    }
  }
  const std::pair<const char*, double> non_negative[] = {
      {"max_linear_kick_speed", l.max_linear_kick_speed},
      {"max_chip_kick_speed", l.max_chip_kick_speed},
      {"max_chip_angle", l.max_chip_angle},
      {"max_dribbler_rpm", l.max_dribbler_rpm},
  };
  for (const auto& [name, value] : non_negative) {
    if (!(std::isfinite(value) && value >= 0)) {
      return Error{std::string("robot limit ") + name + " must be a number >= 0"};
    }
  }
  if (config.command_timeout <= time::Duration::zero()) return Error{"command_timeout must be positive"};
  if (config.send_period <= time::Duration::zero()) return Error{"send_period must be positive"};
  if (config.startup_stop < time::Duration::zero()) return Error{"startup_stop must not be negative"};
  return {};
}

// ---------------------------------------------------------------------------------------------------------

void CommandTable::update(std::span<const RobotCommand> commands, time::Timestamp received_mono) {
  ++samples_;
  for (const RobotCommand& command : commands) {
    if (command.id >= kMaxRobots) {
      ++invalid_ids_;
      continue;
    }
    ++robot_commands_;
    auto at =
        std::lower_bound(entries_.begin(), entries_.end(), command.id,
                         [](const TimedCommand& entry, std::uint32_t id) { return entry.command.id < id; });
    if (at != entries_.end() && at->command.id == command.id) {
      *at = {command, received_mono};
    } else {
      entries_.insert(at, {command, received_mono});
    }
  }
}

// ---------------------------------------------------------------------------------------------------------

void EstopLatch::on_sample(bool engaged, std::string source, std::string reason) {
  if (engaged && !engaged_) ++engagements_;
  if (!engaged && engaged_) ++releases_;
  engaged_ = engaged;
  source_ = std::move(source);
  reason_ = std::move(reason);
}

void EstopLatch::on_writer_lost() {
  // Deliberately no state change: a crashed console or an unplugged button must not release the stop.
  if (engaged_) ++writers_lost_while_engaged_;
}

// ---------------------------------------------------------------------------------------------------------

RobotLinkCore::RobotLinkCore(const CoreConfig& config) : config_(config) {
  if (Status valid = validate(config); !valid) throw std::invalid_argument(valid.error().message);
}

Status RobotLinkCore::reconfigure(const CoreConfig& config) {
  if (Status valid = validate(config); !valid) return valid;
  config_ = config;
  return {};
}

RobotCommand RobotLinkCore::make_safe(const RobotCommand& wanted, RobotState& state, time::Duration dt) {
  const RobotLimits& limits = config_.limits;
  RobotCommand safe = wanted;

  // Speeds: non-finite -> 0, linear speed scaled down keeping its direction, angular clamped.
  safe.forward = finite_or_zero(wanted.forward, counters_);
  safe.left = finite_or_zero(wanted.left, counters_);
  const double speed = std::hypot(safe.forward, safe.left);
  if (speed > limits.vel_absolute_max) {
    const double scale = limits.vel_absolute_max / speed;
    safe.forward *= scale;
    safe.left *= scale;
    ++counters_.clamped_values;
  }
  safe.angular = clamp_value(wanted.angular, -limits.vel_angular_max, limits.vel_angular_max, counters_);

  // Acceleration: the change since the last sent velocity, speed-up or brake limit by whether the
  // commanded speed grows.
  const double seconds = time::to_seconds(dt);
  bool limited = false;
  {
    const double previous_speed = std::hypot(state.forward, state.left);
    const double target_speed = std::hypot(safe.forward, safe.left);
    const double acc =
        target_speed >= previous_speed ? limits.acc_speedup_absolute_max : limits.acc_brake_absolute_max;
    const double max_step = acc * seconds;
    const double d_forward = safe.forward - state.forward;
    const double d_left = safe.left - state.left;
    const double step = std::hypot(d_forward, d_left);
    if (step > max_step) {
      const double scale = max_step / step;
      safe.forward = state.forward + d_forward * scale;
      safe.left = state.left + d_left * scale;
      limited = true;
    }
  }
  {
    const double acc = std::abs(safe.angular) >= std::abs(state.angular) ? limits.acc_speedup_angular_max
                                                                         : limits.acc_brake_angular_max;
    limited = limit_step(state.angular, safe.angular, acc * seconds) || limited;
  }
  if (limited) ++counters_.accel_limited;

  // Kicker: a kick type's speed and angle within the spec; fields of other kick types are ignored.
  switch (wanted.kick) {
    case KickType::kNone:
      safe.kick_speed = 0;
      safe.chip_angle = 0;
      break;
    case KickType::kFlat:
      safe.kick_speed = clamp_value(wanted.kick_speed, 0, limits.max_linear_kick_speed, counters_);
      safe.chip_angle = 0;
      break;
    case KickType::kChip:
      safe.kick_speed = clamp_value(wanted.kick_speed, 0, limits.max_chip_kick_speed, counters_);
      safe.chip_angle = clamp_value(wanted.chip_angle, 0, limits.max_chip_angle, counters_);
      break;
  }
  if (safe.kick_speed == 0) {
    safe.kick = KickType::kNone;
    safe.chip_angle = 0;
  }
  safe.dribbler_rpm = clamp_value(wanted.dribbler_rpm, 0, limits.max_dribbler_rpm, counters_);

  state.forward = safe.forward;
  state.left = safe.left;
  state.angular = safe.angular;
  return safe;
}

TickOutput RobotLinkCore::step(const TickInputs& inputs, time::Timestamp now_mono) {
  time::Duration dt = config_.send_period;
  if (!started_) {
    started_ = true;
    first_tick_mono_ = now_mono;
  } else {
    // The limiter uses the real tick spacing, but a stalled loop does not earn a velocity jump.
    dt = std::clamp(now_mono - last_tick_mono_, time::Duration::zero(), 2 * config_.send_period);
  }
  last_tick_mono_ = now_mono;
  ++counters_.ticks;

  std::array<const TimedCommand*, kMaxRobots> latest{};
  for (const TimedCommand& entry : inputs.latest) {
    if (entry.command.id >= kMaxRobots) continue;
    const TimedCommand*& slot = latest[entry.command.id];
    if (slot == nullptr || slot->received_mono <= entry.received_mono) slot = &entry;
  }
  const bool in_startup = now_mono - first_tick_mono_ < config_.startup_stop;

  if (inputs.estop_engaged) {
    ++counters_.estop_ticks;
  } else if (inputs.halt) {
    ++counters_.halted_ticks;
  }

  TickOutput output;
  counters_.stale_robots = 0;
  counters_.fresh_robots = 0;
  for (std::uint32_t id = 0; id < kMaxRobots; ++id) {
    RobotState& state = robots_[id];
    const TimedCommand* entry = latest[id];
    if (entry == nullptr && !in_startup) continue;

    StopReason stop = StopReason::kNone;
    if (entry == nullptr) {
      stop = StopReason::kStartup;
      ++counters_.startup_stop_ticks;
    } else {
      const bool stale = now_mono - entry->received_mono > config_.command_timeout;
      if (stale && !state.stale) ++counters_.stale_events;
      state.stale = stale;
      if (stale) {
        ++counters_.stale_robots;
      } else {
        ++counters_.fresh_robots;
      }
      if (inputs.estop_engaged) {
        stop = StopReason::kEstop;
      } else if (inputs.halt) {
        stop = StopReason::kHalt;
      } else if (stale) {
        stop = StopReason::kStale;
        ++counters_.stale_robot_ticks;
      }
    }
    if (stop == StopReason::kStartup && inputs.estop_engaged) stop = StopReason::kEstop;
    if (stop == StopReason::kStartup && inputs.halt) stop = StopReason::kHalt;

    OutgoingCommand out;
    out.stop = stop;
    if (stop == StopReason::kNone) {
      out.command = make_safe(entry->command, state, dt);
    } else {
      out.command = stop_command(id);
      state.forward = state.left = state.angular = 0;
      ++counters_.stops_sent;
    }
    out.command.id = id;
    output.commands.push_back(out);
    ++counters_.commands_sent;
  }
  return output;
}

}  // namespace ssl::robot_link
