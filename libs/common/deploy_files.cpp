#include "libs/common/deploy_files.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <vector>

namespace ssl {

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> deploy_roots() {
  std::vector<fs::path> roots;
  if (const char* env = std::getenv("SSL_DEPLOY_DIR"); env != nullptr && *env != '\0') roots.emplace_back(env);
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    roots.push_back(exe.parent_path() / "../../deploy");                // build/<dir>/<exe>
    roots.push_back(exe.parent_path() / "../../../etc/ssl-stack");      // <root>/opt/ssl-stack/bin/<exe>
  }
  roots.push_back(fs::current_path(error) / "deploy");
  roots.push_back(fs::path(SSL_SOURCE_DIR) / "deploy");         // the tree this binary was built from
  return roots;
}

}  // namespace

Result<std::string> find_deploy_file(std::string_view relative) {
  std::string tried;
  std::error_code error;
  for (const fs::path& root : deploy_roots()) {
    const fs::path candidate = root / relative;
    if (fs::exists(candidate, error)) return fs::weakly_canonical(candidate, error).string();
    tried += ' ';
    tried += candidate.string();
  }
  return Error{"cannot find deploy/" + std::string(relative) + " (tried:" + tried + "); set SSL_DEPLOY_DIR"};
}

std::string chosen_site(const std::string& flag) {
  if (!flag.empty()) return flag;
  const char* env = std::getenv("SSL_SITE");
  return env != nullptr ? env : "";
}

Result<std::string> find_site(std::string_view site) {
  std::error_code error;
  if (site.find('/') != std::string_view::npos) {
    if (!fs::is_directory(site, error)) return Error{"site directory '" + std::string(site) + "' does not exist"};
    return fs::weakly_canonical(site, error).string();
  }
  if (site.empty() || site == "." || site == "..") return Error{"empty site name"};
  auto found = find_deploy_file("sites/" + std::string(site));
  if (found && fs::is_directory(*found, error)) return found;
  std::vector<std::string> known;
  if (auto sites = find_deploy_file("sites"); sites) {
    for (const fs::directory_entry& entry : fs::directory_iterator(*sites, error)) {
      if (entry.is_directory(error)) known.push_back(entry.path().filename().string());
    }
  }
  std::sort(known.begin(), known.end());
  std::string list;
  for (const std::string& name : known) list += (list.empty() ? "" : ", ") + name;
  return Error{"unknown site '" + std::string(site) + "' (known: " + (list.empty() ? "none found" : list) +
               "; or give a directory)"};
}

Result<std::vector<std::string>> config_layers(std::string_view service, std::string_view site,
                                               const std::string& user_file, const std::string& saved_file) {
  auto defaults = find_deploy_file("config/" + std::string(service) + ".yaml");
  if (!defaults) return defaults.error();
  std::vector<std::string> layers{*defaults};
  if (!site.empty()) {
    auto directory = find_site(site);
    if (!directory) return directory.error();
    const fs::path layer = fs::path(*directory) / (std::string(service) + ".yaml");
    std::error_code error;
    if (fs::exists(layer, error)) layers.push_back(layer.string());
  }
  if (!saved_file.empty()) {
    std::error_code error;
    if (fs::exists(saved_file, error)) layers.push_back(saved_file);
  }
  if (!user_file.empty()) layers.push_back(user_file);
  return layers;
}

std::string saved_parameters_file(std::string_view instance) {
  fs::path directory;
  if (const char* dir = std::getenv("SSL_PARAMS_DIR"); dir != nullptr && *dir != '\0') {
    directory = dir;
  } else if (const char* state = std::getenv("XDG_STATE_HOME"); state != nullptr && *state != '\0') {
    directory = fs::path(state) / "ssl-stack" / "params";
  } else if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') {
    directory = fs::path(home) / ".local" / "state" / "ssl-stack" / "params";
  } else {
    directory = "/var/lib/ssl-stack/params";
  }
  std::string name(instance);
  for (char& c : name) {
    if (c == '/') c = '-';
  }
  return (directory / (name + ".yaml")).string();
}

}  // namespace ssl
