// The run-time instruction-set dispatch (hbos/detail/isa.hpp): every kernel with an AVX2 body
// gives the bits of its baseline body, checked kernel by kernel against the plain scalar rules
// and end to end through the public API with each path forced (scores, per-row contributions,
// and the histograms). On a CPU or build without AVX2 both runs take the baseline path (the
// test says so) and the comparisons hold trivially.

#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "hbos/detail/byte_bins.hpp"
#include "hbos/detail/column_view.hpp"
#include "hbos/detail/isa.hpp"
#include "hbos/model.hpp"

namespace {

using hbos::detail::Isa;
using hbos::detail::ScopedIsa;

constexpr std::array<Isa, 2> kIsas{Isa::Baseline, Isa::Avx2};

template <class Scalar>
bool same_bits(Scalar a, Scalar b) {
  return std::memcmp(&a, &b, sizeof(Scalar)) == 0;
}

template <class Scalar>
bool same_bits(const Scalar* a, const Scalar* b, std::size_t n) {
  return n == 0 || std::memcmp(a, b, n * sizeof(Scalar)) == 0;
}

// Lengths around every vector width, unroll and round of the kernels.
const std::vector<std::size_t>& lengths() {
  static const std::vector<std::size_t> l = {
      0,  1,  2,   3,   7,   8,   15,  16,  17,   31,   32,   33,   47,   48,   63,   64,
      65, 95, 127, 128, 129, 255, 256, 257, 4079, 4080, 4081, 8160, 8161, 8192, 16417};
  return l;
}

// Values in [lo, hi] that sit on the bin edges, one ulp beside them, at hi, or anywhere.
template <class Scalar>
std::vector<Scalar> edge_values(std::size_t m, std::size_t k, Scalar lo, Scalar hi,
                                std::mt19937_64& rng) {
  const Scalar width = (hi - lo) / static_cast<Scalar>(k);
  std::uniform_real_distribution<double> u(static_cast<double>(lo), static_cast<double>(hi));
  std::vector<Scalar> x(m);
  for (std::size_t i = 0; i < m; ++i) {
    const Scalar edge = lo + static_cast<Scalar>(rng() % (k + 1)) * width;
    switch (rng() % 4) {
      case 0:
        x[i] = std::min(edge, hi);
        break;
      case 1:
        x[i] = std::min(std::nextafter(edge, hi + 1), hi);
        break;
      case 2:
        x[i] = std::max(std::nextafter(edge, lo - 1), lo);
        break;
      default:
        x[i] = static_cast<Scalar>(u(rng));
    }
  }
  return x;
}

template <class Scalar>
std::uint8_t plain_bin(Scalar v, Scalar lo, Scalar inv, Scalar last) {
  const Scalar u = (v - lo) * inv;
  return static_cast<std::uint8_t>(static_cast<std::int32_t>(u < last ? u : last));
}

template <class Scalar>
void check_bin_kernels(std::mt19937_64& rng) {
  for (const std::size_t k :
       {std::size_t{1}, std::size_t{2}, std::size_t{3}, std::size_t{10}, std::size_t{16}}) {
    const Scalar lo = Scalar(-1.5), hi = Scalar(2.25);
    const Scalar inv = static_cast<Scalar>(k) / (hi - lo);
    const auto last = static_cast<Scalar>(k - 1);
    for (const std::size_t m : lengths()) {
      const std::vector<Scalar> x = edge_values<Scalar>(m, k, lo, hi, rng);
      std::vector<std::uint8_t> expected(m);
      for (std::size_t i = 0; i < m; ++i) expected[i] = plain_bin(x[i], lo, inv, last);
      std::vector<std::uint64_t> expected_counts(k, 0);
      for (const std::uint8_t b : expected) ++expected_counts[b];
      // Two interleaved features: the second takes other constants.
      const std::vector<Scalar> y = edge_values<Scalar>(m, 7, Scalar(-3), Scalar(5), rng);
      std::vector<Scalar> rows(2 * m);
      for (std::size_t i = 0; i < m; ++i) {
        rows[2 * i] = x[i];
        rows[2 * i + 1] = y[i];
      }
      const hbos::detail::ByteBinConstants<Scalar> c0{lo, inv, last};
      const hbos::detail::ByteBinConstants<Scalar> c1{Scalar(-3), Scalar(7) / Scalar(8), Scalar(6)};
      std::vector<std::uint8_t> expected_y(m);
      for (std::size_t i = 0; i < m; ++i) expected_y[i] = plain_bin(y[i], c1.lo, c1.inv, c1.last);
      for (const Isa isa : kIsas) {
        CAPTURE(k, m, static_cast<int>(isa));
        std::vector<std::uint8_t> b(m + 1, 0xAB);
        hbos::detail::uniform_byte_bins(x.data(), m, lo, inv, last, b.data(), isa);
        CHECK(std::equal(expected.begin(), expected.end(), b.begin()));
        CHECK(b[m] == 0xAB);  // nothing written past the end
        std::vector<std::uint64_t> counts(k, 1);
        hbos::detail::count_byte_indices(expected.data(), m, k, counts.data(), isa);
        for (std::size_t j = 0; j < k; ++j) CHECK(counts[j] == expected_counts[j] + 1);
        std::vector<std::uint8_t> b0(m + 1, 0xAB), b1(m + 1, 0xAB);
        hbos::detail::interleaved_byte_bins_2(rows.data(), m, c0, c1, b0.data(), b1.data(), isa);
        CHECK(std::equal(expected.begin(), expected.end(), b0.begin()));
        CHECK(std::equal(expected_y.begin(), expected_y.end(), b1.begin()));
        CHECK(b0[m] == 0xAB);
        CHECK(b1[m] == 0xAB);
      }
    }
  }
}

// The pair-table lookup of two features' one-byte bins: every entry's bits, on each path,
// streamed or not, into aligned and unaligned outputs, with nothing written past the end.
template <class Scalar>
void check_pair_lookup(std::mt19937_64& rng) {
  const std::array<std::array<std::size_t, 2>, 6> shapes{
      {{1, 1}, {2, 3}, {10, 10}, {16, 16}, {3, 85}, {128, 2}}};
  for (const auto& [k0, k1] : shapes) {
    std::vector<Scalar> table(k0 * k1);
    std::uniform_real_distribution<double> u(0.0, 30.0);
    for (Scalar& t : table) t = static_cast<Scalar>(u(rng));
    for (const std::size_t m : lengths()) {
      std::vector<std::uint8_t> first(m), second(m);
      for (std::size_t i = 0; i < m; ++i) {
        first[i] = static_cast<std::uint8_t>(rng() % k0);
        second[i] = static_cast<std::uint8_t>(rng() % k1);
      }
      std::vector<Scalar> expected(m);
      for (std::size_t i = 0; i < m; ++i) expected[i] = table[first[i] * k1 + second[i]];
      for (const bool stream : {false, true}) {
        for (const std::size_t offset : {std::size_t{0}, std::size_t{1}, std::size_t{2}}) {
          std::vector<std::vector<Scalar>> out;
          for (const Isa isa : kIsas) {
            CAPTURE(k0, k1, m, stream, offset, static_cast<int>(isa));
            // 32-byte aligned storage, so that the offsets give each alignment of the output.
            std::vector<Scalar> storage(m + 16, Scalar(-1));
            const auto skip =
                (32 - reinterpret_cast<std::uintptr_t>(storage.data()) % 32) % 32 / sizeof(Scalar);
            Scalar* o = storage.data() + skip + offset;
            hbos::detail::lookup_byte_pairs(table.data(), first.data(), second.data(), k1, m, o,
                                            stream, isa);
            hbos::detail::fence_streaming_stores();
            CHECK(same_bits(expected.data(), o, m));
            CHECK(same_bits(o[m], Scalar(-1)));  // nothing written past the end
            out.emplace_back(o, o + m);
          }
          CHECK(same_bits(out[0].data(), out[1].data(), m));
        }
      }
    }
  }
}

// What the scans must give: the exact min and max and the finiteness. The bits of a zero
// extreme (when -0.0 and +0.0 both occur) depend on the order of the scan; that both paths
// agree on them is checked separately.
template <class Scalar>
void check_scans(std::mt19937_64& rng) {
  const Scalar inf = std::numeric_limits<Scalar>::infinity();
  const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN();
  for (const std::size_t m : lengths()) {
    if (m == 0) continue;
    for (int kind = 0; kind < 6; ++kind) {
      std::vector<Scalar> x(m);
      std::normal_distribution<double> normal;
      for (std::size_t i = 0; i < m; ++i) {
        switch (kind) {
          case 0:  // ordinary values
            x[i] = static_cast<Scalar>(normal(rng));
            break;
          case 1:  // only signed zeros: the extremes' bits come from the order of the scan
            x[i] = rng() % 2 != 0 ? Scalar(0) : -Scalar(0);
            break;
          case 2:  // non-negative with zeros of both signs at the minimum
            x[i] = rng() % 3 == 0 ? (rng() % 2 != 0 ? Scalar(0) : -Scalar(0))
                                  : static_cast<Scalar>(std::abs(normal(rng)));
            break;
          case 3:  // non-positive with zeros of both signs at the maximum
            x[i] = rng() % 3 == 0 ? (rng() % 2 != 0 ? Scalar(0) : -Scalar(0))
                                  : -static_cast<Scalar>(std::abs(normal(rng)));
            break;
          default:  // ordinary values around one non-finite value (placed below)
            x[i] = static_cast<Scalar>(normal(rng));
        }
      }
      if (kind >= 4) {
        const std::array<Scalar, 3> bad{nan, inf, -inf};
        x[rng() % m] = bad[rng() % 3];
        if (kind == 5) x[rng() % m] = inf;
      }
      std::vector<hbos::detail::MinMax<Scalar>> results;
      for (const Isa isa : kIsas) {
        results.push_back(hbos::detail::scan_min_max(
            hbos::detail::ColumnView<Scalar>{x.data(), static_cast<Eigen::Index>(m), 1}, isa));
      }
      CAPTURE(m, kind);
      bool finite = true;
      for (const Scalar v : x) finite = finite && std::isfinite(v);
      for (const auto& r : results) CHECK(r.finite == finite);
      if (!finite) continue;
      const Scalar lo = *std::min_element(x.begin(), x.end());
      const Scalar hi = *std::max_element(x.begin(), x.end());
      for (const auto& r : results) {
        CHECK(r.lo == lo);
        CHECK(r.hi == hi);
      }
      CHECK(same_bits(results[0].lo, results[1].lo));
      CHECK(same_bits(results[0].hi, results[1].hi));
      // The same values as the rows of a row-major matrix of 1, 2, 3 and 4 columns.
      for (const Eigen::Index d : {1, 2, 3, 4}) {
        const auto n = static_cast<Eigen::Index>(m) / d;
        if (n == 0) continue;
        std::array<std::vector<Scalar>, 2> lo_d, hi_d;
        std::array<bool, 2> ok{};
        for (std::size_t p = 0; p < 2; ++p) {
          lo_d[p].assign(static_cast<std::size_t>(d), 0);
          hi_d[p].assign(static_cast<std::size_t>(d), 0);
          ok[p] = hbos::detail::scan_rows_min_max(x.data(), n, d, d, lo_d[p].data(), hi_d[p].data(),
                                                  kIsas[p]);
        }
        CAPTURE(d);
        CHECK(ok[0]);
        CHECK(ok[1]);
        CHECK(same_bits(lo_d[0].data(), lo_d[1].data(), lo_d[0].size()));
        CHECK(same_bits(hi_d[0].data(), hi_d[1].data(), hi_d[0].size()));
      }
    }
  }
}

template <class Scalar>
using RowMajor = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Everything a fit exposes, and the scores, with the kernels on one instruction set.
template <class Scalar>
struct Run {
  std::vector<Scalar> scores, refit_scores, edges, contributions, row_contributions;
  std::vector<Eigen::Index> counts;
  std::string error;
};

template <class Scalar, class Matrix>
Run<Scalar> run_with(Isa isa, const Matrix& x, const hbos::HbosParams& params) {
  const ScopedIsa scoped(isa);
  Run<Scalar> r;
  try {
    typename hbos::Hbos<Scalar>::Vector s(x.rows());
    const auto model = hbos::Hbos<Scalar>::fit_and_score(x, s, params);
    r.scores.assign(s.data(), s.data() + s.size());
    const auto again = hbos::Hbos<Scalar>::fit(x, params).score(x);
    r.refit_scores.assign(again.data(), again.data() + again.size());
    const auto c = model.contributions(x);
    r.row_contributions.assign(c.data(), c.data() + c.size());
    for (Eigen::Index j = 0; j < model.n_features(); ++j) {
      const auto& h = model.histogram(j);
      r.edges.insert(r.edges.end(), h.edges().begin(), h.edges().end());
      r.counts.insert(r.counts.end(), h.counts().begin(), h.counts().end());
      r.contributions.insert(r.contributions.end(), h.bin_contributions().begin(),
                             h.bin_contributions().end());
      r.contributions.push_back(h.cap());
    }
  } catch (const hbos::InvalidArgument& e) {
    r.error = e.what();
  }
  return r;
}

template <class Scalar>
void check_same_run(const Run<Scalar>& a, const Run<Scalar>& b) {
  CHECK(a.error == b.error);
  REQUIRE(a.scores.size() == b.scores.size());
  CHECK(same_bits(a.scores.data(), b.scores.data(), a.scores.size()));
  REQUIRE(a.refit_scores.size() == b.refit_scores.size());
  CHECK(same_bits(a.refit_scores.data(), b.refit_scores.data(), a.refit_scores.size()));
  REQUIRE(a.edges.size() == b.edges.size());
  CHECK(same_bits(a.edges.data(), b.edges.data(), a.edges.size()));
  CHECK(a.counts == b.counts);
  REQUIRE(a.contributions.size() == b.contributions.size());
  CHECK(same_bits(a.contributions.data(), b.contributions.data(), a.contributions.size()));
  REQUIRE(a.row_contributions.size() == b.row_contributions.size());
  CHECK(same_bits(a.row_contributions.data(), b.row_contributions.data(),
                  a.row_contributions.size()));
}

std::vector<hbos::HbosParams> specs() {
  std::vector<hbos::HbosParams> all;
  for (const Eigen::Index bins : {1, 2, 10, 16, 17, 300}) {
    hbos::HbosParams p;
    p.feature.binning.bins = bins;
    p.feature.binning.shifts = 1;
    all.push_back(p);
  }
  all.emplace_back();  // the default: 5 bins x 5 shifts
  hbos::HbosParams fixed;
  fixed.feature.binning.method = hbos::BinningMethod::FixedWidth;
  fixed.feature.binning.width = 0.25;
  fixed.feature.binning.shifts = 1;
  all.push_back(fixed);
  hbos::HbosParams sturges;
  sturges.feature.binning.rule = hbos::BinCountRule::Sturges;
  sturges.feature.binning.shifts = 1;
  all.push_back(sturges);
  hbos::HbosParams frequency;
  frequency.feature.binning.method = hbos::BinningMethod::EqualFrequency;
  all.push_back(frequency);
  return all;
}

// Column j of a test matrix: normal values, a few integers and their neighbours (on and beside
// the edges), a constant, signed zeros at the extremes, or ties.
template <class Scalar>
Scalar test_value(int kind, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  switch (kind) {
    case 0:
      return static_cast<Scalar>(normal(rng));
    case 1: {
      const auto v = static_cast<Scalar>(rng() % 11);
      const int side = static_cast<int>(rng() % 3);
      return side == 0 ? v : std::nextafter(v, side == 1 ? Scalar(-1) : Scalar(11));
    }
    case 2:
      return Scalar(3);
    case 3:
      return rng() % 4 == 0 ? (rng() % 2 != 0 ? Scalar(0) : -Scalar(0))
                            : static_cast<Scalar>(std::abs(normal(rng)));
    default:
      return static_cast<Scalar>(rng() % 3);
  }
}

template <class Scalar>
void check_models(std::mt19937_64& rng) {
  const std::vector<hbos::HbosParams> all = specs();
  for (const Eigen::Index n : {1, 2, 15, 16, 17, 33, 4081, 8161, 100003}) {
    for (const Eigen::Index d : {1, 2, 3, 5}) {
      Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> x(n, d);
      for (Eigen::Index j = 0; j < d; ++j) {
        const int kind = static_cast<int>((j + n) % 5);
        for (Eigen::Index i = 0; i < n; ++i) x(i, j) = test_value<Scalar>(kind, rng);
      }
      const RowMajor<Scalar> rows = x;
      for (std::size_t s = 0; s < all.size(); ++s) {
        if (n > 10000 && s % 3 != 0) continue;  // the large shape on a few specs only
        CAPTURE(n, d, s);
        check_same_run(run_with<Scalar>(Isa::Baseline, x, all[s]),
                       run_with<Scalar>(Isa::Avx2, x, all[s]));
        check_same_run(run_with<Scalar>(Isa::Baseline, rows, all[s]),
                       run_with<Scalar>(Isa::Avx2, rows, all[s]));
      }
      // A non-finite value is refused, naming the same entry, on either path.
      if (n >= 2) {
        for (const Scalar bad :
             {std::numeric_limits<Scalar>::quiet_NaN(), -std::numeric_limits<Scalar>::infinity()}) {
          Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> y = x;
          y(n - 1, d - 1) = bad;
          if (n > 17) y(n / 2, 0) = bad;
          const RowMajor<Scalar> y_rows = y;
          const auto a = run_with<Scalar>(Isa::Baseline, y, all[2]);
          const auto b = run_with<Scalar>(Isa::Avx2, y, all[2]);
          CHECK(!a.error.empty());
          check_same_run(a, b);
          const auto c = run_with<Scalar>(Isa::Baseline, y_rows, all[2]);
          const auto e = run_with<Scalar>(Isa::Avx2, y_rows, all[2]);
          CHECK(!c.error.empty());
          check_same_run(c, e);
        }
      }
    }
  }
}

// Two features over 2^20 rows with 10 bins: the fit and score stream the scores past the
// caches, which the AVX2 pair lookup leaves to the baseline's stores.
template <class Scalar>
void check_streamed_scores(std::mt19937_64& rng) {
  const Eigen::Index n = (Eigen::Index{1} << 20) + 7;
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> x(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    x(i, 0) = test_value<Scalar>(0, rng);
    x(i, 1) = test_value<Scalar>(1, rng);
  }
  const RowMajor<Scalar> rows = x;
  hbos::HbosParams p;
  p.feature.binning.bins = 10;
  p.feature.binning.shifts = 1;
  check_same_run(run_with<Scalar>(Isa::Baseline, x, p), run_with<Scalar>(Isa::Avx2, x, p));
  check_same_run(run_with<Scalar>(Isa::Baseline, rows, p), run_with<Scalar>(Isa::Avx2, rows, p));
}

}  // namespace

