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

}  // namespace hbos::examples
