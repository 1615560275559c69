// The newest request wins; see remapper.hpp.
#include "tactile/author/remapper.hpp"

#include <utility>

namespace tactile::author {

Remapper::Remapper(std::shared_ptr<const capture::StrainMovie> strain)
    : strain_(std::move(strain)), worker_([this] { work(); }) {}

Remapper::~Remapper() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  worker_.join();
}

std::uint64_t Remapper::submit(const mapping::MapRequest& request) {
  std::uint64_t number = 0;
  {
    std::lock_guard lock(mutex_);
    if (pending_) ++skipped_;  // replaced before the worker took it
    pending_ = request;
    number = ++submitted_;
  }
  changed_.notify_all();
  return number;
}

Remapper::Done Remapper::latest() const {
  std::lock_guard lock(mutex_);
  return latest_;
}

bool Remapper::busy() const {
  std::lock_guard lock(mutex_);
  return latest_.number < submitted_;
}

Remapper::Done Remapper::wait_for(std::uint64_t number) const {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return latest_.number >= number || stopping_; });
  return latest_;
}

std::uint64_t Remapper::mapped_count() const {
  std::lock_guard lock(mutex_);
  return mapped_;
}

std::uint64_t Remapper::skipped_count() const {
  std::lock_guard lock(mutex_);
  return skipped_;
}

void Remapper::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return pending_.has_value() || stopping_; });
    if (stopping_) return;
    const mapping::MapRequest request = std::move(*pending_);
    pending_.reset();
    const std::uint64_t number = submitted_;
    lock.unlock();
    auto outcome = std::make_shared<const MappingOutcome>(map_for_authoring(*strain_, request));
    lock.lock();
    latest_ = {number, std::move(outcome)};
    ++mapped_;
    changed_.notify_all();
  }
}

}  // namespace tactile::author
