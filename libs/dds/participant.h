// Participant: one DDS domain participant of a process, created from the XML profile "ssl.participant",
// and the factory of typed writers and readers whose QoS comes only from named XML profiles.
//
//   auto participant = ssl::dds::Participant::create({.domain_id = 3, .name = "world_model/blue"});
//   if (!participant) { fail(participant.error().message); }
//   auto writer = participant->make_writer(ssl::dds::topics::kWorldState, ssl::TeamColor::kBlue);
//   auto reader = participant->make_reader(ssl::dds::topics::kRefereeState);
//
// Lifetime: a Participant is a handle to shared DDS state; writers and readers keep it alive, so entities
// are always deleted children first. When the last handle goes, every entity is deleted and Fast DDS
// removes its shared-memory segments (a process must therefore exit through destructors: see
// libs/common/shutdown.h).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <functional>
#include <string>
#include <utility>

#include "libs/common/result.h"
#include "libs/common/team.h"
#include "libs/dds/discovery.h"
#include "libs/dds/reader.h"
#include "libs/dds/security.h"
#include "libs/dds/topics.h"
#include "libs/dds/writer.h"

namespace ssl::dds {

struct ParticipantOptions {
  int domain_id = 0;        // DDS domain id, 0..232
  std::string qos_file;     // Fast DDS XML profiles; empty: find_qos_file()
  std::string name = "ssl"; // participant name shown to discovery tools, e.g. "world_model/blue"
  DiscoveryConfig discovery;  // how it finds the others (the site's deploy/.../dds.yaml)
  SecurityConfig security;    // DDS Security (the same file; off by default)
  std::string identity;       // with security on: whose certificate and permissions (libs/dds/security.h)
};

/// Finds deploy/qos/profiles.xml: $SSL_QOS_FILE, else as ssl::find_deploy_file does.
Result<std::string> find_qos_file();

class Participant {
 public:
  /// Loads the QoS profiles (once per file and process) and creates the participant; with security on, as
  /// `options.identity`, whose files must exist (an error names the missing one).
  static Result<Participant> create(const ParticipantOptions& options);

  /// A writer on `spec`'s topic with the profile "<topic>.writer". `team` selects the partition: required
  /// for team-scoped topics, rejected for shared ones; for team-addressed ones, none means every team.
  template <typename Spec>
  Result<Writer<typename Spec::Sample>> make_writer(const Spec& spec,
                                                    std::optional<TeamColor> team = std::nullopt) {
    auto entities = create_writer(spec.name, spec.scope, team, std::make_unique<typename Spec::Support>());
    if (!entities) return entities.error();
    return Writer<typename Spec::Sample>(std::move(*entities));
  }

  /// A reader on `spec`'s topic with the profile "<topic>.reader"; see make_writer for `team`.
  template <typename Spec>
  Result<Reader<typename Spec::Sample>> make_reader(const Spec& spec,
                                                    std::optional<TeamColor> team = std::nullopt) {
    auto entities =
        create_reader(spec.name, spec.scope, team, std::make_unique<typename Spec::Support>(), nullptr);
    if (!entities) return entities.error();
    return Reader<typename Spec::Sample>(std::move(*entities));
  }

  /// A reader that calls `callback(const Sample<T>&)` on the Fast DDS thread for every sample that
  /// arrives. The callback must be quick and thread-safe with respect to the caller's state.
  template <typename Spec, typename Callback>
  Result<Reader<typename Spec::Sample>> make_reader(const Spec& spec, std::optional<TeamColor> team,
                                                    Callback callback) {
    using T = typename Spec::Sample;
    auto on_data = [callback = std::move(callback)](detail::ReaderEntities& entities,
                                                    eprosima::fastdds::dds::DataReader* reader) mutable {
      Sample<T> sample;
      while (Reader<T>::take_next(reader, entities, sample)) callback(std::as_const(sample));
    };
    auto entities = create_reader(spec.name, spec.scope, team, std::make_unique<typename Spec::Support>(),
                                  std::move(on_data));
    if (!entities) return entities.error();
    return Reader<T>(std::move(*entities));
  }

  int domain_id() const;
  const std::string& qos_file() const;
  /// How long peers wait for this participant's announcements before they drop it (the profile's lease).
  std::chrono::nanoseconds lease_duration() const;

 private:
  explicit Participant(std::shared_ptr<detail::ParticipantState> state) : state_(std::move(state)) {}

  Result<std::shared_ptr<detail::WriterEntities>> create_writer(
      std::string_view topic, TopicScope scope, std::optional<TeamColor> team,
      std::unique_ptr<eprosima::fastdds::dds::TopicDataType> support);
  Result<std::shared_ptr<detail::ReaderEntities>> create_reader(
      std::string_view topic, TopicScope scope, std::optional<TeamColor> team,
      std::unique_ptr<eprosima::fastdds::dds::TopicDataType> support,
      std::function<void(detail::ReaderEntities&, eprosima::fastdds::dds::DataReader*)> on_data);

  std::shared_ptr<detail::ParticipantState> state_;
};

}  // namespace ssl::dds
