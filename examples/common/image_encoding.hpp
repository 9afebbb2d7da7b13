#pragma once
// Checks of an encoded image file's bytes that OpenCV does not make (shared by the front end's
// dataset reader and the renderer's textures).

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

namespace hbos::examples {

/// Why an encoded JPEG or PNG is incomplete, or empty when it is whole. OpenCV decodes a
/// truncated JPEG (grey rows where data is missing) and only warns on stderr, so the ends are
/// checked here: a JPEG must end with its EOI marker FF D9 (trailing padding of up to 64 bytes is
/// tolerated), a PNG with its IEND chunk.
inline std::string incomplete_encoding(const std::vector<unsigned char>& b) {
  const std::size_t n = b.size();
  if (n >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) {
    const std::size_t from = n > 66 ? n - 66 : 0;
    for (std::size_t i = n - 1; i > from; --i) {
      if (b[i - 1] == 0xFF && b[i] == 0xD9) return {};
    }
    return "is a truncated JPEG (no end-of-image marker FF D9)";
  }
  static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (n >= 8 && std::equal(kPng, kPng + 8, b.begin())) {
    static constexpr unsigned char kIend[8] = {'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
    if (n >= 8 + 12 && std::equal(kIend, kIend + 8, b.end() - 8)) return {};
    return "is a truncated PNG (no IEND chunk at its end)";
  }
  return {};  // another format: left to OpenCV
}

/// The bit depth of a PNG's samples (its IHDR chunk), 0 for another format.
inline int png_bit_depth(const std::vector<unsigned char>& b) {
  static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (b.size() < 25 || !std::equal(kPng, kPng + 8, b.begin())) return 0;
  return b[24];  // signature 8, chunk length 4, "IHDR" 4, width 4, height 4, then bit depth
}

}  // namespace hbos::examples
