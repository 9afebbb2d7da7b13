// Tests of the order-statistic selection behind numpy's percentile (hbos/detail/numpy.hpp):
// radix_select_adjacent and both numpy_percentile_linear overloads against a full std::sort, on
// random and adversarial inputs (ties like HBOS scores, all equal, sorted, reversed, both zeros,
// denormals, the largest magnitudes, infinities, values over every order of magnitude, inputs
// that defeat the sample), float and double, sizes around the crossover to std::nth_element and
// around the bucket count.

#include <hbos/detail/numpy.hpp>
#include <hbos/threshold.hpp>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using hbos::detail::kRadixSelectMin;

template <class Scalar>
bool same_bits(Scalar a, Scalar b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// The selection's contract for one result: the sorted array's value to the bit, except that a
/// zero may come back with either sign that the input holds.
template <class Scalar>
bool matches(Scalar got, Scalar expected, const std::vector<Scalar>& input) {
  if (expected != Scalar(0)) return same_bits(got, expected);
  if (got != Scalar(0)) return false;
  return std::any_of(input.begin(), input.end(), [got](Scalar x) { return same_bits(x, got); });
}

/// Sorted by value, zeros by sign bit: equal multisets of bit patterns compare equal.
template <class Scalar>
std::vector<Scalar> canonical(std::vector<Scalar> v) {
  std::sort(v.begin(), v.end(), [](Scalar a, Scalar b) {
    if (a != b) return a < b;
    return std::signbit(a) && !std::signbit(b);
  });
  return v;
}

/// numpy.percentile(linear) from a full sort: the reference.
template <class Scalar>
Scalar reference_percentile(const std::vector<Scalar>& sorted, double q) {
  const std::size_t n = sorted.size();
  const double v = static_cast<double>(n - 1) * q;
  const auto i = static_cast<std::size_t>(std::floor(v));
  if (i + 1 >= n) return sorted[n - 1];
  return static_cast<Scalar>(hbos::detail::numpy_lerp(static_cast<double>(sorted[i]),
                                                      static_cast<double>(sorted[i + 1]),
                                                      v - static_cast<double>(i)));
}

/// A percentile result: bitwise the reference's, or a zero of either sign when that is zero (the
/// interpolation of two zeros is a zero of either sign).
template <class Scalar>
bool percentile_matches(Scalar got, Scalar expected) {
  return expected != Scalar(0) ? same_bits(got, expected) : got == Scalar(0);
}

struct Case {
  std::string name;
  std::vector<double> values;
};

/// Inputs of n values; Scalar picks the magnitudes (float's largest is 3.4e38).
template <class Scalar>
std::vector<Case> inputs(std::size_t n, std::mt19937_64& rng) {
  using L = std::numeric_limits<Scalar>;
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Case> out;
  auto make = [&](const std::string& name, auto f) {
    Case c{name, std::vector<double>(n)};
    for (std::size_t i = 0; i < n; ++i)
      c.values[i] = static_cast<double>(static_cast<Scalar>(f(i)));
    out.push_back(std::move(c));
  };
  make("normal", [&](std::size_t) { return normal(rng); });
  // HBOS-like scores: ~100 distinct values, a few of them holding most rows.
  std::vector<double> levels(100);
  for (auto& l : levels) l = 2.0 + 8.0 * uniform(rng);
  make("hbos-like ties", [&](std::size_t) {
    const double u = uniform(rng);
    return levels[static_cast<std::size_t>(99.0 * u * u * u)];
  });
  make("two values", [&](std::size_t) { return uniform(rng) < 0.9 ? 1.0 : 2.0; });
  make("all equal", [&](std::size_t) { return 2.5; });
  make("sorted", [&](std::size_t i) { return static_cast<double>(i) * 0.25 - 3.0; });
  make("reversed", [&](std::size_t i) { return static_cast<double>(n - i) * 0.25 - 3.0; });
  make("both zeros", [&](std::size_t) {
    const double u = uniform(rng);
    return u < 0.4 ? -0.0 : u < 0.8 ? 0.0 : u < 0.9 ? -1.0 : 1.0;
  });
  make("zeros and tiny values", [&](std::size_t) {
    const double u = uniform(rng);
    const double tiny = static_cast<double>(L::min()) * uniform(rng);  // denormal or 0
    return u < 0.3 ? -0.0 : u < 0.5 ? 0.0 : u < 0.75 ? tiny : -tiny;
  });
  make("denormals", [&](std::size_t) {
    return static_cast<double>(L::denorm_min()) * std::floor(1000.0 * normal(rng));
  });
  make("huge magnitudes", [&](std::size_t) {
    const double u = uniform(rng);
    const double big = static_cast<double>(L::max());
    return u < 0.25 ? big : u < 0.5 ? -big : (2.0 * uniform(rng) - 1.0) * big;
  });
  make("huge and small", [&](std::size_t) {
    const double u = uniform(rng);
    return u < 0.1   ? static_cast<double>(L::max())
           : u < 0.2 ? static_cast<double>(L::lowest())
                     : normal(rng);
  });
  make("every order of magnitude", [&](std::size_t) {
    const double e = (2.0 * uniform(rng) - 1.0) * (std::is_same_v<Scalar, float> ? 37.0 : 300.0);
    return (uniform(rng) < 0.5 ? -1.0 : 1.0) * std::pow(10.0, e);
  });
  make("infinities", [&](std::size_t) {
    const double u = uniform(rng);
    return u < 0.05 ? -L::infinity() : u < 0.2 ? L::infinity() : normal(rng);
  });
  // The sample reads every (n / 2048)-th value: make those all 0 and the rest not.
  const std::size_t stride = std::max<std::size_t>(1, n / 2048);
  make("defeats the sample",
       [&](std::size_t i) { return i % stride == 0 ? 0.0 : 1.0 + std::abs(normal(rng)); });
  make("sample sees only the top",
       [&](std::size_t i) { return i % stride == 0 ? 1e6 + normal(rng) : normal(rng); });
  return out;
}

template <class Scalar>
std::vector<Scalar> as(const std::vector<double>& v) {
  return std::vector<Scalar>(v.begin(), v.end());
}

const double kQs[] = {
    0.0, 1e-9, 0.001, 0.25, 0.5, 0.9, 0.999, 1.0 - 1e-12, std::nextafter(1.0, 0.0), 1.0};

template <class Scalar>
void check_selection_on(const std::vector<Scalar>& input, const std::string& name) {
  const std::size_t n = input.size();
  const std::vector<Scalar> sorted = canonical(input);
  std::vector<std::size_t> ranks = {0, (n - 1) / 2, n - 2};  // every rank k has k + 1 < n
  for (const double q : kQs) {
    const auto i = static_cast<std::size_t>(std::floor(static_cast<double>(n - 1) * q));
    if (i + 1 < n) ranks.push_back(i);
  }
  std::sort(ranks.begin(), ranks.end());
  ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());
  std::vector<Scalar> buffer(n);
  for (const std::size_t k : ranks) {
    INFO(name << ", n = " << n << ", k = " << k);
    {  // separate buffer: input untouched
      const std::vector<Scalar> copy = input;
      const auto [lo, hi] =
          hbos::detail::radix_select_adjacent(copy.data(), n, k, buffer.data(), n).value();
      CHECK(matches(lo, sorted[k], input));
      CHECK(matches(hi, sorted[k + 1], input));
      CHECK(std::memcmp(copy.data(), input.data(), n * sizeof(Scalar)) == 0);
    }
    {  // room for an eighth of the values: a result, or nullopt when it needs more
      const auto got = hbos::detail::radix_select_adjacent(input.data(), n, k, buffer.data(),
                                                           std::max<std::size_t>(1, n / 8));
      if (got) {
        CHECK(matches(got->first, sorted[k], input));
        CHECK(matches(got->second, sorted[k + 1], input));
      }
    }
    {  // the bucket rounds all the way down (no hand-over to std::nth_element)
      const auto [lo, hi] =
          hbos::detail::radix_select_adjacent(input.data(), n, k, buffer.data(), n, 0).value();
      CHECK(matches(lo, sorted[k], input));
      CHECK(matches(hi, sorted[k + 1], input));
    }
    {  // in place: a permutation of the input afterwards
      std::vector<Scalar> work = input;
      const auto [lo, hi] =
          hbos::detail::radix_select_adjacent(work.data(), n, k, work.data(), n).value();
      CHECK(matches(lo, sorted[k], input));
      CHECK(matches(hi, sorted[k + 1], input));
      const std::vector<Scalar> after = canonical(work);
      CHECK(std::equal(after.begin(), after.end(), sorted.begin(), sorted.end(),
                       [](Scalar a, Scalar b) { return same_bits(a, b); }));
    }
  }
  std::vector<Scalar> scratch;  // grown by the first call, reused by the next ones
  for (const double q : kQs) {
    INFO(name << ", n = " << n << ", q = " << q);
    const Scalar expected = reference_percentile(sorted, q);
    CHECK(percentile_matches(hbos::detail::numpy_percentile_linear(input.data(), n, q, scratch),
                             expected));
    std::vector<Scalar> work = input;
    CHECK(percentile_matches(hbos::detail::numpy_percentile_linear(work.data(), work.data() + n, q),
                             expected));
  }
}

