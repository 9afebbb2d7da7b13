#pragma once
/// \file
/// CLI11 checks for numeric options whose messages print numbers as a person writes them.
/// CLI11's own PositiveNumber / NonNegativeNumber print their bound with std::to_string, so a
/// bad value is reported against a 309-digit DBL_MAX. Header-only: each command links CLI11.

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

namespace hbos::examples {

namespace detail {

/// A check that `text` is a finite number with `accept(value)`; `rule` completes "must be ...".
template <class Accept>
CLI::Validator number_check(Accept accept, const std::string& rule, const std::string& name) {
  return CLI::Validator(
      [accept, rule](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size()) {
          return "Value " + text + " is not a number";
        }
        if (!std::isfinite(value) || errno == ERANGE || !accept(value)) {
          std::ostringstream out;  // default stream format: %g-like, 6 significant digits
          out << "Value " << text << " must be " << rule;
          return out.str();
        }
        return std::string();
      },
      name, name);
}

}  // namespace detail

/// A finite number > 0.
inline CLI::Validator positive_number() {
  return detail::number_check([](double v) { return v > 0.0; }, "a finite number > 0", "POSITIVE");
}

/// A finite number >= 0.
inline CLI::Validator non_negative_number() {
  return detail::number_check([](double v) { return v >= 0.0; }, "a finite number >= 0",
                              "NONNEGATIVE");
}

/// A seed: a decimal integer in [0, 2^64 - 1] (the standard parse took "-1" for 2^64 - 1 and
/// larger numbers for 2^64 - 1 too, and an empty value for 0).
inline CLI::Validator seed_value() {
  return CLI::Validator(
      [](std::string& value) {
        const std::string what =
            "a seed is a decimal integer in [0, 18446744073709551615], got '" + value + "'";
        if (value.empty() || value.size() > 20 ||
            value.find_first_not_of("0123456789") != std::string::npos)
          return what;
        errno = 0;
        static_cast<void>(std::strtoull(value.c_str(), nullptr, 10));
        return errno == ERANGE ? what : std::string();
      },
      "SEED");
}

/// A path that is not empty (`--json ''` was silently the same as no --json at all).
inline CLI::Validator non_empty_path() {
  return CLI::Validator(
      [](std::string& value) {
        return value.empty() ? std::string("an empty path names no file") : std::string();
      },
      "PATH");
}

}  // namespace hbos::examples
