// EventLog: the console's last events, newest first (commands, goals, fouls, status messages, e-stop
// changes, operator actions), bounded so that a long match costs nothing.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>
#include <string>

#include "libs/common/team.h"
#include "libs/time/time.h"

namespace ssl::console {

enum class LogKind { kCommand, kGoal, kFoul, kEvent, kStatus, kEstop, kOperator };

std::string_view to_string(LogKind kind);

struct LogEntry {
  time::Timestamp at;              // console host wall clock
  LogKind kind = LogKind::kEvent;
  std::string text;
  std::optional<TeamColor> team;   // the team it concerns, if one
};

class EventLog {
 public:
  static constexpr std::size_t kCapacity = 20;

  void add(LogEntry entry);
  /// Newest first, at most kCapacity.
  const std::deque<LogEntry>& entries() const { return entries_; }

 private:
  std::deque<LogEntry> entries_;
};

}  // namespace ssl::console
