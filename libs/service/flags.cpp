#include "libs/service/flags.h"

#include <CLI/CLI.hpp>

#include "libs/service/setup.h"

namespace ssl::service {

std::vector<std::string> CommonFlags::overrides() const {
  std::vector<std::string> all = set;
  all.insert(all.end(), named.begin(), named.end());
  return all;
}

void add_common_flags(CLI::App& app, CommonFlags& flags, const CommonFlagOptions& options) {
  app.add_option("--config", flags.config_file,
                 "YAML file laid over the defaults and the site (only the keys it changes)");
  app.add_option("--site", flags.site, kSiteHelp);
  app.add_option("--domain", flags.domain, "DDS domain id")->check(CLI::Range(0, 232));
  app.add_option("--log-level", flags.log_level, "trace, debug, info, warn, error, critical or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  app.add_option("--set", flags.set, "override any config key: --set " + options.set_example)->take_all();
  app.add_flag("--print-config", flags.print_config, "print the effective config and exit");
  if (options.help_config) app.add_flag("--help-config", flags.help_config, "describe every config key and exit");
}

void add_key_flag(CLI::App& app, CommonFlags& flags, const std::string& flag, const std::string& key,
                  const std::string& help, const std::vector<std::string>& allowed) {
  CLI::Option* option = app.add_option_function<std::string>(
      flag, [&flags, key](const std::string& value) { flags.named.push_back(key + "=" + value); }, help);
  if (!allowed.empty()) option->check(CLI::IsMember(allowed));
}

}  // namespace ssl::service
