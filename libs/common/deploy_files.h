// Finds the stack's deployment files (qos/profiles.xml, config/<service>.yaml, sites/<site>/...) wherever a
// program runs from: $SSL_DEPLOY_DIR, then relative to the executable (the build tree build/<dir>/<exe>;
// an install, /opt/ssl-stack/bin/<exe> with /etc/ssl-stack, or the same under a prefix: cmake/SslInstall.cmake),
// the working directory's deploy/, and last the source tree the binary was built from.
//
//   ssl::Result<std::string> file = ssl::find_deploy_file("config/simulator.yaml");
//
// A service's config comes in layers, lowest first: the defaults (config/<service>.yaml, complete), the
// site's file (sites/<site>/<service>.yaml: only what differs between the simulator and the real field)
// and the user's --config file (only the keys it changes); config::load_files lays them over each other.
//
//   auto layers = ssl::config_layers("vision_gateway", ssl::chosen_site(flags.site), flags.config_file);
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "libs/common/result.h"

namespace ssl {

/// The path of `relative` (relative to deploy/), or an error listing every place searched.
Result<std::string> find_deploy_file(std::string_view relative);

/// The site: `flag` (--site) when given, else $SSL_SITE, else "" (no site layer).
std::string chosen_site(const std::string& flag);

/// The directory of `site`: a name under deploy/sites/ (sim, field), or a directory path (one holding a
/// '/'). Error: an unknown name, listing the known ones.
Result<std::string> find_site(std::string_view site);

/// The config files of `service`, lowest first: config/<service>.yaml; sites/<site>/<service>.yaml when
/// `site` is set and changes something of the service; `saved_file` (run-time parameters saved by the
/// instance) when not empty and it exists; `user_file` when not empty.
Result<std::vector<std::string>> config_layers(std::string_view service, std::string_view site,
                                               const std::string& user_file, const std::string& saved_file = "");

/// Where service instance `instance` ("planner/blue") saves its run-time parameters:
/// <dir>/planner-blue.yaml, <dir> being $SSL_PARAMS_DIR, else $XDG_STATE_HOME/ssl-stack/params, else
/// ~/.local/state/ssl-stack/params (the units: /var/lib/ssl-stack/params).
std::string saved_parameters_file(std::string_view instance);

}  // namespace ssl
