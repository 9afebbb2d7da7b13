#pragma once
/// \file
/// ROC-AUC of outlier scores against 0/1 ground truth, as scikit-learn's `roc_auc_score`.

#include <Eigen/Core>
#include <optional>

namespace hbos::cli {

/// The area under the ROC curve of `scores` (higher = more likely an outlier) against `labels`
/// (1 = outlier, 0 = inlier): the Mann–Whitney statistic
///
///     AUC = (R_1 - n_1 (n_1 + 1) / 2) / (n_1 n_0),
///
/// with R_1 the sum of the outliers' ranks among all scores and tied scores sharing their average
/// rank, so an outlier tied with an inlier counts one half, exactly as the trapezoidal area that
/// scikit-learn computes. Ranks are summed in integers (twice the average rank is an integer), so
/// the result is the correctly rounded quotient, independent of the order of the samples.
///
/// \returns std::nullopt when the labels hold only one class (the AUC is undefined).
/// \throws std::invalid_argument when the sizes differ, a label is not 0 or 1, or a score is NaN.
[[nodiscard]] std::optional<double> roc_auc(const Eigen::Ref<const Eigen::VectorXd>& scores,
                                            const Eigen::Ref<const Eigen::VectorXi>& labels);

}  // namespace hbos::cli
