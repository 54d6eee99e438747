// DDS Security between teams: authentication (PKI-DH), access control (Permissions) and encryption
// (AES-GCM-GMAC), Fast DDS's builtin plugins, with the files `./ssl certs` makes (deploy/dds-certs.sh says
// what each identity may do and why). The site's dds config turns it on:
//
//   security:
//     enabled: true
//     directory: /etc/ssl-stack/certs   # "": ~/.local/state/ssl-stack/certs; $SSL_CERTS_DIR beats both
//
// A process picks its identity from what it is (the names below); Participant::create then loads
// <directory>/ca.pem, governance.p7s and <directory>/<identity>/{cert.pem,key.pem,permissions.p7s}.
//
//   auto participant = ssl::dds::Participant::create({.domain_id = 3, .discovery = setup->discovery,
//       .security = setup->security, .identity = ssl::dds::identity::team_stack(team)});
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "libs/common/result.h"
#include "libs/common/team.h"
#include "libs/config/config.h"

namespace ssl::dds {

struct SecurityConfig {
  bool enabled = false;
  std::string directory;  // what `./ssl certs` made; see security_directory()
};

/// The `security` section of the site's dds config (libs/dds/discovery.h loads the file).
config::Fields<SecurityConfig> security_fields();

/// Where the files are: $SSL_CERTS_DIR (tests, or a PC that keeps them elsewhere), else the config's
/// directory, else $XDG_STATE_HOME/ssl-stack/certs, else ~/.local/state/ssl-stack/certs (`./ssl certs`
/// resolves it the same way).
std::string security_directory(const SecurityConfig& config);

/// The files of one identity, each checked to exist and be readable.
struct SecurityFiles {
  std::string ca;           // identity CA and permissions CA
  std::string governance;   // signed
  std::string certificate;
  std::string private_key;
  std::string permissions;  // signed
};

/// The files of `identity` under the config's directory; an error naming the first missing or unreadable
/// file and how to make it.
Result<SecurityFiles> security_files(const SecurityConfig& config, std::string_view identity);

/// "off", "on (identity blue, /etc/ssl-stack/certs)": for logs.
std::string describe(const SecurityConfig& config, std::string_view identity);

/// Who a process is, as deploy/dds-certs.sh names the identities.
namespace identity {
/// vision_gateway, referee_gateway, simulator: shared topics only.
inline constexpr std::string_view kSharedServices = "shared";
/// world_model, planner, robot_link of `team`.
std::string team_stack(TeamColor team);
/// console or sslctl: of one team ("blue-operator"), or of every team of the trust domain ("operator").
std::string operator_of(std::optional<TeamColor> team);
}  // namespace identity

}  // namespace ssl::dds
