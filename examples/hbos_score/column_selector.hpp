#pragma once
/// \file
/// How the command-line tools let a user point at a column: by name, by 0-based index, or `last`.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace hbos::cli {

/// The index of the column `selector` designates among `names`: an exact name first (so a
/// column literally named `3` or `last` is found by its name), then a 0-based index, then `last`.
/// \throws std::invalid_argument naming the selector and the available columns when nothing
///         matches, or when the name is used by several columns.
[[nodiscard]] std::size_t select_column(std::string_view selector,
                                        const std::vector<std::string>& names);

/// Splits a comma-separated list (`a,b,3`) into its items, trimming spaces around each.
/// \throws std::invalid_argument on an empty item (`a,,b`, a trailing comma, an empty list).
[[nodiscard]] std::vector<std::string> split_list(std::string_view list);

}  // namespace hbos::cli
