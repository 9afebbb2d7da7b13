// The few-bins kernels (hbos/detail/byte_bins.hpp) against the plain rules they replace: the bin
// of every value, the count of every bin and every looked-up score, on lengths that exercise the
// 16-value vectors, the scalar tails and the 255-vector rounds of the compare-and-count.

#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "hbos/detail/byte_bins.hpp"
#include "hbos/model.hpp"

namespace {

template <class Scalar>
std::uint8_t plain_bin(Scalar v, Scalar lo, Scalar inv, Scalar last) {
  const Scalar u = (v - lo) * inv;
  if (!(u > Scalar(0))) return 0;
  if (u >= last) return static_cast<std::uint8_t>(last);
  return static_cast<std::uint8_t>(static_cast<std::int32_t>(u));
}

template <class Scalar>
void check_bins(std::size_t k, std::size_t m, std::mt19937_64& rng) {
  const Scalar lo = Scalar(-1.5), hi = Scalar(2.25);
  const Scalar width = (hi - lo) / static_cast<Scalar>(k);
  const Scalar inv = Scalar(1) / width;
  std::uniform_real_distribution<double> u(static_cast<double>(lo), static_cast<double>(hi));
  std::vector<Scalar> x(m);
  for (std::size_t i = 0; i < m; ++i) {
    // A third of the values sit on an edge or one ulp either side of it, where truncation and
    // the cap decide; the rest anywhere in [lo, hi], hi itself included.
    const std::size_t e = i % (k + 1);
    const Scalar edge = e == k ? hi : lo + static_cast<Scalar>(e) * width;
    switch (i % 9) {
      case 0:
        x[i] = edge;
        break;
      case 1:
        x[i] = std::max(lo, std::nextafter(edge, lo));
        break;
      case 2:
        x[i] = std::min(hi, std::nextafter(edge, hi));
        break;
      default:
        x[i] = static_cast<Scalar>(u(rng));
    }
  }
  std::vector<std::uint8_t> b(m, 0xFF);
  const auto last = static_cast<Scalar>(k - 1);
  hbos::detail::uniform_byte_bins(x.data(), m, lo, inv, last, b.data());
  for (std::size_t i = 0; i < m; ++i) {
    INFO("k " << k << ", m " << m << ", i " << i << ", x " << x[i]);
    REQUIRE(b[i] == plain_bin(x[i], lo, inv, last));
  }
}

}  // namespace

TEST_CASE("uniform_byte_bins gives the bin of the scalar rule for every value", "[byte_bins]") {
  std::mt19937_64 rng(7);
  for (const std::size_t k : {1UL, 2UL, 3UL, 10UL, 16UL, 255UL}) {
    for (const std::size_t m : {0UL, 1UL, 15UL, 16UL, 17UL, 33UL, 256UL, 1000UL}) {
      check_bins<double>(k, m, rng);
      check_bins<float>(k, m, rng);
    }
  }
}

TEST_CASE("interleaved_byte_bins_2 gives each feature's uniform_byte_bins", "[byte_bins]") {
  // Two features stored row by row, each with its own range and bin count: every byte must be
  // the bin uniform_byte_bins gives the feature's own contiguous column (and the scalar rule),
  // on row counts that exercise the 16-row vectors and the scalar tail.
  std::mt19937_64 rng(13);
  auto run = [&](auto zero, std::size_t k0, std::size_t k1, std::size_t m) {
    using Scalar = decltype(zero);
    const Scalar lo0 = Scalar(-1.5), hi0 = Scalar(2.25), lo1 = Scalar(1e3), hi1 = Scalar(1e3 + 7);
    const Scalar w0 = (hi0 - lo0) / static_cast<Scalar>(k0),
                 w1 = (hi1 - lo1) / static_cast<Scalar>(k1);
    const hbos::detail::ByteBinConstants<Scalar> c0{lo0, Scalar(1) / w0,
                                                    static_cast<Scalar>(k0 - 1)};
    const hbos::detail::ByteBinConstants<Scalar> c1{lo1, Scalar(1) / w1,
                                                    static_cast<Scalar>(k1 - 1)};
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Scalar> rows(2 * m), col0(m), col1(m);
    for (std::size_t r = 0; r < m; ++r) {
      // On an edge, one ulp either side of it, or anywhere in the range, hi included.
      auto value = [&](Scalar lo, Scalar hi, Scalar w, std::size_t k, std::size_t salt) {
        const std::size_t e = (r + salt) % (k + 1);
        const Scalar edge = e == k ? hi : lo + static_cast<Scalar>(e) * w;
        switch ((r + salt) % 7) {
          case 0:
            return edge;
          case 1:
            return std::max(lo, std::nextafter(edge, lo));
          case 2:
            return std::min(hi, std::nextafter(edge, hi));
          default:
            return std::min(hi, lo + static_cast<Scalar>(u(rng)) * (hi - lo));
        }
      };
      col0[r] = rows[2 * r] = value(lo0, hi0, w0, k0, 0);
      col1[r] = rows[2 * r + 1] = value(lo1, hi1, w1, k1, 3);
    }
    std::vector<std::uint8_t> b0(m + 1, 0xEE), b1(m + 1, 0xEE), e0(m), e1(m);
    hbos::detail::interleaved_byte_bins_2(rows.data(), m, c0, c1, b0.data(), b1.data());
    hbos::detail::uniform_byte_bins(col0.data(), m, c0.lo, c0.inv, c0.last, e0.data());
    hbos::detail::uniform_byte_bins(col1.data(), m, c1.lo, c1.inv, c1.last, e1.data());
    for (std::size_t r = 0; r < m; ++r) {
      INFO("k " << k0 << ", " << k1 << ", m " << m << ", row " << r);
      REQUIRE(b0[r] == e0[r]);
      REQUIRE(b1[r] == e1[r]);
      REQUIRE(b0[r] == plain_bin(col0[r], c0.lo, c0.inv, c0.last));
      REQUIRE(b1[r] == plain_bin(col1[r], c1.lo, c1.inv, c1.last));
    }
    REQUIRE(b0[m] == 0xEE);  // nothing written past the rows
    REQUIRE(b1[m] == 0xEE);
  };
  for (const auto& [k0, k1] : std::vector<std::pair<std::size_t, std::size_t>>{
           {10, 10}, {1, 16}, {16, 3}, {7, 255}, {2, 1}}) {
    for (const std::size_t m : {0UL, 1UL, 15UL, 16UL, 17UL, 31UL, 32UL, 33UL, 1000UL, 4081UL}) {
      run(0.0, k0, k1, m);
      run(0.0F, k0, k1, m);
    }
  }
}

