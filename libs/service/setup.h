// What every executable of the stack does before its own work: pick the site (--site, else $SSL_SITE),
// find the service's config layers for it, and load the site's DDS discovery and security. One place, so that the
// services, sslctl and the units all agree on what a site means.
//
//   auto setup = ssl::service::prepare("planner", flags.site, flags.config_file);
//   if (!setup) { logger->critical("{}", setup.error().message); return 1; }
//   auto config = ssl::planner::load_planner_config(setup->config_files, overrides);
//   auto participant = ssl::dds::Participant::create({.domain_id = d, .name = n, .discovery = setup->discovery,
//       .security = setup->security, .identity = ssl::dds::identity::team_stack(team)});
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "libs/common/result.h"
#include "libs/dds/discovery.h"

namespace ssl::service {

struct Setup {
  std::string site;                        // "" without a site
  std::vector<std::string> config_files;   // the service's config layers, lowest first
  std::string saved_parameters;            // where the instance saves its run-time parameters ("" none)
  dds::DiscoveryConfig discovery;          // the site's (deploy/config/dds.yaml + sites/<site>/dds.yaml)
  dds::SecurityConfig security;            // the same files' security section
};

/// `service`: the config's name (config/<service>.yaml), or "" for a program without one (sslctl);
/// `site_flag`: --site; `config_file`: --config, laid over the defaults and the site; `instance`
/// ("planner/blue"): a service with run-time parameters, whose saved ones are a layer under --config.
Result<Setup> prepare(std::string_view service, const std::string& site_flag, const std::string& config_file,
                      std::string_view instance = "");

/// prepare() and the config of a service instance with run-time parameters, whose instance name comes
/// from its config (the team): loaded once to learn the instance, and again when that instance saved
/// parameters (a layer under --config). `load(config_files)` loads the config with the flags' overrides.
template <typename Config, typename Load, typename InstanceOf>
Result<std::pair<Setup, Config>> prepare_instance(std::string_view service, const std::string& site_flag,
                                                  const std::string& config_file, Load load, InstanceOf instance_of) {
  auto setup = prepare(service, site_flag, config_file);
  if (!setup) return setup.error();
  Result<Config> config = load(setup->config_files);
  if (!config) return config.error();
  auto with_saved = prepare(service, site_flag, config_file, instance_of(*config));
  if (!with_saved) return with_saved.error();
  if (with_saved->config_files != setup->config_files) {
    config = load(with_saved->config_files);
    if (!config) return config.error();
  }
  return std::pair<Setup, Config>{std::move(*with_saved), std::move(*config)};
}

/// "site sim, config /etc/ssl-stack/config/planner.yaml + .../sites/sim/planner.yaml, discovery multicast,
/// DDS security off": the startup log line (`identity`: the process's, libs/dds/security.h).
std::string describe(const Setup& setup, std::string_view identity);

/// The --site flag's help text.
inline constexpr const char* kSiteHelp =
    "site: sim, field or a directory of site files (default $SSL_SITE; none: the defaults only)";

}  // namespace ssl::service
