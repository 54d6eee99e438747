#include "services/console/adapter/stream_hub.h"

#include <algorithm>
#include <utility>

namespace ssl::console {

Message sse_message(std::string_view event, std::string_view data) {
  std::string text;
  text.reserve(event.size() + data.size() + 16);
  text.append("event: ").append(event).append("\ndata: ").append(data).append("\n\n");
  return std::make_shared<const std::string>(std::move(text));
}

void StreamClient::push_frame(Message frame) {
  {
    std::lock_guard lock(mutex_);
    if (closed_) return;
    if (frame_) ++dropped_;
    frame_ = std::move(frame);
  }
  ready_.notify_one();
}

void StreamClient::push(Message message) {
  {
    std::lock_guard lock(mutex_);
    if (closed_) return;
    queue_.push_back(std::move(message));
    if (queue_.size() > kQueueLimit) {
      queue_.pop_front();
      ++dropped_;
    }
  }
  ready_.notify_one();
}

std::vector<Message> StreamClient::wait(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  ready_.wait_for(lock, timeout, [&] { return closed_ || frame_ || !queue_.empty(); });
  std::vector<Message> out;
  if (closed_) return out;
  out.assign(queue_.begin(), queue_.end());
  queue_.clear();
  if (frame_) out.push_back(std::exchange(frame_, nullptr));
  return out;
}

void StreamClient::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  ready_.notify_all();
}

bool StreamClient::closed() const {
  std::lock_guard lock(mutex_);
  return closed_;
}

std::uint64_t StreamClient::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

std::shared_ptr<StreamClient> StreamHub::open() {
  std::lock_guard lock(mutex_);
  if (clients_.size() >= max_clients_) return nullptr;
  clients_.push_back(std::make_shared<StreamClient>());
  return clients_.back();
}

void StreamHub::remove(const std::shared_ptr<StreamClient>& client) {
  client->close();
  std::lock_guard lock(mutex_);
  const auto it = std::find(clients_.begin(), clients_.end(), client);
  if (it == clients_.end()) return;
  dropped_by_removed_ += client->dropped();
  clients_.erase(it);
}

void StreamHub::push_frame(const Message& frame) {
  std::lock_guard lock(mutex_);
  for (const auto& client : clients_) client->push_frame(frame);
}

void StreamHub::push(const Message& message) {
  std::lock_guard lock(mutex_);
  for (const auto& client : clients_) client->push(message);
}

void StreamHub::close_all() {
  std::lock_guard lock(mutex_);
  for (const auto& client : clients_) client->close();
}

std::size_t StreamHub::size() const {
  std::lock_guard lock(mutex_);
  return clients_.size();
}

std::uint64_t StreamHub::dropped() const {
  std::lock_guard lock(mutex_);
  std::uint64_t total = dropped_by_removed_;
  for (const auto& client : clients_) total += client->dropped();
  return total;
}

}  // namespace ssl::console
