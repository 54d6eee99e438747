// Finds the project's deployment files (deploy/qos/profiles.xml, deploy/config/<service>.yaml) wherever a
// program runs from: $SSL_DEPLOY_DIR, then relative to the executable (build tree build/<dir>/<exe>, or an
// install prefix <prefix>/bin/<exe> with <prefix>/share/ssl), the working directory, and last the source
// tree the binary was built from.
//
//   ssl::Result<std::string> file = ssl::find_deploy_file("config/simulator.yaml");
#pragma once

#include <string>
#include <string_view>

#include "libs/common/result.h"

namespace ssl {

/// The path of `relative` (relative to deploy/), or an error listing every place searched.
Result<std::string> find_deploy_file(std::string_view relative);

}  // namespace ssl