TEST_CASE("the instruction set in use can be forced per thread", "[isa]") {
  const Isa best = hbos::detail::best_isa();
  if (best != Isa::Avx2) WARN("no AVX2 body on this CPU or build: both paths are the baseline");
  CHECK(hbos::detail::active_isa() == best);
  {
    const ScopedIsa baseline(Isa::Baseline);
    CHECK(hbos::detail::active_isa() == Isa::Baseline);
    {
      const ScopedIsa avx2(Isa::Avx2);
      CHECK(hbos::detail::active_isa() == best);
    }
    CHECK(hbos::detail::active_isa() == Isa::Baseline);
  }
  CHECK(hbos::detail::active_isa() == best);
}

TEST_CASE("the bin and count kernels give the plain rule's bytes on every path", "[isa]") {
  std::mt19937_64 rng(20261203);
  check_bin_kernels<double>(rng);
  check_bin_kernels<float>(rng);
}

TEST_CASE("the range scans give the same extremes, bit for bit, on every path", "[isa]") {
  std::mt19937_64 rng(7);
  check_scans<double>(rng);
  check_scans<float>(rng);
}

TEST_CASE("fits and scores are bitwise the same on every path", "[isa]") {
  std::mt19937_64 rng(11);
  check_models<double>(rng);
  check_models<float>(rng);
}

TEST_CASE("the pair lookup gives the table's entries, bit for bit, on every path", "[isa]") {
  std::mt19937_64 rng(13);
  check_pair_lookup<double>(rng);
  check_pair_lookup<float>(rng);
}

TEST_CASE("streamed training scores are bitwise the same on every path", "[isa]") {
  std::mt19937_64 rng(17);
  check_streamed_scores<double>(rng);
  check_streamed_scores<float>(rng);
}
