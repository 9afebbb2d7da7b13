#pragma once
/// \file
/// Few equal-width bins, as one-byte indices: the bin computation and the counting of a fit with
/// up to 16 bins (the classic static HBOS job), where the scalar code spent most of its time.
///
/// Bins: (v - lo) * inv, capped at the last bin, truncated: with SSE2, 16 values at a time with
/// packed subtract, multiply, `minpd`/`minps` (a < b ? a : b, exactly the scalar cap) and a
/// truncating conversion, narrowed to bytes by saturating packs (exact, as indices are < 256).
/// Counting: 16 indices at a time are compared with each bin number (one compare and one
/// subtract per bin and 16 values, the per-lane counts summed with `psadbw`) instead of one
/// read-modify-write of a counter per value, which serialises when consecutive values fall in
/// the same bin. Without SSE2 both are plain loops. Every path gives the same bytes and counts.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#if defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)
#include <emmintrin.h>
#define HBOS_DETAIL_BYTE_BINS_SSE2 1
#endif

namespace hbos::detail {

#ifdef HBOS_DETAIL_BYTE_BINS_SSE2
/// Stores 16 bin indices, given as four vectors of four int32 (each below 256), as 16 bytes:
/// saturating packs to int16 and then to uint8, exact for such values.
inline void store_16_bins(__m128i q0, __m128i q1, __m128i q2, __m128i q3, std::uint8_t* b) {
  const __m128i lo8 = _mm_packs_epi32(q0, q1), hi8 = _mm_packs_epi32(q2, q3);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(b), _mm_packus_epi16(lo8, hi8));
}
#endif

/// b[i] = min(trunc((x[i] - lo) * inv), last) for the contiguous x[0, m), each x[i] >= lo, where
/// last is an integer below 256: the bin of uniform_bin (histogram.hpp), computed the same way.
template <class Scalar>
void uniform_byte_bins(const Scalar* x, std::size_t m, Scalar lo, Scalar inv, Scalar last,
                       std::uint8_t* b) {
  std::size_t i = 0;
#ifdef HBOS_DETAIL_BYTE_BINS_SSE2
  if constexpr (std::is_same_v<Scalar, double>) {
    const __m128d vlo = _mm_set1_pd(lo), vinv = _mm_set1_pd(inv), vlast = _mm_set1_pd(last);
    auto four = [&](const double* p) {  // four values as four int32
      const __m128d u0 = _mm_min_pd(_mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(p), vlo), vinv), vlast);
      const __m128d u1 = _mm_min_pd(_mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(p + 2), vlo), vinv), vlast);
      return _mm_unpacklo_epi64(_mm_cvttpd_epi32(u0), _mm_cvttpd_epi32(u1));
    };
    for (; m - i >= 16; i += 16)
      store_16_bins(four(x + i), four(x + i + 4), four(x + i + 8), four(x + i + 12), b + i);
  } else if constexpr (std::is_same_v<Scalar, float>) {
    const __m128 vlo = _mm_set1_ps(lo), vinv = _mm_set1_ps(inv), vlast = _mm_set1_ps(last);
    auto four = [&](const float* p) {
      return _mm_cvttps_epi32(
          _mm_min_ps(_mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(p), vlo), vinv), vlast));
    };
    for (; m - i >= 16; i += 16)
      store_16_bins(four(x + i), four(x + i + 4), four(x + i + 8), four(x + i + 12), b + i);
  }
#endif
  for (; i < m; ++i) {
    const Scalar u = (x[i] - lo) * inv;
    b[i] = static_cast<std::uint8_t>(static_cast<std::int32_t>(u < last ? u : last));
  }
}

/// Most bins the compare-and-count path takes: it costs k compares per 16 values, which beyond
/// about 16 bins is more than the scalar increments it replaces (docs/benchmarks.md).
inline constexpr std::size_t kCompareCountMaxBins = 16;

/// Adds to counts[b] the number of entries of `index[0, m)` equal to b, for every b < k, where
/// k <= kCompareCountMaxBins and every entry is below k.
inline void count_byte_indices(const std::uint8_t* index, std::size_t m, std::size_t k,
                               std::uint64_t* counts) {
  std::size_t i = 0;
#ifdef HBOS_DETAIL_BYTE_BINS_SSE2
  // At most 255 vectors per round, so no byte lane can overflow.
  constexpr std::size_t max_vectors = 255;
  const __m128i zero = _mm_setzero_si128();
  while (m - i >= 16) {
    const std::size_t vectors = std::min((m - i) / 16, max_vectors);
    const std::uint8_t* p = index + i;
    for (std::size_t b = 0; b < k; ++b) {
      const __m128i bin = _mm_set1_epi8(static_cast<char>(b));
      __m128i lanes = zero;
      for (std::size_t v = 0; v < vectors; ++v) {
        const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 16 * v));
        lanes = _mm_sub_epi8(lanes, _mm_cmpeq_epi8(x, bin));  // a match compares as -1
      }
      const __m128i sums = _mm_sad_epu8(lanes, zero);  // one sum per 8 lanes, in 64-bit halves
      counts[b] += static_cast<std::uint64_t>(_mm_cvtsi128_si32(sums)) +
                   static_cast<std::uint64_t>(_mm_cvtsi128_si32(_mm_unpackhi_epi64(sums, sums)));
    }
    i += 16 * vectors;
  }
#else
  // Four interleaved sub-histograms, so increments of one bin by consecutive values do not wait
  // on each other.
  std::uint32_t sub[4 * kCompareCountMaxBins] = {};
  for (; m - i >= 4; i += 4) {
    ++sub[4 * index[i]];
    ++sub[4 * index[i + 1] + 1];
    ++sub[4 * index[i + 2] + 2];
    ++sub[4 * index[i + 3] + 3];
  }
  for (std::size_t b = 0; b < k; ++b)
    counts[b] += std::uint64_t{sub[4 * b]} + sub[4 * b + 1] + sub[4 * b + 2] + sub[4 * b + 3];
#endif
  for (; i < m; ++i) ++counts[index[i]];
}

/// out[i] = table[index[i]] for i < m. With `stream_out`, doubles are written with non-temporal
/// stores (SSE2, `out` 16-byte aligned): for outputs far larger than the caches, which are then
/// not read back into the cache line by line before being overwritten.
template <class Scalar>
void lookup_byte_indices(const Scalar* table, const std::uint8_t* index, std::size_t m, Scalar* out,
                         bool stream_out) {
  std::size_t i = 0;
#ifdef HBOS_DETAIL_BYTE_BINS_SSE2
  if constexpr (std::is_same_v<Scalar, double>) {
    if (stream_out && reinterpret_cast<std::uintptr_t>(out) % 16 == 0) {
      for (; m - i >= 2; i += 2)
        _mm_stream_pd(out + i, _mm_set_pd(table[index[i + 1]], table[index[i]]));
    }
  }
#endif
  (void)stream_out;
  for (; i < m; ++i) out[i] = table[index[i]];
}

/// Orders the non-temporal stores of lookup_byte_indices before any later store (they are
/// weakly ordered): called once after the last of them.
inline void fence_streaming_stores() {
#ifdef HBOS_DETAIL_BYTE_BINS_SSE2
  _mm_sfence();
#endif
}

}  // namespace hbos::detail