template <class Scalar>
void check_sizes(const std::vector<std::size_t>& sizes, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (const std::size_t n : sizes) {
    for (const Case& c : inputs<Scalar>(n, rng)) check_selection_on(as<Scalar>(c.values), c.name);
  }
}

}  // namespace

TEMPLATE_TEST_CASE("numpy percentile: the selection equals a full sort, small and crossover sizes",
                   "[numpy][percentile]", float, double) {
  // From 2048 values on (the sample's size) the bucket rounds are also run to the end.
  check_sizes<TestType>({2, 3, 4, 5, 17, 100, 2047, 2048, 2049, 3001, kRadixSelectMin - 1,
                         kRadixSelectMin, kRadixSelectMin + 1, 2 * kRadixSelectMin + 3},
                        11);
}

TEMPLATE_TEST_CASE("numpy percentile: the selection equals a full sort, large sizes",
                   "[numpy][percentile]", float, double) {
  // 2048 buckets and a 2048-value sample: sizes on and beside their multiples.
  check_sizes<TestType>({2048 * 16 - 1, 2048 * 16, 65536 + 2048 + 1, 200003}, 12);
}

TEMPLATE_TEST_CASE("numpy percentile: one and two values, q at both ends", "[numpy][percentile]",
                   float, double) {
  using Scalar = TestType;
  std::vector<Scalar> scratch;
  const std::vector<Scalar> one = {Scalar(3.5)};
  for (const double q : kQs) {
    CHECK(hbos::detail::numpy_percentile_linear(one.data(), 1, q, scratch) == Scalar(3.5));
  }
  const std::vector<Scalar> two = {Scalar(4), Scalar(2)};
  CHECK(hbos::detail::numpy_percentile_linear(two.data(), 2, 0.0, scratch) == Scalar(2));
  CHECK(hbos::detail::numpy_percentile_linear(two.data(), 2, 0.5, scratch) == Scalar(3));
  CHECK(hbos::detail::numpy_percentile_linear(two.data(), 2, 1.0, scratch) == Scalar(4));
}

