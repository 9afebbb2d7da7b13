#pragma once
// Input as an error message shows it (shared by the CSV, trajectory and other readers).

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace hbos::examples {

/// `text` as a message shows it: at most 40 characters (then "..."), `\r` as \r, other control
/// bytes and DEL as \xhh, a backslash and the quote character escaped, the whole between two
/// `quote`s. With `ascii_only`, bytes beyond ASCII are escaped too: where only ASCII can be right
/// (a number), a byte order mark or stray binary is shown instead of printing as nothing.
inline std::string shown_text(std::string_view text, char quote = '"', bool ascii_only = false) {
  constexpr std::size_t kMax = 40;
  std::string out(1, quote);
  for (std::size_t i = 0; i < text.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\r') {
      out += "\\r";
    } else if (c == static_cast<unsigned char>(quote) || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20 || c == 0x7f || (ascii_only && c > 0x7f)) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned>(c));
      out += hex;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (text.size() > kMax) out += "...";
  return out + quote;
}

}  // namespace hbos::examples
