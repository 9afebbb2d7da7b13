#pragma once
/// \file
/// numpy's rounding and percentile rules, replicated to the bit: the threshold rules and the
/// PyOD-compatible mode both need `numpy.percentile(..., method="linear")` exactly as numpy
/// computes it.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace hbos::detail {

/// `a * b` rounded to T before the caller uses it. Bit-parity with numpy needs a product and a
/// following addition to round twice; GCC (GNU mode, -ffp-contract=fast) and Clang
/// (-ffp-contract=on) may fuse them into one FMA when the target has FMA (-march=native, -mfma),
/// and GCC ignores
/// `#pragma STDC FP_CONTRACT`. Storing the product through a volatile forces the rounding on
/// every compiler; it costs one store/load, so it is used only where parity depends on it.
template <class T>
[[nodiscard]] inline T mul_rounded(T a, T b) {
  volatile T product = a * b;
  return product;
}

/// numpy's `_lerp(a, b, t)`: a + (b - a) t, evaluated from the upper end, b - (b - a)(1 - t), when
/// t >= 0.5 (so t = 1 gives b exactly).
/// Where b - a overflows (a = -1e308, b = 1e308; numpy returns inf there) the same formula runs
/// on halves, exactly scaled back: the interpolant always lies in [a, b].
[[nodiscard]] inline double numpy_lerp(double a, double b, double t) {
  const double diff = b - a;
  if (!std::isfinite(diff) && std::isfinite(a) && std::isfinite(b)) {
    return 2.0 * numpy_lerp(a * 0.5, b * 0.5, t);
  }
  return t >= 0.5 ? b - mul_rounded(diff, 1.0 - t) : a + mul_rounded(diff, t);
}

/// The unsigned integer as wide as Scalar (float, double), for radix_key().
template <class Scalar>
using RadixKey = std::conditional_t<sizeof(Scalar) == 8, std::uint64_t, std::uint32_t>;

/// An order-preserving integer image of a float or double: x < y implies key(x) < key(y), and
/// x == y implies key(x) == key(y), so -0.0 and +0.0 share one key (sign + magnitude for x >= 0,
/// sign - magnitude for x < 0). Infinities keep their place at the ends; NaNs get keys beyond them
/// (no order statistic is defined with a NaN).
template <class Scalar>
[[nodiscard]] inline RadixKey<Scalar> radix_key(Scalar x) {
  using Key = RadixKey<Scalar>;
  static_assert(sizeof(Key) == sizeof(Scalar));
  constexpr int kTop = static_cast<int>(8 * sizeof(Key)) - 1;
  constexpr Key kSign = Key{1} << kTop;
  Key bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  const Key magnitude = bits & ~kSign;
  const Key negative = Key{0} - (bits >> kTop);  // all ones when the sign bit is set
  return static_cast<Key>(kSign + ((magnitude ^ negative) - negative));
}

/// Smallest and largest of m >= 1 values (no NaN), vectorised.
template <class Scalar>
[[nodiscard]] inline std::pair<Scalar, Scalar> min_max(const Scalar* values, std::size_t m) {
  const Eigen::Map<const Eigen::Array<Scalar, Eigen::Dynamic, 1>> a(values,
                                                                    static_cast<Eigen::Index>(m));
  return {a.minCoeff(), a.maxCoeff()};
}

/// Below this many values std::nth_element beats the radix selection (its histogram is a fixed
/// cost); docs/benchmarks.md has the crossover measurement.
inline constexpr std::size_t kRadixSelectMin = 16384;

/// Moves the values x of [src, src + m) with inside(x) to the front of `buffer` (room for m;
/// it may be src) and returns their count. No branch on inside(x): the kept values are a
/// random-looking subset, so a branch would mispredict. With `permute` (buffer == src) the values
/// are swapped, so that they stay a permutation; otherwise those not kept are overwritten.
/// inside() is called once per value, in order.
template <class Scalar, class Inside>
std::size_t gather_if(const Scalar* src, std::size_t m, Scalar* buffer, bool permute,
                      Inside inside) {
  std::size_t kept = 0;
  if (permute) {
    for (std::size_t j = 0; j < m; ++j) {
      const Scalar x = buffer[j];
      const bool in = inside(x);
      const Scalar y = buffer[kept];
      buffer[kept] = in ? x : y;
      buffer[j] = in ? y : x;
      kept += in ? std::size_t{1} : std::size_t{0};
    }
  } else {
    for (std::size_t j = 0; j < m; ++j) {
      const Scalar x = src[j];
      buffer[kept] = x;  // written always, kept only when inside
      kept += inside(x) ? std::size_t{1} : std::size_t{0};
    }
  }
  return kept;
}

