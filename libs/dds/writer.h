// Writer<T>: a typed DDS writer created by Participant::make_writer with QoS from a named profile.
//
//   auto writer = participant->make_writer(topics::kRefereeState);
//   writer->wait_for_match(1, std::chrono::seconds(5));   // only where a test needs a reader first
//   ssl::Status sent = writer->write(state);
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>

#include "libs/common/result.h"
#include "libs/dds/entities.h"

namespace ssl::dds {

/// What a writer has done and seen since it was created.
struct WriterCounters {
  std::uint64_t written = 0;
  std::uint64_t write_failures = 0;
  std::uint64_t deadlines_missed = 0;   // the writer did not write within its deadline
  std::uint64_t incompatible_qos = 0;   // a reader was found whose requested QoS this writer cannot offer
  std::size_t matched_readers = 0;
};

template <typename T>
class Writer {
 public:
  explicit Writer(std::shared_ptr<detail::WriterEntities> entities) : entities_(std::move(entities)) {}

  /// Publishes one sample; an error when Fast DDS refuses it (e.g. a reliable history full past the
  /// profile's max_blocking_time).
  Status write(const T& sample) {
    // Fast DDS takes a non-const pointer but does not modify the sample.
    if (!entities_->writer->write(const_cast<T*>(&sample))) {
      ++entities_->write_failures;
      return Error{"DDS write on topic '" + entities_->topic + "' failed"};
    }
    ++entities_->written;
    return {};
  }

  /// Waits until at least `count` readers are matched; false on timeout.
  bool wait_for_match(std::size_t count, std::chrono::nanoseconds timeout) {
    return entities_->status.wait_for_matches(count, timeout);
  }

  /// For reliable topics: waits until every matched reader acknowledged every sample; false on timeout.
  /// Call before destroying a writer whose last samples must arrive.
  bool wait_for_acknowledgments(std::chrono::nanoseconds timeout) {
    const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(timeout);
    const auto nanos = std::chrono::duration_cast<std::chrono::nanoseconds>(timeout - seconds);
    return entities_->writer->wait_for_acknowledgments(
               eprosima::fastrtps::Duration_t(static_cast<std::int32_t>(seconds.count()),
                                              static_cast<std::uint32_t>(nanos.count()))) ==
           ReturnCode_t::RETCODE_OK;
  }

  WriterCounters counters() const {
    std::lock_guard lock(entities_->status.mutex);
    return {entities_->written.load(), entities_->write_failures.load(),
            entities_->status.deadlines_missed.load(), entities_->status.incompatible_qos.load(),
            entities_->status.matched};
  }

  const std::string& topic() const { return entities_->topic; }

 private:
  std::shared_ptr<detail::WriterEntities> entities_;
};

}  // namespace ssl::dds
