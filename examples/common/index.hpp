#pragma once
/// \file
/// A signed index (Eigen's, OpenCV's `int`) as the position in a std::vector, in one named place:
/// the examples index vectors with the indices their libraries hand out, which are never negative.

#include <cstddef>
#include <type_traits>

namespace hbos::examples {

template <class SignedIndex>
[[nodiscard]] constexpr std::size_t at(SignedIndex i) noexcept {
  static_assert(std::is_integral_v<SignedIndex>, "an index is an integer");
  return static_cast<std::size_t>(i);
}

}  // namespace hbos::examples
