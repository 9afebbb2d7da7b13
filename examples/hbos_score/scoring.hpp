#pragma once
/// \file
/// hbos-score's one modelling step: fit the chosen model on every row, score every row, apply
/// the threshold. Both modes give the same result shape, so output and summary do not care which
/// one ran.
///
/// Memory: the model is fitted one feature at a time (HBOS is a sum over features of
/// per-feature terms; both modes add them in the library's order, so the scores are bitwise
/// those of a model fitted on all features at once), and each feature's values are overwritten
/// by its contributions as soon as they are scored. Beyond the values themselves a run costs
/// O(rows) (scores, labels) plus O(features) (names, bin counts), never a fitted histogram per
/// feature at once.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "csv_reader.hpp"
#include "row_store.hpp"
#include "score_options.hpp"

namespace hbos::cli {

/// The model's verdict on every row of a table.
struct ScoredTable {
  Eigen::VectorXd scores;  ///< one per row, higher = more anomalous
  /// rows x features, row-major: each feature's contribution to each score; a row sums to its
  /// score (to rounding). Made from the values, in place.
  RowStore contributions;
  double threshold = 0.0;          ///< outliers have score > threshold
  Eigen::VectorXi outlier;         ///< 1 where score > threshold, else 0
  Eigen::Index n_outliers = 0;     ///< rows with outlier == 1
  std::vector<Eigen::Index> bins;  ///< bins per feature (before any shifting)
  std::string model;               ///< one line describing the fitted model
};

/// Fits the model `options` asks for on `values` (rows x layout.n_features(), consumed: it
/// becomes ScoredTable::contributions), scores and thresholds every row.
/// \throws hbos::InvalidArgument (from the library, prefixed with the feature's name) or
///         std::invalid_argument (options).
[[nodiscard]] ScoredTable score_table(const ScoreOptions& options, const CsvLayout& layout,
                                      RowStore values);

}  // namespace hbos::cli
