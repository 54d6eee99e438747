#include "services/console/core/event_log.h"

namespace ssl::console {

std::string_view to_string(LogKind kind) {
  switch (kind) {
    case LogKind::kCommand: return "command";
    case LogKind::kGoal: return "goal";
    case LogKind::kFoul: return "foul";
    case LogKind::kEvent: return "event";
    case LogKind::kStatus: return "status";
    case LogKind::kEstop: return "estop";
    case LogKind::kOperator: return "operator";
  }
  return "event";
}

void EventLog::add(LogEntry entry) {
  entries_.push_front(std::move(entry));
  if (entries_.size() > kCapacity) entries_.pop_back();
}

}  // namespace ssl::console
