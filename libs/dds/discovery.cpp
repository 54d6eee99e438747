#include "libs/dds/discovery.h"

#include <arpa/inet.h>

#include "libs/config/config.h"

namespace ssl::dds {

namespace {

bool is_ipv4(const std::string& text) {
  in_addr address{};
  return ::inet_pton(AF_INET, text.c_str(), &address) == 1;
}

// "host:port" with an IPv4 host and a port in 1..65535.
bool is_server_address(const std::string& text) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos || !is_ipv4(text.substr(0, colon))) return false;
  const std::string port = text.substr(colon + 1);
  if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos) return false;
  const int value = std::stoi(port);
  return value >= 1 && value <= 65535;
}

// The file as written: discovery's keys at the top level beside the security section.
struct SiteDdsFile : DiscoveryConfig {
  SecurityConfig security;
};

config::Fields<SiteDdsFile> site_dds_fields() {
  using namespace config;
  using File = SiteDdsFile;
  Fields<File> fields{
      field<File, DiscoveryMode>("discovery", &File::mode)
          .values({{"multicast", DiscoveryMode::kMulticast},
                   {"server", DiscoveryMode::kServer},
                   {"peers", DiscoveryMode::kPeers}})
          .doc("multicast (standard), server (clients of `servers`) or peers (unicast to `peers`)"),
      optional_field<File, std::vector<std::string>>("servers", &File::servers, {})
          .doc("server: discovery servers as IPv4 host:port, the i-th started with fastdds discovery -i i"),
      optional_field<File, std::vector<std::string>>("peers", &File::peers, {}).doc("peers: IPv4 addresses of the hosts"),
      optional_field<File, std::uint32_t>("peer_participants", &File::peer_participants, 16u)
          .range(1u, 120u)
          .doc("peers: participants per host and domain that are contacted"),
      nested("security", &File::security, security_fields()),
  };
  fields.check([](const File& c) -> Status {
    for (const std::string& server : c.servers) {
      if (!is_server_address(server)) return Error{"servers: '" + server + "' is not an IPv4 host:port"};
    }
    for (const std::string& peer : c.peers) {
      if (!is_ipv4(peer)) return Error{"peers: '" + peer + "' is not an IPv4 address"};
    }
    if (c.mode == DiscoveryMode::kServer && c.servers.empty()) {
      return Error{"discovery: server needs at least one entry in servers"};
    }
    if (c.mode == DiscoveryMode::kPeers && c.peers.empty()) {
      return Error{"discovery: peers needs at least one entry in peers"};
    }
    if (c.mode == DiscoveryMode::kServer && c.security.enabled) {
      return Error{"discovery: server cannot be used with security.enabled: Fast DDS 2.9's discovery server "
                   "cannot authenticate its clients; use peers (or multicast)"};
    }
    return Status::success();
  });
  return fields;
}

std::string join(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

}  // namespace

Result<SiteDdsConfig> load_site_dds_config(std::span<const std::string> files,
                                           const std::vector<std::string>& overrides) {
  auto file = config::load_files(files, site_dds_fields(), overrides);
  if (!file) return file.error();
  return SiteDdsConfig{.discovery = static_cast<const DiscoveryConfig&>(*file), .security = file->security};
}

std::string describe(const DiscoveryConfig& config) {
  switch (config.mode) {
    case DiscoveryMode::kMulticast: return "multicast";
    case DiscoveryMode::kServer: return "server " + join(config.servers);
    case DiscoveryMode::kPeers: return "peers " + join(config.peers);
  }
  return "?";
}

}  // namespace ssl::dds
