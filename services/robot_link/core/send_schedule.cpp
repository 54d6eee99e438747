#include "services/robot_link/core/send_schedule.h"

#include <algorithm>
#include <stdexcept>

namespace ssl::robot_link {

SendSchedule::SendSchedule(time::Duration period, time::Timestamp start)
    : period_(period), full_at_(start), last_sent_(start - period) {
  if (period <= time::Duration::zero()) throw std::invalid_argument("SendSchedule: period must be positive");
}

time::Timestamp SendSchedule::holds(int tokens) const { return full_at_ - (kBurst - tokens) * period_; }

time::Timestamp SendSchedule::next_send(Waiting waiting) const {
  switch (waiting) {
    case Waiting::kStop: return last_sent_;
    case Waiting::kInput: return holds(1);
    case Waiting::kNothing: break;
  }
  return std::max(last_sent_ + period_, holds(kBurst));
}

void SendSchedule::on_sent(time::Timestamp now) {
  full_at_ = std::max(full_at_, now) + period_;
  last_sent_ = now;
}

}  // namespace ssl::robot_link
