#pragma once
/// \file
/// hbos-score's one modelling step: fit the chosen model on every row, score every row, apply
/// the threshold. Both modes give the same result shape, so output and summary do not care which
/// one ran.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "csv_reader.hpp"
#include "score_options.hpp"

namespace hbos::cli {

/// The model's verdict on every row of a table.
struct ScoredTable {
  Eigen::VectorXd scores;         ///< one per row, higher = more anomalous
  Eigen::MatrixXd contributions;  ///< rows x features; each row sums to its score (to rounding)
  double threshold = 0.0;         ///< outliers have score > threshold
  Eigen::VectorXi outlier;        ///< 1 where score > threshold, else 0
  Eigen::Index n_outliers = 0;
  std::vector<Eigen::Index> bins;  ///< bins per feature (before any shifting)
  std::string model;               ///< one line describing the fitted model
};

/// Fits the model `options` asks for on `table.features`, scores and thresholds every row.
/// \throws hbos::InvalidArgument (from the library) or std::invalid_argument (options).
[[nodiscard]] ScoredTable score_table(const ScoreOptions& options, const CsvTable& table);

}  // namespace hbos::cli
