#include "libs/dds/participant.h"

#include "libs/common/deploy_files.h"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <set>

namespace ssl::dds {

namespace fdds = eprosima::fastdds::dds;
namespace fs = std::filesystem;

namespace detail {

ParticipantState::~ParticipantState() {
  if (participant == nullptr) return;
  // Writers and readers are gone (they hold this state); delete what is left, then the participant.
  participant->delete_contained_entities();
  fdds::DomainParticipantFactory::get_instance()->delete_participant(participant);
}

WriterEntities::~WriterEntities() {
  if (writer != nullptr) publisher->delete_datawriter(writer);
}

ReaderEntities::~ReaderEntities() {
  if (reader != nullptr) subscriber->delete_datareader(reader);
}

void WriterStatus::on_publication_matched(fdds::DataWriter*, const fdds::PublicationMatchedStatus& info) {
  {
    std::lock_guard lock(mutex);
    matched = static_cast<std::size_t>(info.current_count);
  }
  changed.notify_all();
}

void WriterStatus::on_offered_deadline_missed(fdds::DataWriter*, const fdds::OfferedDeadlineMissedStatus&) {
  ++deadlines_missed;
}

void WriterStatus::on_offered_incompatible_qos(fdds::DataWriter*, const fdds::OfferedIncompatibleQosStatus&) {
  ++incompatible_qos;
}

void WriterStatus::on_liveliness_lost(fdds::DataWriter*, const fdds::LivelinessLostStatus&) { ++liveliness_lost; }

bool WriterStatus::wait_for_matches(std::size_t count, std::chrono::nanoseconds timeout) {
  std::unique_lock lock(mutex);
  return changed.wait_for(lock, timeout, [&] { return matched >= count; });
}

void ReaderStatus::on_data_available(fdds::DataReader* reader) {
  if (on_data) on_data(reader);
  {
    std::lock_guard lock(mutex);
    ++data_signals;
  }
  changed.notify_all();
}

void ReaderStatus::on_subscription_matched(fdds::DataReader*, const fdds::SubscriptionMatchedStatus& info) {
  {
    std::lock_guard lock(mutex);
    matched = static_cast<std::size_t>(info.current_count);
  }
  changed.notify_all();
}

void ReaderStatus::on_requested_deadline_missed(fdds::DataReader*,
                                                const fdds::RequestedDeadlineMissedStatus&) {
  ++deadlines_missed;
}

void ReaderStatus::on_requested_incompatible_qos(fdds::DataReader*,
                                                 const fdds::RequestedIncompatibleQosStatus&) {
  ++incompatible_qos;
}

void ReaderStatus::on_sample_lost(fdds::DataReader*, const fdds::SampleLostStatus& info) {
  samples_lost += static_cast<std::uint64_t>(info.total_count_change);
}

void ReaderStatus::on_liveliness_changed(fdds::DataReader*, const fdds::LivelinessChangedStatus& info) {
  {
    std::lock_guard lock(mutex);
    alive_writers = info.alive_count;
  }
  changed.notify_all();
}

bool ReaderStatus::wait_for_matches(std::size_t count, std::chrono::nanoseconds timeout) {
  std::unique_lock lock(mutex);
  return changed.wait_for(lock, timeout, [&] { return matched >= count; });
}

bool ReaderStatus::wait_for_data(std::chrono::nanoseconds timeout) {
  std::unique_lock lock(mutex);
  if (!changed.wait_for(lock, timeout, [&] { return data_signals != data_consumed; })) return false;
  data_consumed = data_signals;
  return true;
}

std::int64_t to_unix_ns(const eprosima::fastrtps::rtps::Time_t& time) {
  return static_cast<std::int64_t>(time.seconds()) * 1'000'000'000 + static_cast<std::int64_t>(time.nanosec());
}

}  // namespace detail

namespace {

/// Loads an XML profiles file into the process-wide Fast DDS factory once. The factory is Fast DDS's own
/// singleton, so the record of loaded files has to be process-wide too.
Status load_profiles_once(const std::string& path) {
  static std::mutex mutex;
  static std::set<std::string> loaded;
  std::lock_guard lock(mutex);
  if (loaded.count(path) != 0) return {};
  if (!fs::exists(path)) return Error{"QoS profiles file '" + path + "' does not exist"};
  if (fdds::DomainParticipantFactory::get_instance()->load_XML_profiles_file(path) != ReturnCode_t::RETCODE_OK) {
    return Error{"QoS profiles file '" + path + "' could not be parsed (Fast DDS printed the reason)"};
  }
  loaded.insert(path);
  return {};
}

std::string partition_profile(TopicScope scope, std::optional<TeamColor> team, std::string_view kind) {
  if (scope == TopicScope::kShared) return "shared." + std::string(kind);
  if (!team) return "teams." + std::string(kind);  // kTeamAddressed, to every team
  return "team." + std::string(to_string(*team)) + "." + std::string(kind);
}

// Why creating an endpoint may have failed besides its QoS.
std::string denied_hint(const detail::ParticipantState& state) {
  if (state.security_identity.empty()) return "";
  return ", or DDS Security's permissions of identity '" + state.security_identity + "' deny it";
}

Status check_team(std::string_view topic, TopicScope scope, std::optional<TeamColor> team) {
  if (scope == TopicScope::kTeam && !team) {
    return Error{"topic '" + std::string(topic) + "' is team-scoped: a team (blue or yellow) is required"};
  }
  if (scope == TopicScope::kShared && team) {
    return Error{"topic '" + std::string(topic) + "' is shared by both teams: no team may be given"};
  }
  return {};
}

Result<fdds::Topic*> find_or_create_topic(detail::ParticipantState& state, std::string_view name,
                                          std::unique_ptr<fdds::TopicDataType> support) {
  const std::string key(name);
  if (auto it = state.topics.find(key); it != state.topics.end()) return it->second;
  fdds::TypeSupport type(support.release());
  const std::string type_name = type.get_type_name();
  // Registering an already registered type of the same name is accepted by Fast DDS.
  if (type.register_type(state.participant) != ReturnCode_t::RETCODE_OK) {
    return Error{"cannot register DDS type '" + type_name + "'"};
  }
  fdds::Topic* topic = state.participant->create_topic(key, type_name, fdds::TOPIC_QOS_DEFAULT);
  if (topic == nullptr) return Error{"cannot create DDS topic '" + key + "'"};
  state.topics.emplace(key, topic);
  return topic;
}

// The transport: UDPv4 only, also between the processes of one host. Fast DDS 2.9's shared memory breaks
// when a process is killed: its successor, given the same participant id, reopens the dead one's port
// segment while its peers keep writing into the old one, so the restarted service matches and hears
// nothing (seen in tests/faults: a planner restarted after SIGKILL stayed without world.state). Its
// segments are also writable by their owner only, which shuts out an operator's sslctl beside the units'
// user. Loopback UDP measured the same here when this changed (bench/dds_round_trip medians 123-154 us vs
// 127-139 us with shared memory). Our own descriptor so that a peer without a port is tried on the
// well-known ports of as many participants as the site says (Fast DDS's default is 4; a field PC runs more).
void apply_transports(const ParticipantOptions& options, fdds::DomainParticipantQos& qos) {
  qos.transport().use_builtin_transports = false;
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->maxInitialPeersRange = options.discovery.peer_participants;
  qos.transport().user_transports.push_back(udp);
}

// The site's discovery on top of the profile's participant QoS (libs/dds/discovery.h).
Status apply_discovery(const DiscoveryConfig& discovery, fdds::DomainParticipantQos& qos) {
  auto& builtin = qos.wire_protocol().builtin;
  switch (discovery.mode) {
    case DiscoveryMode::kMulticast: return Status::success();
    case DiscoveryMode::kServer: {
      // Fast DDS's own parser of "host:port;host:port" gives the i-th server the GUID prefix of
      // `fastdds discovery -i i`.
      std::string list;
      for (const std::string& server : discovery.servers) list += (list.empty() ? "" : ";") + server;
      eprosima::fastdds::rtps::RemoteServerList_t servers;
      if (!eprosima::fastdds::rtps::load_environment_server_info(list, servers)) {
        return Error{"cannot use the discovery servers '" + list + "'"};
      }
      builtin.discovery_config.discoveryProtocol = eprosima::fastrtps::rtps::DiscoveryProtocol_t::CLIENT;
      builtin.discovery_config.m_DiscoveryServers = servers;
      return Status::success();
    }
    case DiscoveryMode::kPeers: {
      for (const std::string& peer : discovery.peers) {
        eprosima::fastrtps::rtps::Locator_t locator;
        if (!eprosima::fastrtps::rtps::IPLocator::setIPv4(locator, peer)) {
          return Error{"discovery peer '" + peer + "' is not an IPv4 address"};
        }
        builtin.initialPeersList.push_back(locator);
      }
      return Status::success();
    }
  }
  return Error{"unknown discovery mode"};
}

// DDS Security through Fast DDS's builtin plugins, configured by participant properties.
Status apply_security(const ParticipantOptions& options, fdds::DomainParticipantQos& qos) {
  if (!options.security.enabled) return Status::success();
  auto files = security_files(options.security, options.identity);
  if (!files) return files.error();
  auto& properties = qos.properties().properties();
  const auto set = [&](const std::string& name, const std::string& value) { properties.emplace_back(name, value); };
  set("dds.sec.auth.plugin", "builtin.PKI-DH");
  set("dds.sec.auth.builtin.PKI-DH.identity_ca", "file://" + files->ca);
  set("dds.sec.auth.builtin.PKI-DH.identity_certificate", "file://" + files->certificate);
  set("dds.sec.auth.builtin.PKI-DH.private_key", "file://" + files->private_key);
  set("dds.sec.access.plugin", "builtin.Access-Permissions");
  set("dds.sec.access.builtin.Access-Permissions.permissions_ca", "file://" + files->ca);
  set("dds.sec.access.builtin.Access-Permissions.governance", "file://" + files->governance);
  set("dds.sec.access.builtin.Access-Permissions.permissions", "file://" + files->permissions);
  set("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
  return Status::success();
}

}  // namespace

Result<std::string> find_qos_file() {
  if (const char* env = std::getenv("SSL_QOS_FILE"); env != nullptr && *env != '\0') {
    if (!fs::exists(env)) return Error{std::string("SSL_QOS_FILE names '") + env + "', which does not exist"};
    return std::string(env);
  }
  return find_deploy_file("qos/profiles.xml");
}

Result<Participant> Participant::create(const ParticipantOptions& options) {
  if (options.domain_id < 0 || options.domain_id > 232) {
    return Error{"DDS domain id " + std::to_string(options.domain_id) + " is out of range [0, 232]"};
  }
  std::string qos_file = options.qos_file;
  if (qos_file.empty()) {
    auto found = find_qos_file();
    if (!found) return found.error();
    qos_file = *found;
  }
  if (auto loaded = load_profiles_once(qos_file); !loaded) return loaded.error();

  auto* factory = fdds::DomainParticipantFactory::get_instance();
  fdds::DomainParticipantQos qos;
  if (factory->get_participant_qos_from_profile("ssl.participant", qos) != ReturnCode_t::RETCODE_OK) {
    return Error{"QoS profiles file '" + qos_file + "' has no participant profile 'ssl.participant'"};
  }
  qos.name(options.name);
  if (Status applied = apply_discovery(options.discovery, qos); !applied) return applied.error();
  apply_transports(options, qos);
  if (Status secured = apply_security(options, qos); !secured) return secured.error();
  auto state = std::make_shared<detail::ParticipantState>();
  state->domain_id = options.domain_id;
  state->qos_file = qos_file;
  if (options.security.enabled) state->security_identity = options.identity;
  state->participant = factory->create_participant(static_cast<fdds::DomainId_t>(options.domain_id), qos);
  if (state->participant == nullptr) {
    if (options.security.enabled) {
      return Error{"cannot create a secure DDS participant on domain " + std::to_string(options.domain_id) +
                   " as " + describe(options.security, options.identity) +
                   ": a certificate, key or signed document is broken, expired or not made by that directory's CA "
                   "(Fast DDS logged which; ./ssl certs remakes missing files)"};
    }
    return Error{"cannot create a DDS participant on domain " + std::to_string(options.domain_id)};
  }
  return Participant(std::move(state));
}

int Participant::domain_id() const { return state_->domain_id; }
const std::string& Participant::qos_file() const { return state_->qos_file; }

std::chrono::nanoseconds Participant::lease_duration() const {
  const auto& lease = state_->participant->get_qos().wire_protocol().builtin.discovery_config.leaseDuration;
  return std::chrono::seconds(lease.seconds) + std::chrono::nanoseconds(lease.nanosec);
}

Result<std::shared_ptr<detail::WriterEntities>> Participant::create_writer(
    std::string_view topic_name, TopicScope scope, std::optional<TeamColor> team,
    std::unique_ptr<fdds::TopicDataType> support) {
  if (auto ok = check_team(topic_name, scope, team); !ok) return ok.error();
  std::lock_guard lock(state_->mutex);
  auto topic = find_or_create_topic(*state_, topic_name, std::move(support));
  if (!topic) return topic.error();

  const std::string publisher_profile = partition_profile(scope, team, "publisher");
  fdds::Publisher*& publisher = state_->publishers[publisher_profile];
  if (publisher == nullptr) {
    publisher = state_->participant->create_publisher_with_profile(publisher_profile);
    if (publisher == nullptr) {
      state_->publishers.erase(publisher_profile);
      return Error{"no publisher profile '" + publisher_profile + "' in " + state_->qos_file};
    }
  }
  auto entities = std::make_shared<detail::WriterEntities>();
  entities->participant = state_;
  entities->publisher = publisher;
  entities->topic = std::string(topic_name);
  const std::string profile = entities->topic + ".writer";
  entities->writer = publisher->create_datawriter_with_profile(*topic, profile, &entities->status);
  if (entities->writer == nullptr) {
    return Error{"cannot create a writer on '" + entities->topic + "' (" + publisher_profile + ") with QoS profile '" +
                 profile + "' from " + state_->qos_file + denied_hint(*state_)};
  }
  return entities;
}

Result<std::shared_ptr<detail::ReaderEntities>> Participant::create_reader(
    std::string_view topic_name, TopicScope scope, std::optional<TeamColor> team,
    std::unique_ptr<fdds::TopicDataType> support,
    std::function<void(detail::ReaderEntities&, fdds::DataReader*)> on_data) {
  if (auto ok = check_team(topic_name, scope, team); !ok) return ok.error();
  std::lock_guard lock(state_->mutex);
  auto topic = find_or_create_topic(*state_, topic_name, std::move(support));
  if (!topic) return topic.error();

  const std::string subscriber_profile = partition_profile(scope, team, "subscriber");
  fdds::Subscriber*& subscriber = state_->subscribers[subscriber_profile];
  if (subscriber == nullptr) {
    subscriber = state_->participant->create_subscriber_with_profile(subscriber_profile);
    if (subscriber == nullptr) {
      state_->subscribers.erase(subscriber_profile);
      return Error{"no subscriber profile '" + subscriber_profile + "' in " + state_->qos_file};
    }
  }
  auto entities = std::make_shared<detail::ReaderEntities>();
  entities->participant = state_;
  entities->subscriber = subscriber;
  entities->topic = std::string(topic_name);
  if (on_data) {
    entities->status.on_data = [raw = entities.get(), on_data = std::move(on_data)](fdds::DataReader* reader) {
      on_data(*raw, reader);
    };
  }
  const std::string profile = entities->topic + ".reader";
  entities->reader = subscriber->create_datareader_with_profile(*topic, profile, &entities->status);
  if (entities->reader == nullptr) {
    return Error{"cannot create a reader on '" + entities->topic + "' (" + subscriber_profile +
                 ") with QoS profile '" + profile + "' from " + state_->qos_file + denied_hint(*state_)};
  }
  return entities;
}

std::vector<TopicInfo> all_topics() {
  std::vector<TopicInfo> infos;
  std::apply(
      [&](const auto&... spec) {
        (infos.push_back(TopicInfo{std::string(spec.name),
                                   typename std::decay_t<decltype(spec)>::Support().getName(), spec.scope,
                                   spec.writer_profile(), spec.reader_profile(), std::string(spec.description)}),
         ...);
      },
      topics::kAll);
  return infos;
}

}  // namespace ssl::dds