/// The k-th and (k+1)-th smallest (0-based, k + 1 < m) of the m values at `values` (no NaN),
/// using `buffer` (room for `capacity` values; it may be `values` itself, with capacity m) as
/// scratch. With less room than m values, std::nullopt when the selection would need more (the
/// caller retries with room for m); never with room for m.
///
/// Either result is an element of the input, as std::nth_element would return it: equal values
/// are interchangeable, so the only freedom is the sign of a zero. When the order statistic is
/// zero and the input holds zeros of both signs, either zero may come back (as with
/// nth_element); otherwise the bits are the sorted array's.
///
/// `values` is left unchanged when `buffer` is another array, and only permuted when it is the
/// same array (callers may reuse the values).
///
/// Large inputs, in rounds that each keep a slice of the current set holding both ranks:
/// - First, a bracket from a sample: the two sample values some standard deviations of the
///   sample rank either side of rank k; one pass counts the values below the bracket and
///   gathers those inside it (a few percent). A bracket that misses the ranks (rare: an unlucky
///   sample or an adversarial order), or holds more values than the room, costs that pass.
/// - Then bucket rounds: 2^kBits buckets by a monotone map (equal values share a bucket), one
///   pass to count them, one to gather the bucket of rank k. The map is linear in the value,
///   (x - lo) * scale, while that splits the set well; when a round keeps more than a quarter of
///   its set (values spread over many orders of magnitude) or the range overflows, it becomes
///   the top bits of radix_key() above [lo, hi], which shrinks the key range 2^10-fold a round,
///   so the selection always ends. Without a bracket the first bucket round takes [lo, hi] from
///   the sample (values outside are clamped into the end buckets: still monotone), later rounds
///   the set's exact extremes.
/// When rank k is the last of its bucket, one pass reads the bucket's maximum and the smallest
/// value above it; a set of equal values ends the selection at once, so heavily tied data (HBOS
/// scores take few distinct values) are cheap. Small sets go to std::nth_element.
template <class Scalar>
std::optional<std::pair<Scalar, Scalar>> radix_select_adjacent(
    const Scalar* values, std::size_t m, std::size_t k, Scalar* buffer, std::size_t capacity,
    std::size_t small = kRadixSelectMin) {
  auto by_nth_element = [&](const Scalar* src, std::size_t size, std::size_t rank) {
    if (src != buffer) std::copy(src, src + size, buffer);
    const auto r = static_cast<std::ptrdiff_t>(rank);
    const auto end = static_cast<std::ptrdiff_t>(size);
    std::nth_element(buffer, buffer + r, buffer + end);
    return std::make_pair(buffer[rank], *std::min_element(buffer + r + 1, buffer + end));
  };
  if constexpr (!std::is_same_v<Scalar, float> && !std::is_same_v<Scalar, double>) {
    return by_nth_element(values, m, k);
  } else {
    using Key = RadixKey<Scalar>;
    constexpr int kBits = 11;
    constexpr std::size_t kBuckets = std::size_t{1} << kBits;
    // Four interleaved histograms: ties hit one counter back to back, and a single counter
    // would serialise on its own increments.
    constexpr std::size_t kLanes = 4;
    // Bucket indices are computed a block at a time (a loop the compiler vectorises), then
    // counted.
    constexpr std::size_t kBlock = 256;
    constexpr std::size_t kSample = 2048;
    constexpr Scalar kInf = std::numeric_limits<Scalar>::infinity();
    if (m < small || m < kSample || m / kLanes >= std::numeric_limits<std::uint32_t>::max()) {
      if (capacity < m) return std::nullopt;
      return by_nth_element(values, m, k);
    }
    const bool permute = values == buffer;
    const Scalar* src = values;

    // The sample: every (m / kSample)-th value.
    Scalar sample[kSample];
    const std::size_t stride = m / kSample;
    for (std::size_t s = 0; s < kSample; ++s) sample[s] = src[s * stride];
    auto sample_at = [&sample](std::size_t rank) {
      std::nth_element(sample, sample + rank, sample + kSample);
      return sample[rank];
    };
    Scalar lo_value = *std::min_element(sample, sample + kSample);
    Scalar hi_value = *std::max_element(sample, sample + kSample);
    bool exact = false;  // lo_value, hi_value are the current set's extremes
    {
      // The bracket: the sample rank of k, +-4 standard deviations of it (and some slack).
      const double p = static_cast<double>(k) / static_cast<double>(m);
      const double centre = p * static_cast<double>(kSample);
      const double margin = 4.0 * std::sqrt(static_cast<double>(kSample) * p * (1.0 - p)) + 8.0;
      const double below_rank = std::floor(centre - margin);
      const double above_rank = std::ceil(centre + margin);
      const Scalar low = below_rank < 0.0 ? -kInf : sample_at(static_cast<std::size_t>(below_rank));
      const Scalar high = above_rank >= static_cast<double>(kSample)
                              ? kInf
                              : sample_at(static_cast<std::size_t>(above_rank));
      // One pass counts the values below the bracket and gathers those inside it.
      std::size_t below = 0;
      auto count_and_test = [&below, low, high](Scalar x) {
        below += x < low ? std::size_t{1} : std::size_t{0};
        return static_cast<bool>(static_cast<int>(low <= x) & static_cast<int>(x <= high));
      };
      std::size_t kept = 0;
      if (permute) {
        kept = gather_if(src, m, buffer, true, count_and_test);
      } else {
        const std::size_t last = std::min(capacity, m) - 1;
        for (std::size_t j = 0; j < m; ++j) {
          const Scalar x = src[j];
          buffer[std::min(kept, last)] = x;  // written always, kept only when inside
          kept += count_and_test(x) ? std::size_t{1} : std::size_t{0};
        }
      }
      if (kept <= capacity && below <= k && k + 1 < below + kept) {
        src = buffer;
        m = kept;
        k -= below;
        std::tie(lo_value, hi_value) = min_max(src, m);
        exact = true;
      } else if (capacity < m) {
        // A miss, or more inside than the room (a large tie group at the percentile): the
        // caller retries with room for every value.
        return std::nullopt;
      }
    }

    bool linear = true;
    std::uint32_t count[kLanes][kBuckets];
    std::uint16_t index[kBlock];
    for (;; exact = true) {
      if (exact && !(lo_value < hi_value)) return std::make_pair(src[0], src[0]);  // all equal
      if (m < small) return by_nth_element(src, m, k);
      // The bucket of a value: clamped to [lo, hi] (a no-op but in the sampled round), then
      // mapped; both maps are monotone, so the buckets partition the set in order. Counting and
      // gathering evaluate the same expressions (a subtraction then a product: nothing to fuse),
      // so they agree on every value's bucket.
      const Scalar scale = static_cast<Scalar>(kBuckets - 1) / (hi_value - lo_value);
      linear = linear && std::isfinite(scale) && scale > 0;
      const Key lo = radix_key(lo_value);
      const Key hi = radix_key(hi_value);
      int shift = 0;
      while (((hi - lo) >> shift) >= kBuckets) ++shift;
      // Not constexpr: a copy the lambda captures (Clang calls capturing a constexpr unneeded,
      // GCC reads using it uncaptured as an odr-use).
      const auto last_position = static_cast<Scalar>(kBuckets - 1);
      // The linear map's position of x, clamped to [0, last_position] (x outside [lo, hi] only in
      // the sampled round; an overflow to infinity clamps too). Its integer part is the bucket.
      auto position = [lo_value, scale, last_position](Scalar x) {
        Scalar u = (x - lo_value) * scale;
        u = u > Scalar(0) ? u : Scalar(0);
        return u < last_position ? u : last_position;
      };
      auto key_bucket = [&](Scalar x) {
        x = x > lo_value ? x : lo_value;
        x = x < hi_value ? x : hi_value;
        return static_cast<std::int32_t>((radix_key(x) - lo) >> shift);
      };
      std::memset(count, 0, sizeof count);
      for (std::size_t j = 0; j < m; j += kBlock) {
        const std::size_t len = std::min(kBlock, m - j);
        const Scalar* block = src + j;
        if (linear) {
          for (std::size_t t = 0; t < len; ++t) {
            index[t] = static_cast<std::uint16_t>(static_cast<std::int32_t>(position(block[t])));
          }
        } else {
          for (std::size_t t = 0; t < len; ++t) {
            index[t] = static_cast<std::uint16_t>(key_bucket(block[t]));
          }
        }
        std::size_t t = 0;
        for (; t + kLanes <= len; t += kLanes) {
          for (std::size_t l = 0; l < kLanes; ++l) ++count[l][index[t + l]];
        }
        for (; t < len; ++t) ++count[0][index[t]];
      }
      std::size_t b = 0;
      std::size_t before = 0;
      std::size_t in_b = 0;
      for (;; ++b) {
        in_b = std::size_t{count[0][b]} + count[1][b] + count[2][b] + count[3][b];
        if (before + in_b > k) break;
        before += in_b;
      }
      k -= before;
      // Bucket b of the linear map is the raw position range [b_lo, b_hi) (open at the ends:
      // the clamped positions), so a test needs no clamp.
      const Scalar b_lo = b == 0 ? -kInf : static_cast<Scalar>(b);
      const Scalar b_hi = b == kBuckets - 1 ? kInf : static_cast<Scalar>(b + 1);
      auto raw = [lo_value, scale](Scalar x) { return (x - lo_value) * scale; };
      if (k + 1 == in_b) {
        // Rank k is the bucket's largest, rank k + 1 the smallest above the bucket.
        Scalar top = -kInf;
        Scalar next = kInf;
        auto scan = [&](auto above) {
          for (std::size_t j = 0; j < m; ++j) {
            const Scalar x = src[j];
            const bool up = above(x);
            top = up ? top : std::max(top, x);
            next = up ? std::min(next, x) : next;
          }
        };
        if (linear) {
          scan([&](Scalar x) { return raw(x) >= b_hi; });
        } else {
          scan([&](Scalar x) { return static_cast<std::size_t>(key_bucket(x)) > b; });
        }
        return std::make_pair(top, next);
      }
      // Keep bucket b only, gathered to the front of buffer.
      const std::size_t kept =
          linear ? gather_if(src, m, buffer, permute,
                             [&](Scalar x) {
                               const Scalar u = raw(x);
                               return static_cast<bool>(static_cast<int>(b_lo <= u) &
                                                        static_cast<int>(u < b_hi));
                             })
                 : gather_if(src, m, buffer, permute, [&](Scalar x) {
                     return static_cast<std::size_t>(key_bucket(x)) == b;
                   });
      linear = linear && kept <= m / 4;
      src = buffer;
      m = kept;
      std::tie(lo_value, hi_value) = min_max(src, m);
    }
  }
}

