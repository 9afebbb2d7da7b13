#pragma once
/// \file
/// Reads a fuzzer's bytes as a stream of choices and numbers: the fuzz targets' one helper.
/// Running out of bytes yields zeros, so every input, however short, decodes to something.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string_view>

namespace hbos::fuzz {

class FuzzInput {
 public:
  FuzzInput(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  [[nodiscard]] std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  [[nodiscard]] bool flag() { return (byte() & 1U) != 0; }
  /// An integer in [0, n) (n >= 1).
  [[nodiscard]] std::size_t below(std::size_t n) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8U) | byte();
    return static_cast<std::size_t>(v % n);
  }
  /// Raw 8 bytes as a double: NaN, infinities, subnormals and huge values all appear.
  [[nodiscard]] double raw_double() {
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits = (bits << 8U) | byte();
    double v = 0.0;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  /// A value drawn from a mix that hits the interesting edges often: small integers (ties),
  /// ordinary reals, extremes (+-DBL_MAX, +-FLT_MAX, subnormals, +-inf, NaN) and raw bits.
  [[nodiscard]] double value() {
    switch (byte() % 8) {
      case 0:
      case 1:
        return static_cast<double>(static_cast<int>(byte() % 16) - 8);
      case 2:
      case 3:
        return (static_cast<double>(byte()) - 128.0) / 16.0;
      case 4:
        return extreme();
      default:
        return raw_double();
    }
  }
  /// A parameter value: mostly ordinary, often at an edge of its legal range or beyond it.
  [[nodiscard]] double parameter(double ordinary) {
    switch (byte() % 6) {
      case 0:
        return ordinary;
      case 1:
        return ordinary * std::ldexp(1.0, static_cast<int>(byte() % 64) - 32);
      case 2:
        return extreme();
      case 3:
        return raw_double();
      default:
        return static_cast<double>(byte()) / 64.0;
    }
  }
  /// A count: small mostly, sometimes huge or negative.
  [[nodiscard]] long long count(long long ordinary) {
    switch (byte() % 6) {
      case 0:
        return ordinary;
      case 1:
        return -static_cast<long long>(byte());
      case 2:
        return static_cast<long long>(1) << (byte() % 63);
      default:
        return static_cast<long long>(byte() % 40);
    }
  }
  [[nodiscard]] std::string_view rest() const {
    return {reinterpret_cast<const char*>(data_ + pos_), size_ - pos_};
  }
  [[nodiscard]] bool empty() const { return pos_ >= size_; }

 private:
  [[nodiscard]] double extreme() {
    constexpr double table[] = {std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::lowest(),
                                static_cast<double>(std::numeric_limits<float>::max()),
                                -static_cast<double>(std::numeric_limits<float>::max()),
                                std::numeric_limits<double>::min(),
                                std::numeric_limits<double>::denorm_min(),
                                static_cast<double>(std::numeric_limits<float>::min()),
                                static_cast<double>(std::numeric_limits<float>::denorm_min()),
                                std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity(),
                                std::numeric_limits<double>::quiet_NaN(),
                                1e17,
                                6e16,
                                -0.0,
                                0x1p53,
                                1e-308};
    return table[byte() % 16];
  }

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace hbos::fuzz
