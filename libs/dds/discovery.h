// How this process's participant finds the others on the network: the site's choice (deploy/config/dds.yaml,
// laid over by sites/<site>/dds.yaml), the same for every process of a host. The same file's `security`
// section is libs/dds/security.h's.
//
//   multicast: the standard DDS discovery (SPDP announcements on 239.255.0.1); needs a network that passes
//              multicast between the hosts.
//   server:    every participant is a client of the discovery servers in `servers` ("host:port", the
//              i-th being `fastdds discovery -i i -l host -p port`); no multicast needed.
//   peers:     announcements go by unicast to the hosts in `peers` (IPv4 addresses; each host's first
//              `peer_participants` participants of the domain are contacted); no multicast, no server.
//
//   auto dds = ssl::dds::load_site_dds_config(*ssl::config_layers("dds", site, ""));
//   auto participant = ssl::dds::Participant::create({.domain_id = 3, .discovery = dds->discovery});
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "libs/common/result.h"
#include "libs/dds/security.h"

namespace ssl::dds {

enum class DiscoveryMode { kMulticast, kServer, kPeers };

struct DiscoveryConfig {
  DiscoveryMode mode = DiscoveryMode::kMulticast;
  std::vector<std::string> servers;   // kServer: "host:port", in server-id order
  std::vector<std::string> peers;     // kPeers: IPv4 addresses of the hosts (this one may be listed too)
  std::uint32_t peer_participants = 16;  // kPeers: participants per host and domain that are contacted
};

/// The site's dds config: discovery and security.
struct SiteDdsConfig {
  DiscoveryConfig discovery;
  SecurityConfig security;
};

/// Loads the layered dds config (ssl::config_layers("dds", ...)); `overrides` as "key=value".
Result<SiteDdsConfig> load_site_dds_config(std::span<const std::string> files,
                                           const std::vector<std::string>& overrides = {});

/// "multicast", "server 198.18.0.1:11811", "peers 198.18.0.1, 198.18.0.2": for logs.
std::string describe(const DiscoveryConfig& config);

}  // namespace ssl::dds
