#pragma once
/// \file
/// hbos-score's report on standard error: what was read, which model ran, what it found.

#include <string>

#include "score_input.hpp"
#include "score_options.hpp"
#include "scoring.hpp"

namespace hbos::cli {

/// A few lines for a human: rows and features read, the model and its bins per feature, the
/// threshold and the outliers it flags, the ROC-AUC against the label column when there is one,
/// and the `options.top` highest-scoring rows with the features that contribute most.
[[nodiscard]] std::string format_summary(const ScoreOptions& options, const ScoreInput& table,
                                         const ScoredTable& scored);

}  // namespace hbos::cli
