#pragma once
/// \file
/// The study's outputs: a Markdown table for people, a CSV of every number for regression tests.

#include <string>

#include "study.hpp"

namespace hbos::study {

/// Mean ROC-AUC of method `key` over all data sets. \throws std::out_of_range for an unknown key.
[[nodiscard]] double mean_auc(const StudyResult& result, const std::string& key);
/// Column of method `key`. \throws std::out_of_range for an unknown key.
[[nodiscard]] Eigen::Index method_index(const StudyResult& result, const std::string& key);

/// The table (one row per data set, one column per method, 4 decimals, a mean row), a legend of
/// the methods and the verdicts on the targets (default vs PyOD mean, scale invariance).
[[nodiscard]] std::string format_markdown(const StudyResult& result, std::uint64_t seed);

/// `dataset,rows,features,outliers,<method keys>`, one line per data set, every AUC with 17
/// significant digits (reads back to the same double).
[[nodiscard]] std::string format_csv(const StudyResult& result);

}  // namespace hbos::study
