#pragma once
// Mapping in the background for a window: the newest request wins. submit() returns at once; a
// worker thread maps the newest request submitted (those submitted meanwhile are skipped, never
// queued), so a window that submits on every change of a slider stays responsive and shows the
// newest mapping as soon as it is made.

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "tactile/author/outcome.hpp"

namespace tactile::author {

class Remapper {
 public:
  explicit Remapper(std::shared_ptr<const capture::StrainMovie> strain);
  ~Remapper();  // stops after the mapping under way, if any
  Remapper(const Remapper&) = delete;
  Remapper& operator=(const Remapper&) = delete;

  // Asks for `request` to be mapped; its number (1, 2, ...), which the outcome carries.
  std::uint64_t submit(const mapping::MapRequest& request);

  struct Done {
    std::uint64_t number = 0;
    std::shared_ptr<const MappingOutcome> outcome;
  };
  // The newest outcome made so far (empty before the first).
  Done latest() const;
  // True while a submitted request is not mapped yet.
  bool busy() const;
  // Waits until request `number` (or a newer one) is mapped; the newest outcome.
  Done wait_for(std::uint64_t number) const;
  // How many requests were mapped, and how many skipped because a newer one came first.
  std::uint64_t mapped_count() const;
  std::uint64_t skipped_count() const;

 private:
  void work();

  std::shared_ptr<const capture::StrainMovie> strain_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::optional<mapping::MapRequest> pending_;
  std::uint64_t submitted_ = 0;
  std::uint64_t working_on_ = 0;
  Done latest_;
  std::uint64_t mapped_ = 0, skipped_ = 0;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace tactile::author
