#include "services/robot_link/adapter/link_runner.h"

namespace ssl::robot_link {
namespace {

bool same(const FeedbackReport& a, const FeedbackReport& b) {
  return a.robot_id == b.robot_id && a.ball_in_dribbler == b.ball_in_dribbler &&
         a.battery_voltage == b.battery_voltage && a.kicker_charge == b.kicker_charge &&
         a.link_quality == b.link_quality;
}

}  // namespace

void InputMailbox::on_commands(std::span<const RobotCommand> commands, time::Timestamp received_mono) {
  std::lock_guard lock(mutex_);
  table_.update(commands, received_mono);
}

void InputMailbox::on_wrong_team() {
  std::lock_guard lock(mutex_);
  ++wrong_team_;
}

void InputMailbox::on_referee(bool halt) {
  std::lock_guard lock(mutex_);
  halt_ = halt;
}

void InputMailbox::on_estop(bool engaged, std::string source, std::string reason) {
  std::lock_guard lock(mutex_);
  estop_.on_sample(engaged, std::move(source), std::move(reason));
}

void InputMailbox::on_estop_writer_lost() {
  std::lock_guard lock(mutex_);
  estop_.on_writer_lost();
}

bool InputMailbox::estop_engaged() const {
  std::lock_guard lock(mutex_);
  return estop_.engaged();
}

InputMailbox::Snapshot InputMailbox::snapshot() const {
  std::lock_guard lock(mutex_);
  Snapshot snapshot;
  snapshot.latest.assign(table_.latest().begin(), table_.latest().end());
  snapshot.halt = halt_;
  snapshot.estop_engaged = estop_.engaged();
  snapshot.estop_source = estop_.source();
  snapshot.estop_reason = estop_.reason();
  snapshot.command_samples = table_.samples();
  snapshot.robot_commands = table_.robot_commands();
  snapshot.invalid_ids = table_.invalid_ids();
  snapshot.wrong_team = wrong_team_;
  snapshot.estop_engagements = estop_.engagements();
  snapshot.estop_writers_lost_while_engaged = estop_.writers_lost_while_engaged();
  return snapshot;
}

// ---------------------------------------------------------------------------------------------------------

LinkRunner::LinkRunner(const CoreConfig& config, Backend& backend, InputMailbox& mailbox)
    : core_(config), backend_(backend), mailbox_(mailbox) {}

SendSchedule::Waiting LinkRunner::waiting(const InputMailbox::Snapshot& inputs) const {
  using Waiting = SendSchedule::Waiting;
  if ((inputs.estop_engaged && !sent_estop_) || (inputs.halt && !sent_halt_)) return Waiting::kStop;
  if (inputs.command_samples != sent_command_samples_ || inputs.halt != sent_halt_ ||
      inputs.estop_engaged != sent_estop_) {
    return Waiting::kInput;
  }
  return Waiting::kNothing;
}

std::optional<TickResult> LinkRunner::poll(time::Timestamp now_mono) {
  if (!schedule_) schedule_.emplace(core_.config().send_period, now_mono);
  waiting_ = waiting(mailbox_.snapshot());
  if (now_mono < schedule_->next_send(waiting_)) return std::nullopt;
  const SendSchedule::Waiting cause = waiting_;
  TickResult result = send(now_mono);
  result.cause = cause;
  waiting_ = SendSchedule::Waiting::kNothing;  // the packet carried everything in the mailbox
  return result;
}

time::Timestamp LinkRunner::next_send() const {
  // Before the first poll() nothing was decided yet: poll at once.
  return schedule_ ? schedule_->next_send(waiting_) : time::Timestamp::min();
}

TickResult LinkRunner::send(time::Timestamp now_mono) {
  TickResult result;
  result.now_mono = now_mono;
  result.cause = SendSchedule::Waiting::kNothing;
  result.inputs = mailbox_.snapshot();
  // Feedback first, so that nothing but the send itself lies between the decision and the packet leaving.
  result.feedback = backend_.poll_feedback();
  result.output = core_.step({.latest = result.inputs.latest,
                              .halt = result.inputs.halt,
                              .estop_engaged = result.inputs.estop_engaged},
                             now_mono);
  if (!result.output.commands.empty()) result.sent = backend_.send(result.output.commands);
  if (schedule_) schedule_->on_sent(now_mono);
  sent_command_samples_ = result.inputs.command_samples;
  sent_halt_ = result.inputs.halt;
  sent_estop_ = result.inputs.estop_engaged;
  return result;
}

void LinkRunner::run(time::Clock& clock, const std::function<bool()>& keep_running,
                     const std::function<void(time::Timestamp)>& take_inputs,
                     const std::function<bool(time::Timestamp)>& wait_until,
                     const std::function<void(const TickResult&)>& after_send) {
  while (keep_running() && !clock.stopped()) {
    const time::Timestamp now = clock.now();
    if (take_inputs) take_inputs(now);
    if (std::optional<TickResult> result = poll(now); result && after_send) after_send(*result);
    if (!wait_until(next_send())) break;
  }
}

Status LinkRunner::send_final_stop(time::Timestamp now_mono) {
  InputMailbox::Snapshot inputs = mailbox_.snapshot();
  const TickOutput output =
      core_.step({.latest = inputs.latest, .halt = true, .estop_engaged = true}, now_mono);
  if (output.commands.empty()) return {};
  return backend_.send(output.commands);
}

// ---------------------------------------------------------------------------------------------------------

std::vector<FeedbackReport> FeedbackThrottle::update(std::span<const FeedbackReport> reports,
                                                     time::Timestamp now_mono) {
  for (const FeedbackReport& report : reports) {
    if (report.robot_id >= kMaxRobots) continue;
    Entry& entry = robots_[report.robot_id];
    entry.seen = true;
    entry.merged.robot_id = report.robot_id;
    if (report.ball_in_dribbler) entry.merged.ball_in_dribbler = report.ball_in_dribbler;
    if (report.battery_voltage) entry.merged.battery_voltage = report.battery_voltage;
    if (report.kicker_charge) entry.merged.kicker_charge = report.kicker_charge;
    if (report.link_quality) entry.merged.link_quality = report.link_quality;
  }
  std::vector<FeedbackReport> out;
  for (std::size_t id = 0; id < kMaxRobots; ++id) {
    Entry& entry = robots_[id];
    if (!entry.seen) continue;
    const bool changed = !entry.published || !same(entry.merged, entry.last_published);
    const bool due = entry.published && now_mono - entry.published_mono >= heartbeat_;
    if (!changed && !due) continue;
    // A heartbeat only repeats what a robot still reports: one that fell silent is not republished.
    if (!changed) {
      bool reported = false;
      for (const FeedbackReport& report : reports) reported = reported || report.robot_id == id;
      if (!reported) continue;
    }
    entry.published = true;
    entry.last_published = entry.merged;
    entry.published_mono = now_mono;
    out.push_back(entry.merged);
  }
  return out;
}

std::vector<std::pair<std::uint32_t, double>> FeedbackThrottle::link_quality() const {
  std::vector<std::pair<std::uint32_t, double>> qualities;
  for (const Entry& entry : robots_) {
    if (entry.seen && entry.merged.link_quality)
      qualities.emplace_back(entry.merged.robot_id, *entry.merged.link_quality);
  }
  return qualities;
}

}  // namespace ssl::robot_link
