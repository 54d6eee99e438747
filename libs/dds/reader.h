// Reader<T>: a typed DDS reader created by Participant::make_reader with QoS from a named profile.
//
// Two ways to consume samples:
//  - polling from the owner's thread (no user code on middleware threads): wait_for_data() then take();
//  - a callback run on the Fast DDS thread, given to Participant::make_reader; keep it short.
//
//   auto reader = participant->make_reader(topics::kWorldState, TeamColor::kBlue);
//   while (running) {
//     if (reader->wait_for_data(100ms)) for (auto& s : reader->take()) handle(s.data);
//   }
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "libs/dds/entities.h"

namespace ssl::dds {

/// One received sample with the time stamps DDS attaches to it.
template <typename T>
struct Sample {
  T data;
  std::int64_t source_unix_ns = 0;     // writer's wall clock when written
  std::int64_t reception_unix_ns = 0;  // this host's wall clock when received
};

/// What a reader has seen since it was created.
struct ReaderCounters {
  std::uint64_t received = 0;
  std::uint64_t samples_lost = 0;       // samples DDS knows were sent but never arrived
  std::uint64_t deadlines_missed = 0;   // no sample within the profile's deadline (stale input)
  std::uint64_t incompatible_qos = 0;   // a writer was found whose offered QoS does not satisfy ours
  std::size_t matched_writers = 0;
  std::int32_t alive_writers = 0;       // writers whose liveliness is asserted
};

template <typename T>
class Reader {
 public:
  explicit Reader(std::shared_ptr<detail::ReaderEntities> entities) : entities_(std::move(entities)) {}

  /// Takes every unread sample, oldest first. Never blocks.
  std::vector<Sample<T>> take() {
    std::vector<Sample<T>> samples;
    Sample<T> sample;
    while (take_next(sample)) samples.push_back(std::move(sample));
    return samples;
  }

  /// Takes every unread sample and returns only the newest; nullopt when none was unread.
  std::optional<Sample<T>> take_latest() {
    std::optional<Sample<T>> latest;
    Sample<T> sample;
    while (take_next(sample)) latest = std::move(sample);
    return latest;
  }

  /// Takes the next unread sample into `out`; false when none is left.
  bool take_next(Sample<T>& out) { return take_next(entities_->reader, *entities_, out); }

  /// The same on a given DataReader, for the callback that Participant::make_reader installs (it runs
  /// with the reader Fast DDS hands it, possibly before `entities.reader` is assigned).
  static bool take_next(eprosima::fastdds::dds::DataReader* reader, detail::ReaderEntities& entities,
                        Sample<T>& out) {
    eprosima::fastdds::dds::SampleInfo info;
    while (reader->take_next_sample(&out.data, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;  // instance state changes (disposed, no writers) carry no data
      out.source_unix_ns = detail::to_unix_ns(info.source_timestamp);
      out.reception_unix_ns = detail::to_unix_ns(info.reception_timestamp);
      ++entities.received;
      return true;
    }
    return false;
  }

  /// Waits until data arrived since the last successful wait (or since creation); false on timeout.
  bool wait_for_data(std::chrono::nanoseconds timeout) { return entities_->status.wait_for_data(timeout); }

  /// Waits until at least `count` writers are matched; false on timeout.
  bool wait_for_match(std::size_t count, std::chrono::nanoseconds timeout) {
    return entities_->status.wait_for_matches(count, timeout);
  }

  ReaderCounters counters() const {
    std::lock_guard lock(entities_->status.mutex);
    return {entities_->received.load(), entities_->status.samples_lost.load(),
            entities_->status.deadlines_missed.load(), entities_->status.incompatible_qos.load(),
            entities_->status.matched, entities_->status.alive_writers};
  }

  const std::string& topic() const { return entities_->topic; }

 private:
  std::shared_ptr<detail::ReaderEntities> entities_;
};

}  // namespace ssl::dds
