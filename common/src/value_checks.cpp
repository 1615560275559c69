#include "tactile/common/value_checks.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tactile::checks {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw FormatError(fmt::format("{}: {}", where, what));
}

template <typename T>
void all_finite_any(const std::vector<T>& values, const std::string& where,
                    const std::string& field) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      fail(where, fmt::format("{} entry {} is not finite ({})", field, i, values[i]));
    }
  }
}

}  // namespace

double finite(double v, const std::string& where, const std::string& field) {
  if (!std::isfinite(v)) fail(where, fmt::format("{} is not finite ({})", field, v));
  return v;
}

double in_range(double v, double min, double max, const std::string& where,
                const std::string& field) {
  finite(v, where, field);
  if (!(v >= min && v <= max)) {
    fail(where, fmt::format("{} {} is out of range: must be from {} to {}", field, v, min, max));
  }
  return v;
}

double positive_up_to(double v, double max, const std::string& where, const std::string& field) {
  finite(v, where, field);
  if (!(v > 0 && v <= max)) {
    fail(where, fmt::format("{} {} is out of range: must be > 0 and <= {}", field, v, max));
  }
  return v;
}

std::int64_t int_in_range(std::int64_t v, std::int64_t min, std::int64_t max,
                          const std::string& where, const std::string& field) {
  if (v < min || v > max) {
    fail(where, fmt::format("{} {} is out of range: must be from {} to {}", field, v, min, max));
  }
  return v;
}

void all_finite(const std::vector<double>& values, const std::string& where,
                const std::string& field) {
  all_finite_any(values, where, field);
}

void all_finite(const std::vector<float>& values, const std::string& where,
                const std::string& field) {
  all_finite_any(values, where, field);
}

std::uint64_t memory_limit_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page = ::sysconf(_SC_PAGE_SIZE);
  // Unknown memory: 4 GB, a size every machine this runs on can at least address.
  if (pages <= 0 || page <= 0) return std::uint64_t{4} << 30;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) / 2;
}

std::string format_bytes(double bytes) {
  if (bytes < 1e3) return fmt::format("{:.0f} bytes", bytes);
  if (bytes < 1e6) return fmt::format("{:.3g} kB", bytes / 1e3);
  if (bytes < 1e9) return fmt::format("{:.3g} MB", bytes / 1e6);
  if (bytes < 1e12) return fmt::format("{:.3g} GB", bytes / 1e9);
  return fmt::format("{:.3g} TB", bytes / 1e12);
}

std::uint64_t value_count(const std::vector<std::uint64_t>& dims, std::size_t bytes_per_value,
                          const std::string& where, const std::string& field) {
  const std::uint64_t limit = memory_limit_bytes();
  // In doubles, so that the product of any dims is compared without overflowing.
  double bytes = static_cast<double>(bytes_per_value);
  for (std::uint64_t d : dims) bytes *= static_cast<double>(d);
  if (bytes > static_cast<double>(limit)) {
    fail(where, fmt::format("{} declares {} values ({}), more than the limit of {} (half this "
                            "machine's memory)",
                            field, fmt::join(dims, " x "), format_bytes(bytes),
                            format_bytes(static_cast<double>(limit))));
  }
  std::uint64_t count = 1;
  for (std::uint64_t d : dims) count *= d;
  return count;
}

}  // namespace tactile::checks
