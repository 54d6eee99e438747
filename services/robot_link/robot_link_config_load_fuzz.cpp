// libFuzzer target: robot_link's config loader (libs/config under robot_link's schema) on each input, the
// way the service loads it: as a whole config file, and as the user's --config layer over the deployed
// defaults (ssl::config_layers). Bad input must give an error, never a crash, a sanitizer report or a leak.
// Of a config it accepts it checks to_yaml's promise: the printed config loads again into the same config.
// Seeds: tests/fuzz/corpus/robot_link_config_load_fuzz. Run with tests/fuzz/run.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "libs/common/deploy_files.h"
#include "services/robot_link/robot_link_config.h"

namespace {

using ssl::robot_link::load_robot_link_config;
using ssl::robot_link::robot_link_config_yaml;

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "robot_link_config_load_fuzz: %s\n", what.c_str());
  std::abort();
}

/// A file in memory (no disk, nothing left behind): the loader reads files by path, as the service does.
class MemoryFile {
 public:
  explicit MemoryFile(const char* name) : fd_(memfd_create(name, 0)) {
    if (fd_ < 0) fail("memfd_create failed");
  }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;
  ~MemoryFile() { close(fd_); }

  void write(std::string_view text) const {
    if (ftruncate(fd_, 0) != 0 ||
        pwrite(fd_, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size())) {
      fail("cannot write the in-memory config file");
    }
  }
  std::string path() const { return "/proc/self/fd/" + std::to_string(fd_); }

 private:
  int fd_;
};

struct ConfigFiles {
  ConfigFiles() {
    auto found = ssl::config_layers("robot_link", "", input.path());
    if (!found) fail(found.error().message);
    layers = std::move(*found);
  }

  MemoryFile input{"fuzz_input.yaml"};
  MemoryFile printed{"printed_config.yaml"};
  std::vector<std::string> layers;  // deploy/config/robot_link.yaml, then the input
};

const ConfigFiles& files() {
  static const ConfigFiles instance;
  return instance;
}

void check_printed_config_loads_back(const ssl::robot_link::RobotLinkConfig& config) {
  const std::string printed = robot_link_config_yaml(config);
  files().printed.write(printed);
  auto reloaded = load_robot_link_config(files().printed.path(), {});
  if (!reloaded) fail("the printed config does not load: " + reloaded.error().message + "\n" + printed);
  if (robot_link_config_yaml(*reloaded) != printed) {
    fail("the printed config loads as another one:\n" + printed);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  files().input.write(std::string_view(reinterpret_cast<const char*>(data), size));
  auto whole_file = load_robot_link_config(files().input.path(), {});
  if (whole_file) check_printed_config_loads_back(*whole_file);
  auto over_defaults = load_robot_link_config(files().layers, {});
  if (over_defaults) check_printed_config_loads_back(*over_defaults);
  return 0;
}
