// SendSchedule: WHEN robot_link sends its next command packet, as a pure function of what is waiting and
// of the packets sent so far (no clocks, no threads; time is an argument, host MONOTONIC clock).
//
// The radio's rate (1 / `period`, robot_link's send_rate) is kept by a token bucket of kBurst tokens,
// refilled at that rate; every packet takes one token. What is waiting decides when the next packet leaves:
//   kStop      a new safety stop (e-stop engaged, HALT began): at once, token or not. It still takes a
//              token (the bucket may go into debt), so the packets that follow pay it back.
//   kInput     something new (a robot.commands sample, HALT lifted, e-stop released): at once when the
//              bucket holds a token, else when it next holds one, so it waits at most one period.
//   kNothing   the heartbeat, the last commands again: `period` after the last packet, once the bucket
//              holds kBurst tokens: a heartbeat leaves a token for the next input, which therefore never
//              waits behind a heartbeat. With nothing arriving that is exactly every period; packets are
//              never more than kBurst periods apart.
// Over any window of length T at most kBurst + T / period packets leave (plus one per new stop).
//
//   SendSchedule schedule(send_period, now);               // the first packet is due at once
//   if (now >= schedule.next_send(waiting)) { send(...); schedule.on_sent(now); }
//   wait_until(schedule.next_send(waiting));               // or until an input arrives
#pragma once

#include "libs/time/time.h"

namespace ssl::robot_link {

class SendSchedule {
 public:
  /// Tokens the bucket holds when full: two packets may leave back to back (an input right after a
  /// heartbeat), never more.
  static constexpr int kBurst = 2;

  enum class Waiting { kNothing, kInput, kStop };

  /// The bucket is full and the first heartbeat due at `start`. @throws std::invalid_argument if period <= 0.
  SendSchedule(time::Duration period, time::Timestamp start);

  /// The earliest time the next packet may leave with `waiting` pending (in the past or now: at once).
  time::Timestamp next_send(Waiting waiting) const;

  /// A packet left at `now` (not before the previous one).
  void on_sent(time::Timestamp now);

  time::Duration period() const noexcept { return period_; }

 private:
  /// When the bucket holds `tokens` tokens again (1..kBurst), with no packet sent meanwhile.
  time::Timestamp holds(int tokens) const;

  time::Duration period_;
  time::Timestamp full_at_;    // the bucket holds kBurst tokens from then on
  time::Timestamp last_sent_;  // the last packet (start - period before the first)
};

}  // namespace ssl::robot_link
