#pragma once
// Checks of the numbers read from files: every reader says the same things the same way,
// "<where>: <field> <value> is out of range: must be from <min> to <max>", and refuses a
// declared size before it allocates it. Each check throws tactile::FormatError.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tactile/common/error.hpp"

namespace tactile::checks {

// `v` itself, if finite: "<where>: <field> is not finite (nan)".
double finite(double v, const std::string& where, const std::string& field);

// `v` itself, if finite and min <= v <= max.
double in_range(double v, double min, double max, const std::string& where,
                const std::string& field);

// `v` itself, if finite and 0 < v <= max.
double positive_up_to(double v, double max, const std::string& where, const std::string& field);

// `v` itself, if min <= v <= max.
std::int64_t int_in_range(std::int64_t v, std::int64_t min, std::int64_t max,
                          const std::string& where, const std::string& field);

// Every value finite: "<where>: <field> entry <i> is not finite (inf)".
void all_finite(const std::vector<double>& values, const std::string& where,
                const std::string& field);
void all_finite(const std::vector<float>& values, const std::string& where,
                const std::string& field);

// The most bytes one value read from a file may take: half the machine's memory, so that a
// damaged or hostile size fails at once with a message rather than in the allocator.
std::uint64_t memory_limit_bytes();

// `dims` multiplied, checked for overflow and against memory_limit_bytes() for values of
// `bytes_per_value`: "<where>: <field> declares 2000000000 x 10 x 10 values (800 GB), more than
// the limit of 4 GB (half this machine's memory)".
std::uint64_t value_count(const std::vector<std::uint64_t>& dims, std::size_t bytes_per_value,
                          const std::string& where, const std::string& field);

// A byte count as a person reads it: "812 bytes", "3.2 MB", "800 GB".
std::string format_bytes(double bytes);

}  // namespace tactile::checks
