#pragma once
// Test data shared by the model-file and merge tests: a matrix whose features have the shapes
// that stress histogram fits (a normal, an exponential tail, an integer-valued feature with ties
// on bin edges, an angle, optionally a constant), and a bit-for-bit comparison of results.

#include <Eigen/Core>
#include <algorithm>

#include <cstdint>
#include <cstring>
#include <random>
#include <type_traits>
#include <vector>

namespace hbos::test {

template <class Scalar>
using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

/// n rows of: normal(100, 4), exponential(0.5), an integer die 0..6, uniform(-10, 10), and with
/// `constant_column` a fifth feature of 2.5 everywhere. The same seed gives the same first four.
template <class Scalar>
Matrix<Scalar> mixed_features(std::uint32_t seed, Eigen::Index n, bool constant_column = false) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::exponential_distribution<double> expo(0.5);
  std::uniform_int_distribution<int> dice(0, 6);
  std::uniform_real_distribution<double> angle(-10.0, 10.0);
  Matrix<Scalar> x(n, constant_column ? 5 : 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    x(i, 0) = static_cast<Scalar>(normal(rng) * 4.0 + 100.0);
    x(i, 1) = static_cast<Scalar>(expo(rng));
    x(i, 2) = static_cast<Scalar>(dice(rng));
    x(i, 3) = static_cast<Scalar>(angle(rng));
    if (constant_column) x(i, 4) = Scalar(2.5);
  }
  return x;
}

/// Same shape and the same bits in every coefficient (so +0 and -0, or two NaNs, are told apart
/// as a bit-exact contract requires).
template <class Derived, class Other>
bool same_bits(const Eigen::DenseBase<Derived>& a, const Eigen::DenseBase<Other>& b) {
  using Scalar = typename Derived::Scalar;
  static_assert(std::is_same_v<Scalar, typename Other::Scalar>, "compare like with like");
  const auto& da = a.derived().eval();
  const auto& db = b.derived().eval();
  return da.rows() == db.rows() && da.cols() == db.cols() &&
         (da.size() == 0 || std::memcmp(da.data(), db.data(),
                                        sizeof(Scalar) * static_cast<std::size_t>(da.size())) == 0);
}

/// Row shards of x cut at `cuts` (any order, duplicates ignored; from 0 to x.rows()).
template <class Scalar>
std::vector<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>> row_shards(
    const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& x,
    std::vector<Eigen::Index> cuts) {
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  std::vector<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>> shards;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    shards.push_back(x.middleRows(cuts[i], cuts[i + 1] - cuts[i]));
  return shards;
}

}  // namespace hbos::test
