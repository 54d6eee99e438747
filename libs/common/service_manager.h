// The service manager's notification protocol (systemd units of Type=notify, WatchdogSec=): a service says
// READY=1 once it is up and WATCHDOG=1 from its main loop, so that a hung loop gets it restarted. Each call
// is a no-op in a process the manager did not start (no $NOTIFY_SOCKET), so services call them always.
// dds::HealthReporter calls them on every system.health report (about once a second, from the loop).
#pragma once

#include <string_view>

namespace ssl::service_manager {

/// READY=1 with a STATUS= line (shown by `systemctl status`).
void ready(std::string_view status);
/// WATCHDOG=1 with a STATUS= line.
void alive(std::string_view status);
/// STOPPING=1: the service shuts down on purpose.
void stopping();

}  // namespace ssl::service_manager
