#pragma once
// The queues between a live session's stages. Between acquisition and processing
// (DropOldestQueue): bounded, and a push never waits. When processing falls behind and the queue
// is full, the oldest waiting item is dropped (and counted): a late frame costs a gap in the
// measurement, never a growing delay. Between two processing stages (WaitingQueue): bounded, and
// a push waits for room, so the stage before runs at most `capacity` items ahead; the drops
// happen before the first stage, where the frames come in.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <utility>

namespace tactile::live {

template <typename T>
class DropOldestQueue {
 public:
  explicit DropOldestQueue(std::size_t capacity) : capacity_(capacity < 1 ? 1 : capacity) {}

  // Adds `item`; returns the item it dropped to make room, if any.
  std::optional<T> push(T item) {
    std::optional<T> dropped;
    {
      std::lock_guard lock(mutex_);
      if (items_.size() >= capacity_) {
        dropped = std::move(items_.front());
        items_.pop_front();
        ++dropped_;
      }
      items_.push_back(std::move(item));
    }
    ready_.notify_one();
    return dropped;
  }

  // The oldest item, waiting at most `timeout` for one; nothing when none came or the queue was
  // closed and is empty.
  std::optional<T> pop(std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    ready_.wait_for(lock, timeout, [this] { return !items_.empty() || closed_; });
    if (items_.empty()) return std::nullopt;
    T item = std::move(items_.front());
    items_.pop_front();
    return item;
  }

  // No more pushes will come: pop returns at once when empty.
  void close() {
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
    }
    ready_.notify_all();
  }
  bool closed_and_empty() const {
    std::lock_guard lock(mutex_);
    return closed_ && items_.empty();
  }
  std::int64_t dropped() const {
    std::lock_guard lock(mutex_);
    return dropped_;
  }

 private:
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<T> items_;
  std::int64_t dropped_ = 0;
  bool closed_ = false;
};

template <typename T>
class WaitingQueue {
 public:
  explicit WaitingQueue(std::size_t capacity) : capacity_(capacity < 1 ? 1 : capacity) {}

  // Adds `item` once there is room; false (the item not taken) when the queue is closed.
  bool push(T item) {
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [this] { return items_.size() < capacity_ || closed_; });
      if (closed_) return false;
      items_.push_back(std::move(item));
    }
    changed_.notify_all();
    return true;
  }

  // As DropOldestQueue::pop.
  std::optional<T> pop(std::chrono::milliseconds timeout) {
    std::optional<T> item;
    {
      std::unique_lock lock(mutex_);
      changed_.wait_for(lock, timeout, [this] { return !items_.empty() || closed_; });
      if (items_.empty()) return std::nullopt;
      item = std::move(items_.front());
      items_.pop_front();
    }
    changed_.notify_all();
    return item;
  }

  // No more pushes are taken (a waiting one returns false); pop still hands out what is left.
  void close() {
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
    }
    changed_.notify_all();
  }
  bool closed_and_empty() const {
    std::lock_guard lock(mutex_);
    return closed_ && items_.empty();
  }

 private:
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<T> items_;
  bool closed_ = false;
};

}  // namespace tactile::live
