#pragma once
/// \file
/// The screens hbos-screening-eval compares: every entry of the library's one name table,
/// hbos::named_strategies() (each built through hbos::ReprojectionScreend(config), single
/// round). `default`, `chi2` and `quantile` are the ones the acceptance rule (issue 7 item 7)
/// compares.

#include <hbos/screening.hpp>

#include <string>
#include <vector>

namespace hbos::cases {

struct NamedScreen {
  std::string name;           ///< column name in the tables
  hbos::ScreenConfig config;  ///< what hbos::ReprojectionScreend is constructed with
};

/// The library's strategies, in its table's order (the default first).
[[nodiscard]] inline std::vector<NamedScreen> eval_strategies() {
  std::vector<NamedScreen> list;
  for (const hbos::NamedStrategy& s : hbos::named_strategies()) {
    hbos::ScreenConfig c;
    c.strategy = s.make();
    list.push_back({s.name, c});
  }
  return list;
}

}  // namespace hbos::cases
