#include "libs/common/deploy_files.h"

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace ssl {

namespace fs = std::filesystem;

Result<std::string> find_deploy_file(std::string_view relative) {
  std::vector<fs::path> roots;
  if (const char* env = std::getenv("SSL_DEPLOY_DIR"); env != nullptr && *env != '\0') roots.emplace_back(env);
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    roots.push_back(exe.parent_path() / "../../deploy");     // build/<dir>/<exe>
    roots.push_back(exe.parent_path() / "../share/ssl");     // <prefix>/bin/<exe>
  }
  roots.push_back(fs::current_path(error) / "deploy");
  roots.push_back(fs::path(SSL_SOURCE_DIR) / "deploy");     // the tree this binary was built from
  std::string tried;
  for (const fs::path& root : roots) {
    const fs::path candidate = root / relative;
    if (fs::exists(candidate, error)) return fs::weakly_canonical(candidate, error).string();
    tried += " " + candidate.string();
  }
  return Error{"cannot find deploy/" + std::string(relative) + " (tried:" + tried + "); set SSL_DEPLOY_DIR"};
}

}  // namespace ssl
