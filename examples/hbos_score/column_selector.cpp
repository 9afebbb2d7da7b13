#include "column_selector.hpp"

#include <charconv>
#include <stdexcept>

namespace hbos::cli {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

/// "x0, x1, ..., label": enough of the header to spot a typo without flooding the terminal.
std::string describe_columns(const std::vector<std::string>& names) {
  constexpr std::size_t kShown = 12;
  std::string out;
  for (std::size_t j = 0; j < names.size(); ++j) {
    if (names.size() > kShown && j == kShown - 2) {
      out += "..., ";
      j = names.size() - 1;
    }
    out += names[j];
    if (j + 1 < names.size()) out += ", ";
  }
  return out;
}

}  // namespace

std::size_t select_column(std::string_view selector, const std::vector<std::string>& names) {
  std::size_t found = names.size();
  for (std::size_t j = 0; j < names.size(); ++j) {
    if (names[j] != selector) continue;
    if (found != names.size()) {
      throw std::invalid_argument("column name \"" + std::string(selector) +
                                  "\" is used by columns " + std::to_string(found) + " and " +
                                  std::to_string(j) +
                                  "; select the column by its 0-based index instead");
    }
    found = j;
  }
  if (found != names.size()) return found;

  std::size_t index = 0;
  const char* end = selector.data() + selector.size();
  const auto [ptr, ec] = std::from_chars(selector.data(), end, index);
  if (!selector.empty() && ec == std::errc() && ptr == end && index < names.size()) return index;
  if (selector == "last" && !names.empty()) return names.size() - 1;

  throw std::invalid_argument("no column is named \"" + std::string(selector) +
                              "\", and it is neither a 0-based index below " +
                              std::to_string(names.size()) +
                              " nor \"last\" (columns: " + describe_columns(names) + ")");
}

std::vector<std::string> split_list(std::string_view list) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = list.find(',', start);
    const std::string_view item = trim(list.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (item.empty()) {
      throw std::invalid_argument("empty item in the list \"" + std::string(list) + "\"");
    }
    items.emplace_back(item);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return items;
}

}  // namespace hbos::cli
