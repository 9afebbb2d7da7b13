#pragma once
/// \file
/// Writes a built case as CSV (one file per frame pair plus `pairs.csv`) and the manifest entry
/// describing it. The format is documented in docs/screening_cases.md and read by
/// tests/support/screening_cases.hpp; numbers are rounded to fixed decimals so that the files are
/// small and the same bytes on every run.

#include "case_builder.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hbos::cases {

/// The header of every pair file (the loader checks it).
[[nodiscard]] const char* pair_csv_header();
/// The header of `pairs.csv`.
[[nodiscard]] const char* pairs_csv_header();

/// Writes `folder/pair_NN.csv` and `folder/pairs.csv` (creating `folder`) and returns the
/// case's manifest entry (name, people, speed, mask, rough pose, seed, per-pair rough-pose info).
nlohmann::ordered_json write_case(const std::string& folder, const CaseSpec& spec,
                                  const std::vector<PairRecord>& pairs);

}  // namespace hbos::cases
