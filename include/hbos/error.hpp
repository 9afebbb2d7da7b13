#pragma once
/// \file
/// The one exception type the library throws, and the helpers that build its messages.
///
/// Every message names what was wrong and the offending value, e.g.
/// `hbos: range_alpha must lie in (0, 1), got 1.5`.

#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace hbos {

/// Thrown for every invalid input or parameter. Derived from std::invalid_argument so generic
/// handlers keep working.
class InvalidArgument : public std::invalid_argument {
 public:
  explicit InvalidArgument(const std::string& what) : std::invalid_argument("hbos: " + what) {}
};

namespace detail {

template <class... Parts>
[[nodiscard]] std::string concat(Parts&&... parts) {
  std::ostringstream out;
  out.precision(17);
  (out << ... << std::forward<Parts>(parts));
  return out.str();
}

/// Throws InvalidArgument with the concatenated message when `condition` is false.
/// The message parts are only formatted on failure, so the check is cheap on the hot path.
template <class... Parts>
void require(bool condition, Parts&&... parts) {
  if (!condition) throw InvalidArgument(concat(std::forward<Parts>(parts)...));
}

}  // namespace detail
}  // namespace hbos
