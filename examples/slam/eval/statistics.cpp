#include "eval/statistics.hpp"

#include <hbos/error.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace hbos::slam {

ErrorStatistics ErrorStatistics::radians_to_degrees() const {
  constexpr double kPi = 3.141592653589793;  // numpy.pi, the double nearest to π
  const auto convert = [](double radians) { return radians * 180.0 / kPi; };
  ErrorStatistics s = *this;
  s.rmse = convert(rmse);
  s.mean = convert(mean);
  s.median = convert(median);
  s.std_dev = convert(std_dev);
  s.min = convert(min);
  s.max = convert(max);
  return s;
}

ErrorStatistics compute_statistics(const Eigen::VectorXd& errors) {
  detail::require(errors.size() > 0, "compute_statistics: no errors to summarise");
  for (Eigen::Index i = 0; i < errors.size(); ++i) {
    detail::require(std::isfinite(errors[i]), "compute_statistics: error ", i, " of ",
                    errors.size(), " is not finite (", errors[i], ")");
  }
  const Eigen::Index n = errors.size();
  const auto count = static_cast<double>(n);
  ErrorStatistics s;
  s.count = n;
  s.rmse = std::sqrt(errors.squaredNorm() / count);
  s.mean = errors.sum() / count;
  // Two passes, like numpy.std: subtracting the mean first avoids the cancellation of
  // E[e²] − E[e]².
  s.std_dev = std::sqrt((errors.array() - s.mean).square().sum() / count);
  s.min = errors.minCoeff();
  s.max = errors.maxCoeff();

  std::vector<double> sorted(errors.data(), errors.data() + n);
  const auto half = static_cast<std::vector<double>::difference_type>(n / 2);
  std::nth_element(sorted.begin(), sorted.begin() + half, sorted.end());
  const double upper = sorted[static_cast<std::size_t>(half)];
  if (n % 2 == 1) {
    s.median = upper;
  } else {
    // After nth_element everything before `half` is <= upper; its largest is the lower middle.
    const double lower = *std::max_element(sorted.begin(), sorted.begin() + half);
    s.median = (lower + upper) / 2.0;
  }
  return s;
}

}  // namespace hbos::slam
