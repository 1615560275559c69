#pragma once
// Range checks for numeric options whose errors read as a person would write them, e.g.
// "--px-per-mm: 0 is out of range: must be > 0". CLI11's PositiveNumber, NonNegativeNumber and
// Range on a double print numeric_limits bounds instead: a number of 300 digits.

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <system_error>
#include <type_traits>
#include <utility>

#include "tactile/movie/limits.hpp"

namespace tactile::cli {

namespace detail {

// A validator accepting the numbers for which `ok` holds; `rule` completes "must be ...".
// Written as `ok(v)` rather than its negation so that NaN fails every rule; "inf" and numbers
// beyond a double are refused before the rule, as no command can honour them.
template <typename T, typename Ok>
CLI::Validator number_check(Ok ok, const std::string& rule, std::string description) {
  return CLI::Validator(
      [ok, rule](std::string& value) -> std::string {
        T v{};
        if (!CLI::detail::lexical_cast(value, v)) {
          return fmt::format("{} is not {}", value,
                             std::is_integral_v<T> ? "a whole number" : "a number");
        }
        if constexpr (std::is_floating_point_v<T>) {
          if (!std::isfinite(v)) return fmt::format("{} is not a finite number", value);
        }
        return ok(v) ? std::string() : fmt::format("{} is out of range: must be {}", value, rule);
      },
      std::move(description));
}

}  // namespace detail

// A number > 0.
inline CLI::Validator positive() {
  return detail::number_check<double>([](double v) { return v > 0; }, "> 0", "> 0");
}

// A number >= 0.
inline CLI::Validator non_negative() {
  return detail::number_check<double>([](double v) { return v >= 0; }, ">= 0", ">= 0");
}

// A rate a device can play (movie::kPlayableRateRule), checked where the option is read so the
// error names the option; mapping checks the same rule for every other caller.
inline CLI::Validator playable_rate() {
  return detail::number_check<double>([](double v) { return movie::is_playable_rate(v); },
                                      std::string(movie::kPlayableRateRule), "whole Hz");
}

// A random seed: a whole number from 0 to 2^64 - 1, as typed. CLI11 reads "-1" into an unsigned
// option as 2^64 - 1, another seed than the one written, without a word.
inline CLI::Validator seed_number() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        // from_chars, not CLI11's cast: it reports a number beyond 2^64 - 1 instead of clamping.
        std::uint64_t v{};
        const char* end = value.data() + value.size();
        const auto [stop, error] = std::from_chars(value.data(), end, v);
        if (value.empty() || value.find_first_not_of("0123456789") != std::string::npos ||
            error != std::errc() || stop != end) {
          return fmt::format("{} is not a whole number from 0 to 2^64 - 1", value);
        }
        return {};
      },
      "0 to 2^64 - 1");
}

// A number from `min` to `max`, both included; T is the option's type (int or double).
template <typename T>
CLI::Validator within(T min, T max) {
  const std::string rule = fmt::format("from {} to {}", min, max);
  return detail::number_check<T>([min, max](T v) { return v >= min && v <= max; }, rule,
                                 fmt::format("{} to {}", min, max));
}

}  // namespace tactile::cli
