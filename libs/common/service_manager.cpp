#include "libs/common/service_manager.h"

#include <systemd/sd-daemon.h>

#include <string>

namespace ssl::service_manager {

namespace {

// STATUS= is one line: newlines would end the assignment.
std::string status_line(std::string_view status) {
  std::string line(status);
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return line;
}

}  // namespace

void ready(std::string_view status) {
  (void)sd_notify(0, ("READY=1\nSTATUS=" + status_line(status)).c_str());
}

void alive(std::string_view status) {
  (void)sd_notify(0, ("WATCHDOG=1\nSTATUS=" + status_line(status)).c_str());
}

void stopping() { (void)sd_notify(0, "STOPPING=1"); }

}  // namespace ssl::service_manager
