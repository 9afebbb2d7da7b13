#pragma once
/// \file
/// The one exception type the library throws, and the helpers that build its messages.
///
/// Every message names what was wrong and the offending value, e.g.
/// `hbos: range_alpha must lie in (0, 1), got 1.5`.

#include <array>
#include <charconv>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace hbos {

/// Thrown for every invalid input or parameter. Derived from std::invalid_argument so generic
/// handlers keep working.
class InvalidArgument : public std::invalid_argument {
 public:
  explicit InvalidArgument(const std::string& what) : std::invalid_argument("hbos: " + what) {}
};

namespace detail {

/// Streams one message part; floating-point values in their shortest round-trip form, so a
/// message says "got 0.6", not "got 0.59999999999999998", yet never hides a difference.
template <class Part>
void append(std::ostringstream& out, const Part& part) {
  if constexpr (std::is_floating_point_v<Part>) {
    std::array<char, 32> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), part);
    out.write(buffer.data(), result.ptr - buffer.data());
  } else {
    out << part;
  }
}

template <class... Parts>
[[nodiscard]] std::string concat(const Parts&... parts) {
  std::ostringstream out;
  (append(out, parts), ...);
  return out.str();
}

/// Throws InvalidArgument with the concatenated message when `condition` is false.
/// The message parts are only formatted on failure, so the check is cheap on the hot path.
template <class... Parts>
void require(bool condition, const Parts&... parts) {
  if (!condition) throw InvalidArgument(concat(parts...));
}

}  // namespace detail
}  // namespace hbos
