// The page's files (services/console/web/), compiled into the binary by web/embed.py at build time, so that
// an installed console needs no other file and the page always matches the server.
#pragma once

#include <span>
#include <string_view>

namespace ssl::console {

struct WebAsset {
  std::string_view path;          // "/index.html", "/console.js", ...
  std::string_view content_type;
  std::string_view body;
};

std::span<const WebAsset> web_assets();

}  // namespace ssl::console
