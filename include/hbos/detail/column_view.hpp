#pragma once
/// \file
/// A column as the kernels read it (a strided pointer) and the fused min/max/finiteness pass:
/// shared by edge placement (binning.hpp) and counting and scoring (histogram.hpp).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

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

/// One pass over `x` (at least one value): its min, its max and whether all values are finite.
template <class Scalar>
MinMax<Scalar> scan_min_max(const ColumnView<Scalar>& x) {
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
  return {lo, hi, check == Scalar(0)};
}

/// min and max of every column of a row-major block in one pass over its rows: `n` rows of `d`
/// values, row i at data + i * row_stride (>= d). Writes lo[j], hi[j]; returns whether every
/// value is finite (the caller then re-scans column by column to name the first one that is not).
template <class Scalar>
bool scan_rows_min_max(const Scalar* data, Eigen::Index n, Eigen::Index d, Eigen::Index row_stride,
                       Scalar* lo, Scalar* hi) {
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
  return check == Scalar(0);
}

/// min and max of a column in one pass, throwing on any NaN or infinity.
template <class Scalar>
std::pair<Scalar, Scalar> finite_min_max(const ColumnView<Scalar>& x, Eigen::Index feature) {
  const MinMax<Scalar> r = scan_min_max(x);
  if (!r.finite) throw_not_finite(x, feature);
  return {r.lo, r.hi};
}

}  // namespace hbos::detail
