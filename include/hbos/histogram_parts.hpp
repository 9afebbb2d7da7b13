#pragma once
/// \file
/// What a fitted histogram is made of: its bins and counts, before the per-bin contributions are
/// derived from them. Model files (hbos/model_file.hpp) store these parts and merged fits
/// (hbos/merge.hpp) add their counts; `Histogram::from_parts` rebuilds the fitted histogram,
/// deriving every contribution with the very code `fit` uses, so the result scores bit for bit
/// like the histogram the parts came from.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "hbos/binning.hpp"
#include "hbos/error.hpp"

namespace hbos {

/// The state of one fitted histogram that scoring cannot derive (see the file comment).
///
/// Invariant (checked by detail::validate_parts): bins = counts.size() >= 1, edges.size() =
/// bins + 1, every number finite, edges non-decreasing from edges.front() = lo to edges.back() =
/// hi, counts >= 0; uniform bins have inv_width > 0 unless the feature is constant (lo = hi, one
/// bin, inv_width = 0) and no value of the range maps past the last bin; periodic parts are
/// uniform with a period > 0.
template <class Scalar>
struct HistogramParts {
  std::vector<Scalar> edges;         ///< [feature units] bins + 1 ascending edges
  std::vector<Eigen::Index> counts;  ///< training samples counted in each bin, >= 0
  Scalar lo = 0;                     ///< [feature units] the fitted range's lower end
  Scalar hi = 0;                     ///< [feature units] its upper end
  Scalar inv_width =
      0;  ///< [1/feature units] uniform bins: 1 / bin width (0: constant or not uniform)
  Scalar period = 0;  ///< [feature units] periodic features only, else 0
  /// Uniform bins of extreme columns are cut at (x * scale - base) * inv_width (EdgeLayout): a
  /// power of two, 1 on every ordinary column.
  Scalar scale = 1;
  Scalar base = 0;          ///< [scaled feature units] lo * scale where scale != 1
  Eigen::Index shifts = 1;  ///< averaged shifted histograms: fine bins per coarse bin, >= 1
  Tail tail = Tail::Both;   ///< the tail rule
  bool periodic = false;    ///< values wrap modulo `period`
  bool uniform = true;      ///< equal-width bins (looked up by arithmetic, not by search)
  /// [scaled feature units] uniform bins: the fine width the edges were placed with
  /// (detail::fill_uniform_edges), so a model file can store it instead of the edges; 0 when
  /// unknown (parts read from a version 1 file) or not uniform. Not used by scoring.
  Scalar fine = 0;
};

namespace detail {

/// Checks the invariant of HistogramParts; messages name `where` and the field.
/// \throws InvalidArgument naming the first violated condition.
template <class Scalar>
void validate_parts(const HistogramParts<Scalar>& p, const std::string& where) {
  const std::size_t k = p.counts.size();
  require(k >= 1, where, ": counts is empty (a histogram has at least one bin)");
  require(p.edges.size() == k + 1, where, ": edges has ", p.edges.size(), " values for ", k,
          " bins (needs ", k + 1, ")");
  require(std::isfinite(p.lo) && std::isfinite(p.hi) && p.lo <= p.hi, where,
          ": the range [lo, hi] = [", p.lo, ", ", p.hi, "] is not a finite interval");
  require(std::isfinite(p.inv_width) && p.inv_width >= Scalar(0), where,
          ": inv_width must be finite and >= 0, got ", p.inv_width);
  require(p.shifts >= 1, where, ": shifts must be >= 1, got ", p.shifts);
  require(std::isfinite(p.fine) && p.fine >= Scalar(0) && (p.uniform || p.fine == Scalar(0)), where,
          ": fine must be finite, >= 0 and 0 for irregular bins, got ", p.fine);
  require(std::isfinite(p.scale) && p.scale > Scalar(0) && std::isfinite(p.base), where,
          ": scale must be finite and > 0 and base finite, got ", p.scale, " and ", p.base);
  for (std::size_t i = 0; i < p.edges.size(); ++i) {
    require(std::isfinite(p.edges[i]), where, ": edges[", i, "] is not finite (", p.edges[i], ")");
    // (the message's arguments are evaluated eagerly: edges[i - 1] only exists from i = 1)
    if (i > 0)
      require(p.edges[i - 1] <= p.edges[i], where, ": edges are not ascending: edges[", i - 1,
              "] = ", p.edges[i - 1], " > edges[", i, "] = ", p.edges[i]);
  }
  require(p.edges.front() == p.lo && p.edges.back() == p.hi, where, ": edges run from ",
          p.edges.front(), " to ", p.edges.back(), " but the range is [", p.lo, ", ", p.hi, "]");
  for (std::size_t i = 0; i < k; ++i)
    require(p.counts[i] >= 0, where, ": counts[", i, "] is negative (", p.counts[i], ")");
  if (p.periodic) {
    require(p.uniform, where, ": a periodic histogram has uniform bins");
    require(p.tail == Tail::Both, where, ": a periodic histogram has no upper or lower tail");
    require(std::isfinite(p.period) && p.period > Scalar(0) && p.hi > p.lo, where, ": period ",
            p.period, " or the range [", p.lo, ", ", p.hi, "] is not a positive span");
  } else {
    require(p.period == Scalar(0), where, ": a non-periodic histogram has period 0, got ",
            p.period);
  }
  if (!p.uniform) {
    require(p.inv_width == Scalar(0), where, ": irregular bins have inv_width 0, got ",
            p.inv_width);
    require(p.shifts == 1, where, ": irregular bins have shifts 1, got ", p.shifts);
    return;
  }
  // In scaled units (a range of -1e308 to 1e308 overflows unscaled), in double.
  const double scale = static_cast<double>(p.scale);
  const double span = p.periodic
                          ? static_cast<double>(p.period) * scale
                          : static_cast<double>(p.hi) * scale - static_cast<double>(p.lo) * scale;
  if (!(span > 0.0)) {
    require(k == 1 && p.inv_width == Scalar(0), where,
            ": a constant feature has one bin and inv_width 0, got ", k, " bins and inv_width ",
            p.inv_width);
    return;
  }
  // Lookup truncates offset * inv_width (to int32 on the fast path) and caps it at the last bin:
  // a damaged inv_width must not overflow the truncation. The span is k widths up to rounding of
  // the edges (fixed-width edges in float may be off by a fraction of a bin), hence the slack.
  const double reach = span * static_cast<double>(p.inv_width);
  require(p.inv_width > Scalar(0) && reach <= 2.0 * static_cast<double>(k) + 2.0, where,
          ": inv_width ", p.inv_width, " does not match ", k, " bins over a (scaled) span of ",
          span);
  require(k % static_cast<std::size_t>(p.shifts) == 0, where, ": ", k,
          " fine bins are not a multiple of shifts = ", p.shifts);
}

}  // namespace detail
}  // namespace hbos