TEST_CASE("numpy percentile: random sizes, ranks and inputs against a full sort",
          "[numpy][percentile]") {
  std::mt19937_64 rng(13);
  std::uniform_int_distribution<std::size_t> size(kRadixSelectMin, 40000);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const std::size_t n = size(rng);
    // A few distinct values at a random scale: ties everywhere, ranks land on bucket edges.
    const double scale = std::pow(10.0, 20.0 * uniform(rng) - 10.0);
    const auto distinct = static_cast<int>(1 + 300 * uniform(rng));
    std::vector<double> v(n);
    for (auto& x : v) x = scale * std::floor(distinct * uniform(rng) * uniform(rng));
    const std::vector<double> sorted = canonical(v);
    std::vector<double> buffer(n);
    for (int r = 0; r < 5; ++r) {
      const auto k = static_cast<std::size_t>(uniform(rng) * static_cast<double>(n - 1));
      INFO("trial " << trial << ", n = " << n << ", k = " << k);
      const auto [lo, hi] =
          hbos::detail::radix_select_adjacent(v.data(), n, k, buffer.data(), n).value();
      CHECK(matches(lo, sorted[k], v));
      CHECK(matches(hi, sorted[k + 1], v));
    }
  }
}

TEST_CASE("contamination threshold: contiguous and strided scores against a full sort",
          "[threshold][percentile]") {
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal;
  for (const Eigen::Index n : {Eigen::Index{10}, Eigen::Index{5000}, Eigen::Index{100000}}) {
    // Scores in the first row of a column-major matrix: a strided view, copied to scratch.
    Eigen::MatrixXd m(2, n);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = std::round(20.0 * normal(rng)) / 4;
    const Eigen::VectorXd contiguous = m.row(0).transpose();
    std::vector<double> sorted(contiguous.data(), contiguous.data() + n);
    std::sort(sorted.begin(), sorted.end());
    std::vector<double> scratch;
    for (const double c : {0.5, 0.1, 0.37, 0.001, 1e-6}) {
      INFO("n = " << n << ", contamination " << c);
      const double expected = reference_percentile(sorted, (100.0 * (1.0 - c)) / 100.0);
      const hbos::Contamination rule{c};
      CHECK(hbos::compute_threshold(contiguous, rule, scratch) == expected);
      CHECK(hbos::compute_threshold(m.row(0), rule, scratch) == expected);
      const Eigen::Map<const Eigen::VectorXd> map(contiguous.data(), n);
      CHECK(hbos::compute_threshold(map, rule, scratch) == expected);
    }
  }
}

TEST_CASE("median + k MAD on a large vector equals the sorted computation", "[threshold]") {
  std::mt19937_64 rng(19);
  std::normal_distribution<double> normal;
  const Eigen::Index n = 50001;
  Eigen::VectorXd s(n);
  for (Eigen::Index i = 0; i < n; ++i) s[i] = std::round(8.0 * normal(rng));
  std::vector<double> v(s.data(), s.data() + n);
  std::sort(v.begin(), v.end());
  const double median = v[static_cast<std::size_t>(n / 2)];
  for (auto& x : v) x = std::abs(x - median);
  std::sort(v.begin(), v.end());
  const double mad = v[static_cast<std::size_t>(n / 2)];
  std::vector<double> scratch;
  CHECK(hbos::compute_threshold(s, hbos::MedianMad{3.0, false}, scratch) == median + 3.0 * mad);
}
