// The flags every service has (../shared/design.md), declared once: --config, --site, --domain,
// --log-level, --set, --print-config, and --help-config where the service describes its keys. A service adds
// its own flags beside them; add_key_flag declares one that sets a config key (--vision-port sets
// network.vision_port). CLI11 stays in flags.cpp: this header only names CLI::App.
//
//   ssl::service::CommonFlags flags;
//   CLI::App app{"planner: ...", "planner"};
//   ssl::service::add_common_flags(app, flags, {.help_config = true});
//   ssl::service::add_key_flag(app, flags, "--team", "team", "our colour: blue or yellow", {"blue", "yellow"});
//   ...parse...
//   auto config = load_planner_config(setup->config_files, flags.overrides());
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}  // namespace CLI

namespace ssl::service {

struct CommonFlags {
  std::string config_file;             // --config: a layer over the defaults and the site
  std::string site;                    // --site (else $SSL_SITE)
  int domain = 0;                      // --domain
  std::string log_level = "info";      // --log-level
  bool print_config = false;           // --print-config
  bool help_config = false;            // --help-config
  std::vector<std::string> set;        // --set key=value ...
  std::vector<std::string> named;      // key=value from the service's own flags (add_key_flag), in order

  /// Every override for the config loader: --set first, then the dedicated flags, so that a dedicated
  /// flag wins over a --set of the same key.
  std::vector<std::string> overrides() const;
};

struct CommonFlagOptions {
  bool help_config = false;  // the service offers --help-config
  std::string set_example = "key=value";  // shown in --set's help
};

void add_common_flags(CLI::App& app, CommonFlags& flags, const CommonFlagOptions& options = {});

/// A flag `flag` that sets config key `key` to its value (YAML syntax, as --set); `allowed`, when not
/// empty, lists the accepted values.
void add_key_flag(CLI::App& app, CommonFlags& flags, const std::string& flag, const std::string& key,
                  const std::string& help, const std::vector<std::string>& allowed = {});

}  // namespace ssl::service
