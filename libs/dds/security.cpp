#include "libs/dds/security.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

namespace ssl::dds {

namespace fs = std::filesystem;

config::Fields<SecurityConfig> security_fields() {
  using namespace config;
  Fields<SecurityConfig> fields{
      optional_field("enabled", &SecurityConfig::enabled, false)
          .doc("DDS Security: authentication, access control, encryption (make the files with ./ssl certs)"),
      optional_field("directory", &SecurityConfig::directory, std::string())
          .doc("what ./ssl certs made (absolute path); empty: ~/.local/state/ssl-stack/certs ($SSL_CERTS_DIR beats both)"),
  };
  fields.check([](const SecurityConfig& c) -> Status {
    if (!c.directory.empty() && !fs::path(c.directory).is_absolute()) {
      return Error{"security.directory: '" + c.directory + "' is not an absolute path"};
    }
    return Status::success();
  });
  return fields;
}

std::string security_directory(const SecurityConfig& config) {
  if (const char* dir = std::getenv("SSL_CERTS_DIR"); dir != nullptr && *dir != '\0') return dir;
  if (!config.directory.empty()) return config.directory;
  if (const char* state = std::getenv("XDG_STATE_HOME"); state != nullptr && *state != '\0') {
    return (fs::path(state) / "ssl-stack" / "certs").string();
  }
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') {
    return (fs::path(home) / ".local" / "state" / "ssl-stack" / "certs").string();
  }
  return "/var/lib/ssl-stack/certs";
}

namespace {

Status check_readable(const fs::path& file, const std::string& directory) {
  std::error_code error;
  if (!fs::is_regular_file(file, error)) {
    return Error{"DDS security: " + file.string() + " does not exist (make the files with ./ssl certs --dir " +
                 directory + ")"};
  }
  if (::access(file.c_str(), R_OK) != 0) {
    return Error{"DDS security: " + file.string() + " is not readable by this user"};
  }
  return Status::success();
}

}  // namespace

Result<SecurityFiles> security_files(const SecurityConfig& config, std::string_view identity) {
  const std::string directory = security_directory(config);
  if (identity.empty() || identity.find('/') != std::string_view::npos || identity == "." || identity == "..") {
    return Error{"DDS security: '" + std::string(identity) + "' is not an identity name"};
  }
  const fs::path root(directory);
  const fs::path own = root / std::string(identity);
  SecurityFiles files{
      .ca = (root / "ca.pem").string(),
      .governance = (root / "governance.p7s").string(),
      .certificate = (own / "cert.pem").string(),
      .private_key = (own / "key.pem").string(),
      .permissions = (own / "permissions.p7s").string(),
  };
  for (const std::string* file : {&files.ca, &files.governance, &files.certificate, &files.private_key,
                                  &files.permissions}) {
    if (Status readable = check_readable(*file, directory); !readable) return readable.error();
  }
  return files;
}

std::string describe(const SecurityConfig& config, std::string_view identity) {
  if (!config.enabled) return "off";
  return "on (identity " + std::string(identity) + ", " + security_directory(config) + ")";
}

namespace identity {

std::string team_stack(TeamColor team) { return std::string(to_string(team)); }

std::string operator_of(std::optional<TeamColor> team) {
  return team ? std::string(to_string(*team)) + "-operator" : std::string("operator");
}

}  // namespace identity

}  // namespace ssl::dds