/// numpy.percentile(a, 100*q, method="linear") on `values` (reordered in place), bit-identical to
/// numpy: v = (n-1) q, i = floor(v), g = v - i, then numpy's `_lerp` of the i-th and (i+1)-th
/// smallest values (radix_select_adjacent(); its note on the sign of a zero applies).
template <class Scalar>
Scalar numpy_percentile_linear(Scalar* first, Scalar* last, double q) {
  const auto n = static_cast<std::size_t>(last - first);
  const double v = static_cast<double>(n - 1) * q;
  const auto i = static_cast<std::size_t>(std::floor(v));
  if (i + 1 >= n) return *std::max_element(first, last);
  const auto [lo, hi] = *radix_select_adjacent(first, n, i, first, n);
  const double g = v - static_cast<double>(i);
  return static_cast<Scalar>(numpy_lerp(static_cast<double>(lo), static_cast<double>(hi), g));
}

/// The same percentile of n values left unchanged, with `scratch` as the work area. It grows to
/// n values below kRadixSelectMin, else to about n / 8 (what the selection gathers), and to n
/// only when that is not enough (rare); it allocates nothing once it has grown.
template <class Scalar>
Scalar numpy_percentile_linear(const Scalar* values, std::size_t n, double q,
                               std::vector<Scalar>& scratch) {
  const double v = static_cast<double>(n - 1) * q;
  const auto i = static_cast<std::size_t>(std::floor(v));
  if (i + 1 >= n) return *std::max_element(values, values + n);
  const std::size_t room = n < kRadixSelectMin ? n : std::min(n, n / 8 + kRadixSelectMin);
  if (scratch.size() < room) scratch.resize(room);
  auto selected = radix_select_adjacent(values, n, i, scratch.data(), scratch.size());
  if (!selected) {
    scratch.resize(n);
    selected = radix_select_adjacent(values, n, i, scratch.data(), n);
  }
  const auto [lo, hi] = *selected;
  const double g = v - static_cast<double>(i);
  return static_cast<Scalar>(numpy_lerp(static_cast<double>(lo), static_cast<double>(hi), g));
}

/// Median of [first, last) (mean of the two middle values for an even count), reordering in place.
template <class Scalar>
Scalar median_inplace(Scalar* first, Scalar* last) {
  return numpy_percentile_linear(first, last, 0.5);
}

}  // namespace hbos::detail
