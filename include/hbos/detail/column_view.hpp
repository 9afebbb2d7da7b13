#pragma once
/// \file
/// A column as the kernels read it (a strided pointer) and the fused min/max/finiteness pass:
/// shared by edge placement (binning.hpp) and counting and scoring (histogram.hpp).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "hbos/detail/isa.hpp"
#include "hbos/error.hpp"

namespace hbos::detail {

/// A column as a strided pointer: what every kernel reads.
template <class Scalar>
struct ColumnView {
  const Scalar* data = nullptr;
  Eigen::Index size = 0;
  Eigen::Index stride = 1;
  [[nodiscard]] Scalar operator[](Eigen::Index i) const { return data[i * stride]; }
};

/// A view of `column`: in place when the expression has direct access (matrices, maps, blocks),
/// otherwise evaluated into `storage`.
template <class Scalar, class Column>
ColumnView<Scalar> view_of(const Column& column, std::vector<Scalar>& storage) {
  if constexpr ((Column::Flags & Eigen::DirectAccessBit) != 0) {
    return {column.data(), column.size(), column.innerStride()};
  } else {
    storage.resize(static_cast<std::size_t>(column.size()));
    for (Eigen::Index i = 0; i < column.size(); ++i)
      storage[static_cast<std::size_t>(i)] = column.coeff(i);
    return {storage.data(), column.size(), 1};
  }
}

/// Throws naming the first non-finite value of feature `feature`.
template <class Scalar>
[[noreturn]] void throw_not_finite(const ColumnView<Scalar>& x, Eigen::Index feature) {
  for (Eigen::Index i = 0; i < x.size; ++i)
    require(std::isfinite(x[i]), "X(", i, ", ", feature, ") is not finite (", x[i], ")");
  throw InvalidArgument(concat("feature ", feature, " has a non-finite value"));
}

/// Calls `body(value_at)` with an accessor specialised for contiguous columns, so the common
/// unit-stride case compiles to plain (vectorisable) pointer loops.
template <class Scalar, class Body>
void with_access(const ColumnView<Scalar>& x, Body&& body) {
  if (x.stride == 1) {
    const Scalar* p = x.data;
    body([p](Eigen::Index i) { return p[i]; });
  } else {
    const Scalar* p = x.data;
    const Eigen::Index stride = x.stride;
    body([p, stride](Eigen::Index i) { return p[i * stride]; });
  }
}

/// min and max of a column in one pass, and whether every value is finite.
template <class Scalar>
struct MinMax {
  Scalar lo, hi;
  bool finite;
};

#ifdef HBOS_DETAIL_ISA_DISPATCH
/// The AVX2 body of the packet loops of scan_min_max and scan_rows_min_max, where Eigen's packets
/// are 128-bit (L = 8 doubles or 16 floats per step, lane l holding elements e with e = l mod L):
/// for e = 0, L, 2 L, ... while e + L <= total, lane l takes min and max with p[e + l]. `lo` and
/// `hi` hold the L lanes' starting values and receive their results; `nan` is set when a NaN was
/// read. Returns the elements done. The lanes get the bits of the SSE2 loop: per lane that loop
/// keeps the earliest of equal values (v < acc ? v : acc, which matters only for -0.0 and +0.0),
/// and so does a pairwise min taken with the later value first, so two steps are folded into
/// each other before the accumulator, halving its chain of dependent operations.
template <class Vec, class Scalar, class Ops>
HBOS_DETAIL_TARGET_AVX2 std::size_t min_max_lanes_avx2_impl(const Scalar* p, std::size_t total,
                                                            Scalar* lo, Scalar* hi, bool& nan) {
  constexpr std::size_t w = sizeof(Vec) / sizeof(Scalar);  // lanes per vector
  constexpr std::size_t step = 2 * w;                      // L
  Vec lo0 = Ops::load(lo), lo1 = Ops::load(lo + w), hi0 = Ops::load(hi), hi1 = Ops::load(hi + w);
  Vec bad = Ops::zero();
  std::size_t e = 0;
  for (; e + 2 * step <= total; e += 2 * step) {
    const Vec a0 = Ops::load(p + e), a1 = Ops::load(p + e + w);
    const Vec b0 = Ops::load(p + e + step), b1 = Ops::load(p + e + step + w);
    lo0 = Ops::min(Ops::min(b0, a0), lo0);
    lo1 = Ops::min(Ops::min(b1, a1), lo1);
    hi0 = Ops::max(Ops::max(b0, a0), hi0);
    hi1 = Ops::max(Ops::max(b1, a1), hi1);
    bad = Ops::bit_or(bad, Ops::bit_or(Ops::unordered(a0, b0), Ops::unordered(a1, b1)));
  }
  if (e + step <= total) {
    const Vec a0 = Ops::load(p + e), a1 = Ops::load(p + e + w);
    lo0 = Ops::min(a0, lo0);
    lo1 = Ops::min(a1, lo1);
    hi0 = Ops::max(a0, hi0);
    hi1 = Ops::max(a1, hi1);
    bad = Ops::bit_or(bad, Ops::unordered(a0, a1));
    e += step;
  }
  Ops::store(lo, lo0);
  Ops::store(lo + w, lo1);
  Ops::store(hi, hi0);
  Ops::store(hi + w, hi1);
  nan = Ops::any(bad);
  return e;
}

/// The AVX2 operations min_max_lanes_avx2_impl needs, on doubles. min(a, b) and max(a, b) keep
/// b on ties, as minpd and maxpd do.
struct Avx2Doubles {
  HBOS_DETAIL_TARGET_AVX2 static __m256d load(const double* p) { return _mm256_loadu_pd(p); }
  HBOS_DETAIL_TARGET_AVX2 static void store(double* p, __m256d v) { _mm256_storeu_pd(p, v); }
  HBOS_DETAIL_TARGET_AVX2 static __m256d zero() { return _mm256_setzero_pd(); }
  HBOS_DETAIL_TARGET_AVX2 static __m256d min(__m256d a, __m256d b) { return _mm256_min_pd(a, b); }
  HBOS_DETAIL_TARGET_AVX2 static __m256d max(__m256d a, __m256d b) { return _mm256_max_pd(a, b); }
  HBOS_DETAIL_TARGET_AVX2 static __m256d unordered(__m256d a, __m256d b) {
    return _mm256_cmp_pd(a, b, _CMP_UNORD_Q);
  }
  HBOS_DETAIL_TARGET_AVX2 static __m256d bit_or(__m256d a, __m256d b) { return _mm256_or_pd(a, b); }
  HBOS_DETAIL_TARGET_AVX2 static bool any(__m256d v) { return _mm256_movemask_pd(v) != 0; }
};

/// The same on floats.
struct Avx2Floats {
  HBOS_DETAIL_TARGET_AVX2 static __m256 load(const float* p) { return _mm256_loadu_ps(p); }
  HBOS_DETAIL_TARGET_AVX2 static void store(float* p, __m256 v) { _mm256_storeu_ps(p, v); }
  HBOS_DETAIL_TARGET_AVX2 static __m256 zero() { return _mm256_setzero_ps(); }
  HBOS_DETAIL_TARGET_AVX2 static __m256 min(__m256 a, __m256 b) { return _mm256_min_ps(a, b); }
  HBOS_DETAIL_TARGET_AVX2 static __m256 max(__m256 a, __m256 b) { return _mm256_max_ps(a, b); }
  HBOS_DETAIL_TARGET_AVX2 static __m256 unordered(__m256 a, __m256 b) {
    return _mm256_cmp_ps(a, b, _CMP_UNORD_Q);
  }
  HBOS_DETAIL_TARGET_AVX2 static __m256 bit_or(__m256 a, __m256 b) { return _mm256_or_ps(a, b); }
  HBOS_DETAIL_TARGET_AVX2 static bool any(__m256 v) { return _mm256_movemask_ps(v) != 0; }
};

HBOS_DETAIL_TARGET_AVX2 inline std::size_t min_max_lanes_avx2(const double* p, std::size_t total,
                                                              double* lo, double* hi, bool& nan) {
  return min_max_lanes_avx2_impl<__m256d, double, Avx2Doubles>(p, total, lo, hi, nan);
}
HBOS_DETAIL_TARGET_AVX2 inline std::size_t min_max_lanes_avx2(const float* p, std::size_t total,
                                                              float* lo, float* hi, bool& nan) {
  return min_max_lanes_avx2_impl<__m256, float, Avx2Floats>(p, total, lo, hi, nan);
}
#endif

/// Whether the packet loops of scan_min_max and scan_rows_min_max may take
/// min_max_lanes_avx2 under `isa`: only where Eigen's packets are 128-bit (its lane layout).
template <class Scalar>
[[nodiscard]] bool min_max_by_avx2(Isa isa) {
#ifdef HBOS_DETAIL_ISA_DISPATCH
  using Packet = typename Eigen::internal::packet_traits<Scalar>::type;
  return isa == Isa::Avx2 && Eigen::internal::packet_traits<Scalar>::size > 1 &&
         sizeof(Packet) == 16;
#else
  (void)isa;
  return false;
#endif
}

/// One pass over `x` (at least one value): its min, its max and whether all values are finite.
template <class Scalar>
MinMax<Scalar> scan_min_max(const ColumnView<Scalar>& x, Isa isa = active_isa()) {
  (void)isa;  // unused without HBOS_DETAIL_ISA_DISPATCH
  // v * 0 is 0 for finite v and NaN otherwise, so one accumulated sum checks finiteness in the
  // same pass. GCC does not vectorise min/max reductions on its own; on contiguous data Eigen's
  // packet primitives do it explicitly (SSE2 and up). Four packets per step, each with its own
  // min and max accumulator: with fewer, the loop waits on the latency of the min/max chains
  // (measured: 2x slower than a streaming sum at 1e6 rows) instead of on memory.
  Scalar lo = x[0], hi = x[0], check = 0;
  Eigen::Index i = 0;
  if (x.stride == 1) {
    using Packet = typename Eigen::internal::packet_traits<Scalar>::type;
    constexpr Eigen::Index P = Eigen::internal::packet_traits<Scalar>::size;
    if constexpr (P > 1) {
      namespace in = Eigen::internal;
      const Scalar* p = x.data;
      Packet lo0 = in::pset1<Packet>(lo), lo1 = lo0, lo2 = lo0, lo3 = lo0;
      Packet hi0 = lo0, hi1 = lo0, hi2 = lo0, hi3 = lo0;
      const Packet zero = in::pset1<Packet>(Scalar(0));
      Packet c0 = zero, c1 = zero;
#ifdef HBOS_DETAIL_ISA_DISPATCH
      if (min_max_by_avx2<Scalar>(isa)) {
        // The same lanes (and bits), from the AVX2 body; a NaN is marked in c0, an infinity
        // shows in the extremes (checked below).
        std::array<Scalar, static_cast<std::size_t>(4 * P)> lanes_lo{}, lanes_hi{};
        lanes_lo.fill(lo);
        lanes_hi.fill(lo);
        bool nan = false;
        i = static_cast<Eigen::Index>(min_max_lanes_avx2(p, static_cast<std::size_t>(x.size),
                                                         lanes_lo.data(), lanes_hi.data(), nan));
        lo0 = in::ploadu<Packet>(lanes_lo.data());
        lo1 = in::ploadu<Packet>(lanes_lo.data() + P);
        lo2 = in::ploadu<Packet>(lanes_lo.data() + 2 * P);
        lo3 = in::ploadu<Packet>(lanes_lo.data() + 3 * P);
        hi0 = in::ploadu<Packet>(lanes_hi.data());
        hi1 = in::ploadu<Packet>(lanes_hi.data() + P);
        hi2 = in::ploadu<Packet>(lanes_hi.data() + 2 * P);
        hi3 = in::ploadu<Packet>(lanes_hi.data() + 3 * P);
        if (nan) c0 = in::pset1<Packet>(std::numeric_limits<Scalar>::quiet_NaN());
      }
#endif
      for (; i + 4 * P <= x.size; i += 4 * P) {
        const Packet a = in::ploadu<Packet>(p + i);
        const Packet b = in::ploadu<Packet>(p + i + P);
        const Packet c = in::ploadu<Packet>(p + i + 2 * P);
        const Packet d = in::ploadu<Packet>(p + i + 3 * P);
        lo0 = in::pmin(lo0, a);
        lo1 = in::pmin(lo1, b);
        lo2 = in::pmin(lo2, c);
        lo3 = in::pmin(lo3, d);
        hi0 = in::pmax(hi0, a);
        hi1 = in::pmax(hi1, b);
        hi2 = in::pmax(hi2, c);
        hi3 = in::pmax(hi3, d);
        c0 = in::padd(c0, in::padd(in::pmul(a, zero), in::pmul(b, zero)));
        c1 = in::padd(c1, in::padd(in::pmul(c, zero), in::pmul(d, zero)));
      }
      lo = in::predux_min(in::pmin(in::pmin(lo0, lo1), in::pmin(lo2, lo3)));
      hi = in::predux_max(in::pmax(in::pmax(hi0, hi1), in::pmax(hi2, hi3)));
      check = in::predux(in::padd(c0, c1));
    }
  }
  if (x.stride != 1) {
    // Strided (a row-major matrix's column, numpy's default layout): no packets, but four
    // independent min/max chains, for the same reason as above.
    const Scalar* p = x.data;
    const Eigen::Index s = x.stride;
    Scalar lo1 = lo, lo2 = lo, lo3 = lo, hi1 = hi, hi2 = hi, hi3 = hi, c1 = 0;
    for (; i + 4 <= x.size; i += 4) {
      const Scalar a = p[i * s], b = p[(i + 1) * s], c = p[(i + 2) * s], d = p[(i + 3) * s];
      lo = a < lo ? a : lo;
      lo1 = b < lo1 ? b : lo1;
      lo2 = c < lo2 ? c : lo2;
      lo3 = d < lo3 ? d : lo3;
      hi = a > hi ? a : hi;
      hi1 = b > hi1 ? b : hi1;
      hi2 = c > hi2 ? c : hi2;
      hi3 = d > hi3 ? d : hi3;
      check += a * Scalar(0) + b * Scalar(0);
      c1 += c * Scalar(0) + d * Scalar(0);
    }
    lo = std::min(std::min(lo, lo1), std::min(lo2, lo3));
    hi = std::max(std::max(hi, hi1), std::max(hi2, hi3));
    check += c1;
  }
  for (; i < x.size; ++i) {
    const Scalar v = x[i];
    lo = v < lo ? v : lo;
    hi = v > hi ? v : hi;
    check += v * Scalar(0);
  }
  // An infinity among finite values is the min or the max (the AVX2 packet loop checks only for
  // NaN).
  return {lo, hi, check == Scalar(0) && std::isfinite(lo) && std::isfinite(hi)};
}

/// min and max of every column of a row-major block in one pass over its rows: `n` rows of `d`
/// values, row i at data + i * row_stride (>= d). Writes lo[j], hi[j]; returns whether every
/// value is finite (the caller then re-scans column by column to name the first one that is not).
template <class Scalar>
bool scan_rows_min_max(const Scalar* data, Eigen::Index n, Eigen::Index d, Eigen::Index row_stride,
                       Scalar* lo, Scalar* hi, Isa isa = active_isa()) {
  (void)isa;  // unused without HBOS_DETAIL_ISA_DISPATCH
  for (Eigen::Index j = 0; j < d; ++j) lo[j] = hi[j] = data[j];
  Scalar check = 0;
  Eigen::Index i = 0;
  using Packet = typename Eigen::internal::packet_traits<Scalar>::type;
  constexpr Eigen::Index P = Eigen::internal::packet_traits<Scalar>::size;
  if constexpr (P > 1) {
    // Contiguous rows are one flat array; when d divides the step of 4 packets, lane k of the
    // step always holds column k mod d, so the flat packet scan of scan_min_max gives every
    // column's extremes at once (d = 2: lanes alternate between the two columns).
    if (row_stride == d && (4 * P) % d == 0 && n * d >= 4 * P) {
      namespace in = Eigen::internal;
      const Eigen::Index total = n * d;
      Packet lo_p[4], hi_p[4];
      for (int q = 0; q < 4; ++q) lo_p[q] = hi_p[q] = in::ploadu<Packet>(data + q * P);
      const Packet zero = in::pset1<Packet>(Scalar(0));
      Packet c0 = zero, c1 = zero;
      Eigen::Index e = 0;
#ifdef HBOS_DETAIL_ISA_DISPATCH
      if (min_max_by_avx2<Scalar>(isa)) {
        // The same lanes (and bits) from the AVX2 body, as in scan_min_max.
        std::array<Scalar, static_cast<std::size_t>(4 * P)> start_lo{}, start_hi{};
        for (int q = 0; q < 4; ++q) {
          in::pstoreu(start_lo.data() + q * P, lo_p[q]);
          in::pstoreu(start_hi.data() + q * P, hi_p[q]);
        }
        bool nan = false;
        e = static_cast<Eigen::Index>(min_max_lanes_avx2(data, static_cast<std::size_t>(total),
                                                         start_lo.data(), start_hi.data(), nan));
        for (int q = 0; q < 4; ++q) {
          lo_p[q] = in::ploadu<Packet>(start_lo.data() + q * P);
          hi_p[q] = in::ploadu<Packet>(start_hi.data() + q * P);
        }
        if (nan) c0 = in::pset1<Packet>(std::numeric_limits<Scalar>::quiet_NaN());
      }
#endif
      for (; e + 4 * P <= total; e += 4 * P) {
        const Packet a = in::ploadu<Packet>(data + e);
        const Packet b = in::ploadu<Packet>(data + e + P);
        const Packet c = in::ploadu<Packet>(data + e + 2 * P);
        const Packet dd = in::ploadu<Packet>(data + e + 3 * P);
        lo_p[0] = in::pmin(lo_p[0], a);
        lo_p[1] = in::pmin(lo_p[1], b);
        lo_p[2] = in::pmin(lo_p[2], c);
        lo_p[3] = in::pmin(lo_p[3], dd);
        hi_p[0] = in::pmax(hi_p[0], a);
        hi_p[1] = in::pmax(hi_p[1], b);
        hi_p[2] = in::pmax(hi_p[2], c);
        hi_p[3] = in::pmax(hi_p[3], dd);
        c0 = in::padd(c0, in::padd(in::pmul(a, zero), in::pmul(b, zero)));
        c1 = in::padd(c1, in::padd(in::pmul(c, zero), in::pmul(dd, zero)));
      }
      std::array<Scalar, static_cast<std::size_t>(4 * P)> lanes_lo{}, lanes_hi{};
      for (int q = 0; q < 4; ++q) {
        in::pstoreu(lanes_lo.data() + q * P, lo_p[q]);
        in::pstoreu(lanes_hi.data() + q * P, hi_p[q]);
      }
      for (Eigen::Index k = 0; k < 4 * P; ++k) {
        const Eigen::Index j = k % d;
        lo[j] = lanes_lo[static_cast<std::size_t>(k)] < lo[j]
                    ? lanes_lo[static_cast<std::size_t>(k)]
                    : lo[j];
        hi[j] = lanes_hi[static_cast<std::size_t>(k)] > hi[j]
                    ? lanes_hi[static_cast<std::size_t>(k)]
                    : hi[j];
      }
      check = in::predux(in::padd(c0, c1));
      i = e / d;  // e is a whole number of rows: 4P is a multiple of d
    }
  }
  for (; i < n; ++i) {
    const Scalar* row = data + i * row_stride;
    for (Eigen::Index j = 0; j < d; ++j) {
      const Scalar v = row[j];
      lo[j] = v < lo[j] ? v : lo[j];
      hi[j] = v > hi[j] ? v : hi[j];
      check += v * Scalar(0);
    }
  }
  // An infinity among finite values is a min or a max (the AVX2 packet loop checks only for NaN).
  bool finite = check == Scalar(0);
  for (Eigen::Index j = 0; j < d && finite; ++j)
    finite = std::isfinite(lo[j]) && std::isfinite(hi[j]);
  return finite;
}

/// min and max of a column in one pass, throwing on any NaN or infinity.
template <class Scalar>
std::pair<Scalar, Scalar> finite_min_max(const ColumnView<Scalar>& x, Eigen::Index feature) {
  const MinMax<Scalar> r = scan_min_max(x);
  if (!r.finite) throw_not_finite(x, feature);
  return {r.lo, r.hi};
}

}  // namespace hbos::detail
