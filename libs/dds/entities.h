// Internal: the Fast DDS entities behind Participant, Writer and Reader, with their listeners. Included
// by writer.h and reader.h for their templates; not for use by services.
#pragma once

#include <fastdds/dds/core/status/StatusMask.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace ssl::dds::detail {

/// The participant and the publishers, subscribers and topics it shares between writers and readers.
/// Guarded by `mutex` because services create writers and readers from one thread but tests may not.
struct ParticipantState {
  ~ParticipantState();

  int domain_id = 0;
  std::string qos_file;
  std::string security_identity;  // "" without DDS Security
  eprosima::fastdds::dds::DomainParticipant* participant = nullptr;
  std::mutex mutex;
  std::map<std::string, eprosima::fastdds::dds::Publisher*> publishers;    // by profile name
  std::map<std::string, eprosima::fastdds::dds::Subscriber*> subscribers;  // by profile name
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics;            // by topic name
};

/// Matching and QoS events seen by a writer, updated on Fast DDS threads.
struct WriterStatus final : eprosima::fastdds::dds::DataWriterListener {
  void on_publication_matched(eprosima::fastdds::dds::DataWriter*,
                              const eprosima::fastdds::dds::PublicationMatchedStatus& info) override;
  void on_offered_deadline_missed(eprosima::fastdds::dds::DataWriter*,
                                  const eprosima::fastdds::dds::OfferedDeadlineMissedStatus& info) override;
  void on_offered_incompatible_qos(eprosima::fastdds::dds::DataWriter*,
                                   const eprosima::fastdds::dds::OfferedIncompatibleQosStatus& info) override;
  void on_liveliness_lost(eprosima::fastdds::dds::DataWriter*,
                          const eprosima::fastdds::dds::LivelinessLostStatus& info) override;

  bool wait_for_matches(std::size_t count, std::chrono::nanoseconds timeout);

  std::mutex mutex;
  std::condition_variable changed;
  std::size_t matched = 0;
  std::atomic<std::uint64_t> deadlines_missed{0};
  std::atomic<std::uint64_t> incompatible_qos{0};
  std::atomic<std::uint64_t> liveliness_lost{0};
};

struct WriterEntities {
  ~WriterEntities();

  std::shared_ptr<ParticipantState> participant;  // keeps the participant alive while the writer lives
  eprosima::fastdds::dds::Publisher* publisher = nullptr;
  eprosima::fastdds::dds::DataWriter* writer = nullptr;
  std::string topic;
  WriterStatus status;
  std::atomic<std::uint64_t> written{0};
  std::atomic<std::uint64_t> write_failures{0};
};

/// Matching, QoS and data events seen by a reader, updated on Fast DDS threads.
struct ReaderStatus final : eprosima::fastdds::dds::DataReaderListener {
  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;
  void on_subscription_matched(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::SubscriptionMatchedStatus& info) override;
  void on_requested_deadline_missed(eprosima::fastdds::dds::DataReader*,
                                    const eprosima::fastdds::dds::RequestedDeadlineMissedStatus& info) override;
  void on_requested_incompatible_qos(eprosima::fastdds::dds::DataReader*,
                                     const eprosima::fastdds::dds::RequestedIncompatibleQosStatus& info) override;
  void on_sample_lost(eprosima::fastdds::dds::DataReader*,
                      const eprosima::fastdds::dds::SampleLostStatus& info) override;
  void on_liveliness_changed(eprosima::fastdds::dds::DataReader*,
                             const eprosima::fastdds::dds::LivelinessChangedStatus& info) override;

  bool wait_for_matches(std::size_t count, std::chrono::nanoseconds timeout);
  bool wait_for_data(std::chrono::nanoseconds timeout);

  std::mutex mutex;
  std::condition_variable changed;
  std::size_t matched = 0;
  std::uint64_t data_signals = 0;   // incremented per on_data_available
  std::uint64_t data_consumed = 0;  // data_signals value when the owner last waited successfully
  std::int32_t alive_writers = 0;
  // Set before the DataReader exists and never changed: when set, runs on the Fast DDS thread for each
  // data notification (callback mode) besides waking waiters.
  // Receives the DataReader Fast DDS passes to the listener: data can arrive before
  // create_datareader_with_profile() has returned and ReaderEntities::reader is set.
  std::function<void(eprosima::fastdds::dds::DataReader*)> on_data;
  std::atomic<std::uint64_t> deadlines_missed{0};
  std::atomic<std::uint64_t> incompatible_qos{0};
  std::atomic<std::uint64_t> samples_lost{0};
};

struct ReaderEntities {
  ~ReaderEntities();

  std::shared_ptr<ParticipantState> participant;
  eprosima::fastdds::dds::Subscriber* subscriber = nullptr;
  eprosima::fastdds::dds::DataReader* reader = nullptr;
  std::string topic;
  ReaderStatus status;
  std::atomic<std::uint64_t> received{0};
};

/// Unix nanoseconds of a Fast DDS time stamp.
std::int64_t to_unix_ns(const eprosima::fastrtps::rtps::Time_t& time);

}  // namespace ssl::dds::detail
