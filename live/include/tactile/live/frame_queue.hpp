#pragma once
// The queues between a live session's stages. Between acquisition and processing
// (DropOldestQueue): bounded, and a push never waits. When processing falls behind and the queue
// is full, the oldest waiting item is dropped (and counted): a late frame costs a gap in the
// measurement, never a growing delay. Between two processing stages (WaitingQueue): bounded, and
// a push waits for room, so the stage before runs at most `capacity` items ahead; the drops
// happen before the first stage, where the frames come in. The two differ only in their push.

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
class BoundedQueue {
 public:
  // The oldest item, waiting at most `timeout` for one; nothing when none came or the queue was
  // closed and is empty.
  std::optional<T> pop(std::chrono::milliseconds timeout) {
    std::optional<T> item;
    {
      std::unique_lock lock(mutex_);
      changed_.wait_for(lock, timeout, [this] { return !items_.empty() || closed_; });
      if (items_.empty()) return std::nullopt;
      item = std::move(items_.front());
      items_.pop_front();
    }
    changed_.notify_all();  // room for a push that waits
    return item;
  }

  // No more pushes will come (a WaitingQueue refuses them, and wakes a push that waits); pop
  // still hands out what is left, then returns at once.
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

 protected:
  explicit BoundedQueue(std::size_t capacity) : capacity_(capacity < 1 ? 1 : capacity) {}

  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<T> items_;
  bool closed_ = false;
};

template <typename T>
class DropOldestQueue : public BoundedQueue<T> {
 public:
  explicit DropOldestQueue(std::size_t capacity) : BoundedQueue<T>(capacity) {}

  // Adds `item`; returns the item it dropped to make room, if any.
  std::optional<T> push(T item) {
    std::optional<T> dropped;
    {
      std::lock_guard lock(this->mutex_);
      if (this->items_.size() >= this->capacity_) {
        dropped = std::move(this->items_.front());
        this->items_.pop_front();
        ++dropped_;
      }
      this->items_.push_back(std::move(item));
    }
    this->changed_.notify_all();
    return dropped;
  }

  std::int64_t dropped() const {
    std::lock_guard lock(this->mutex_);
    return dropped_;
  }

 private:
  std::int64_t dropped_ = 0;
};

template <typename T>
class WaitingQueue : public BoundedQueue<T> {
 public:
  explicit WaitingQueue(std::size_t capacity) : BoundedQueue<T>(capacity) {}

  // Adds `item` once there is room; false (the item not taken) when the queue is closed.
  bool push(T item) {
    {
      std::unique_lock lock(this->mutex_);
      this->changed_.wait(
          lock, [this] { return this->items_.size() < this->capacity_ || this->closed_; });
      if (this->closed_) return false;
      this->items_.push_back(std::move(item));
    }
    this->changed_.notify_all();
    return true;
  }
};

}  // namespace tactile::live