TEST_CASE("count_byte_indices counts every bin exactly", "[byte_bins]") {
  std::mt19937_64 rng(11);
  // 4080 = 255 vectors of 16: one full round of the byte lanes; 9000 needs three rounds.
  for (const std::size_t k : {1UL, 2UL, 5UL, 10UL, 16UL}) {
    for (const std::size_t m : {0UL, 1UL, 7UL, 16UL, 255UL, 4080UL, 4081UL, 4096UL, 9000UL}) {
      std::vector<std::uint8_t> index(m);
      std::uniform_int_distribution<int> pick(0, static_cast<int>(k) - 1);
      // Half the runs put every value in one bin: the lanes then reach their 255 limit.
      const bool one_bin = (m % 2) == 0;
      for (auto& b : index)
        b = static_cast<std::uint8_t>(one_bin ? k - 1 : static_cast<std::size_t>(pick(rng)));
      std::vector<std::uint64_t> expected(k, 0), counts(k, 3);  // counts are added to
      for (const auto b : index) ++expected[b];
      hbos::detail::count_byte_indices(index.data(), m, k, counts.data());
      for (std::size_t b = 0; b < k; ++b) {
        INFO("k " << k << ", m " << m << ", bin " << b);
        REQUIRE(counts[b] == expected[b] + 3);
      }
    }
  }
}

TEST_CASE("lookup_byte_indices writes the table entry of every index, streamed or not",
          "[byte_bins]") {
  std::vector<double> table(256);
  for (std::size_t i = 0; i < table.size(); ++i) table[i] = std::log1p(static_cast<double>(i));
  std::vector<std::uint8_t> index(1001);
  for (std::size_t i = 0; i < index.size(); ++i) index[i] = static_cast<std::uint8_t>(i * 37);
  for (const bool stream : {false, true}) {
    for (const std::size_t offset : {0UL, 1UL}) {  // an unaligned output falls back to plain stores
      Eigen::VectorXd out = Eigen::VectorXd::Constant(1002, -1.0);
      hbos::detail::lookup_byte_indices(table.data(), index.data(), 1001, out.data() + offset,
                                        stream);
      hbos::detail::fence_streaming_stores();
      for (std::size_t i = 0; i < 1001; ++i)
        REQUIRE(out[static_cast<Eigen::Index>(i + offset)] == table[index[i]]);
    }
  }
}

TEMPLATE_TEST_CASE(
    "fit_and_score over 2^20 rows (few bins, streamed scores) equals fit, then score",
    "[byte_bins]", float, double) {
  // The large-output path: one-byte indices counted by compares and two features' scores written
  // past the caches. Bitwise what fitting and then scoring gives.
  using Model = hbos::Hbos<TestType>;
  const Eigen::Index n = Eigen::Index{1} << 20;
  std::mt19937_64 rng(20240611);
  std::normal_distribution<double> normal;
  typename Model::Matrix x(n, 2);
  for (Eigen::Index j = 0; j < 2; ++j)
    for (Eigen::Index i = 0; i < n; ++i) x(i, j) = static_cast<TestType>(normal(rng));
  for (const int bins : {10, 16}) {
    hbos::HbosParams params;
    params.feature.binning.bins = bins;
    params.feature.binning.shifts = 1;
    typename Model::Vector training(n);
    const Model model = Model::fit_and_score(x, training, params);
    const typename Model::Vector scored = Model::fit(x, params).score(x);
    REQUIRE(model.score(x) == scored);
    REQUIRE(training == scored);
  }
}
