// StreamHub: the open event streams (one per viewer) and what each has not been sent yet. A viewer that
// reads slowly never slows the others or the bus: a new field frame replaces its unsent one (counted as
// dropped), and its queue of other messages is bounded (the oldest are dropped, counted). Thread-safe:
// the console's loop pushes, each HTTP stream thread waits on its own client.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace ssl::console {

using Message = std::shared_ptr<const std::string>;  // one SSE message, "event: ...\ndata: ...\n\n"

/// "event: NAME\ndata: DATA\n\n"; DATA must be one line (compact JSON).
Message sse_message(std::string_view event, std::string_view data);

class StreamClient {
 public:
  static constexpr std::size_t kQueueLimit = 256;

  /// Replaces the unsent frame, if any.
  void push_frame(Message frame);
  void push(Message message);
  /// Waits up to `timeout` for something to send; returns it in order (the frame last). Empty on timeout
  /// or once closed.
  std::vector<Message> wait(std::chrono::milliseconds timeout);
  void close();
  bool closed() const;
  std::uint64_t dropped() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Message> queue_;
  Message frame_;
  std::uint64_t dropped_ = 0;
  bool closed_ = false;
};

class StreamHub {
 public:
  explicit StreamHub(std::size_t max_clients) : max_clients_(max_clients) {}

  /// A new client, or nullptr when max_clients are open.
  std::shared_ptr<StreamClient> open();
  void remove(const std::shared_ptr<StreamClient>& client);
  void push_frame(const Message& frame);
  void push(const Message& message);
  /// Closes every client (their streams end).
  void close_all();

  std::size_t size() const;
  /// Frames and messages dropped for slow viewers, over all clients ever opened.
  std::uint64_t dropped() const;

 private:
  mutable std::mutex mutex_;
  std::vector<std::shared_ptr<StreamClient>> clients_;
  std::size_t max_clients_;
  std::uint64_t dropped_by_removed_ = 0;
};

}  // namespace ssl::console
