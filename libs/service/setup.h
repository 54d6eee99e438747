// What every executable of the stack does before its own work: pick the site (--site, else $SSL_SITE),
// find the service's config layers for it, and load the site's DDS discovery. One place, so that the
// services, sslctl and the units all agree on what a site means.
//
//   auto setup = ssl::service::prepare("planner", flags.site, flags.config_file);
//   if (!setup) { logger->critical("{}", setup.error().message); return 1; }
//   auto config = ssl::planner::load_planner_config(setup->config_files, overrides);
//   auto participant = ssl::dds::Participant::create({.domain_id = d, .name = n, .discovery = setup->discovery});
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "libs/common/result.h"
#include "libs/dds/discovery.h"

namespace ssl::service {

struct Setup {
  std::string site;                        // "" without a site
  std::vector<std::string> config_files;   // the service's config layers, lowest first
  dds::DiscoveryConfig discovery;          // the site's (deploy/config/dds.yaml + sites/<site>/dds.yaml)
};

/// `service`: the config's name (config/<service>.yaml), or "" for a program without one (sslctl);
/// `site_flag`: --site; `config_file`: --config, laid over the defaults and the site.
Result<Setup> prepare(std::string_view service, const std::string& site_flag, const std::string& config_file);

/// "site sim: /etc/ssl-stack/config/planner.yaml + .../sites/sim/planner.yaml; discovery multicast": the
/// startup log line.
std::string describe(const Setup& setup);

/// The --site flag's help text.
inline constexpr const char* kSiteHelp =
    "site: sim, field or a directory of site files (default $SSL_SITE; none: the defaults only)";

}  // namespace ssl::service
