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
/// the same bin. Without SSE2 both are plain loops. With run-time dispatch (detail/isa.hpp) each
/// kernel also has an AVX2 body, taken on CPUs that have it. Every path gives the same bytes and
/// counts.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#if defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)
#include <emmintrin.h>
#define HBOS_DETAIL_BYTE_BINS_SSE2 1
#endif

#include "hbos/detail/isa.hpp"

namespace hbos::detail {

#ifdef HBOS_DETAIL_BYTE_BINS_SSE2
/// Stores 16 bin indices, given as four vectors of four int32 (each below 256), as 16 bytes:
/// saturating packs to int16 and then to uint8, exact for such values.
inline void store_16_bins(__m128i q0, __m128i q1, __m128i q2, __m128i q3, std::uint8_t* b) {
  const __m128i lo8 = _mm_packs_epi32(q0, q1), hi8 = _mm_packs_epi32(q2, q3);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(b), _mm_packus_epi16(lo8, hi8));
}
#endif

#if defined(HBOS_DETAIL_ISA_DISPATCH) && defined(HBOS_DETAIL_BYTE_BINS_SSE2)
// The AVX2 bodies of the kernels below: four doubles or eight floats per vector, with the very
// subtract, multiply, min (a < b ? a : b) and truncation per value, so the same bytes; no FMA
// is enabled, so nothing can be contracted. Each returns the values it did (a multiple of 16).

/// Four doubles' bins (x - lo) * inv capped at last, as four int32.
HBOS_DETAIL_TARGET_AVX2 inline __m128i four_bins_avx2(const double* p, __m256d lo, __m256d inv,
                                                      __m256d last) {
  return _mm256_cvttpd_epi32(
      _mm256_min_pd(_mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(p), lo), inv), last));
}

/// Eight floats' bins as eight int32.
HBOS_DETAIL_TARGET_AVX2 inline __m256i eight_bins_avx2(const float* p, __m256 lo, __m256 inv,
                                                       __m256 last) {
  return _mm256_cvttps_epi32(
      _mm256_min_ps(_mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(p), lo), inv), last));
}

HBOS_DETAIL_TARGET_AVX2 inline std::size_t uniform_byte_bins_avx2(const double* x, std::size_t m,
                                                                  double lo, double inv,
                                                                  double last, std::uint8_t* b) {
  const __m256d vlo = _mm256_set1_pd(lo), vinv = _mm256_set1_pd(inv), vlast = _mm256_set1_pd(last);
  std::size_t i = 0;
  for (; m - i >= 16; i += 16) {
    const __m128i q0 = four_bins_avx2(x + i, vlo, vinv, vlast);
    const __m128i q1 = four_bins_avx2(x + i + 4, vlo, vinv, vlast);
    const __m128i q2 = four_bins_avx2(x + i + 8, vlo, vinv, vlast);
    const __m128i q3 = four_bins_avx2(x + i + 12, vlo, vinv, vlast);
    store_16_bins(q0, q1, q2, q3, b + i);
  }
  return i;
}

HBOS_DETAIL_TARGET_AVX2 inline std::size_t uniform_byte_bins_avx2(const float* x, std::size_t m,
                                                                  float lo, float inv, float last,
                                                                  std::uint8_t* b) {
  const __m256 vlo = _mm256_set1_ps(lo), vinv = _mm256_set1_ps(inv), vlast = _mm256_set1_ps(last);
  std::size_t i = 0;
  for (; m - i >= 16; i += 16) {
    const __m256i q0 = eight_bins_avx2(x + i, vlo, vinv, vlast);
    const __m256i q1 = eight_bins_avx2(x + i + 8, vlo, vinv, vlast);
    store_16_bins(_mm256_castsi256_si128(q0), _mm256_extracti128_si256(q0, 1),
                  _mm256_castsi256_si128(q1), _mm256_extracti128_si256(q1, 1), b + i);
  }
  return i;
}
#endif

/// b[i] = min(trunc((x[i] - lo) * inv), last) for the contiguous x[0, m), each x[i] >= lo, where
/// last is an integer below 256: the bin of uniform_bin (histogram.hpp), computed the same way.
template <class Scalar>
void uniform_byte_bins(const Scalar* x, std::size_t m, Scalar lo, Scalar inv, Scalar last,
                       std::uint8_t* b, Isa isa = active_isa()) {
  std::size_t i = 0;
#if defined(HBOS_DETAIL_ISA_DISPATCH) && defined(HBOS_DETAIL_BYTE_BINS_SSE2)
  if (isa == Isa::Avx2) i = uniform_byte_bins_avx2(x, m, lo, inv, last, b);
#endif
  (void)isa;
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

/// The constants of one feature's one-byte bins: b = trunc(min((v - lo) * inv, last)).
template <class Scalar>
struct ByteBinConstants {
  Scalar lo = 0, inv = 0, last = 0;
};

#ifdef HBOS_DETAIL_BYTE_BINS_SSE2
/// Sixteen rows at a time of two interleaved features: `four(p, first, second)` gives the int32
/// bins of the four rows at p (eight values) per feature; they are stored as bytes in b0 and b1.
/// Returns the rows done (a multiple of 16).
template <class Scalar, class Four>
std::size_t interleaved_sixteens(const Scalar* x, std::size_t m, const Four& four, std::uint8_t* b0,
                                 std::uint8_t* b1) {
  std::size_t r = 0;
  for (; m - r >= 16; r += 16) {
    const Scalar* p = x + 2 * r;
    __m128i a0, a1, a2, a3, s0, s1, s2, s3;
    four(p, a0, s0);
    four(p + 8, a1, s1);
    four(p + 16, a2, s2);
    four(p + 24, a3, s3);
    store_16_bins(a0, a1, a2, a3, b0 + r);
    store_16_bins(s0, s1, s2, s3, b1 + r);
  }
  return r;
}
#endif

#if defined(HBOS_DETAIL_ISA_DISPATCH) && defined(HBOS_DETAIL_BYTE_BINS_SSE2)
/// Four rows of two interleaved doubles from p: feature 0's bins in `first`, feature 1's in
/// `second` (the constants alternate between the features lane by lane).
HBOS_DETAIL_TARGET_AVX2 inline void four_rows_avx2(const double* p, __m256d lo, __m256d inv,
                                                   __m256d last, __m128i& first, __m128i& second) {
  const __m128 r01 = _mm_castsi128_ps(four_bins_avx2(p, lo, inv, last));      // a0 b0 a1 b1
  const __m128 r23 = _mm_castsi128_ps(four_bins_avx2(p + 4, lo, inv, last));  // a2 b2 a3 b3
  first = _mm_castps_si128(_mm_shuffle_ps(r01, r23, _MM_SHUFFLE(2, 0, 2, 0)));
  second = _mm_castps_si128(_mm_shuffle_ps(r01, r23, _MM_SHUFFLE(3, 1, 3, 1)));
}

/// The same for floats: eight values, four rows, parted by a lane permutation.
HBOS_DETAIL_TARGET_AVX2 inline void four_rows_avx2(const float* p, __m256 lo, __m256 inv,
                                                   __m256 last, __m128i& first, __m128i& second) {
  const __m256i parted = _mm256_permutevar8x32_epi32(eight_bins_avx2(p, lo, inv, last),
                                                     _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7));
  first = _mm256_castsi256_si128(parted);
  second = _mm256_extracti128_si256(parted, 1);
}

template <class Scalar, class Vec>
HBOS_DETAIL_TARGET_AVX2 std::size_t interleaved_sixteens_avx2(const Scalar* x, std::size_t m,
                                                              Vec lo, Vec inv, Vec last,
                                                              std::uint8_t* b0, std::uint8_t* b1) {
  std::size_t r = 0;
  for (; m - r >= 16; r += 16) {
    const Scalar* p = x + 2 * r;
    __m128i a0, a1, a2, a3, s0, s1, s2, s3;
    four_rows_avx2(p, lo, inv, last, a0, s0);
    four_rows_avx2(p + 8, lo, inv, last, a1, s1);
    four_rows_avx2(p + 16, lo, inv, last, a2, s2);
    four_rows_avx2(p + 24, lo, inv, last, a3, s3);
    store_16_bins(a0, a1, a2, a3, b0 + r);
    store_16_bins(s0, s1, s2, s3, b1 + r);
  }
  return r;
}

HBOS_DETAIL_TARGET_AVX2 inline std::size_t interleaved_byte_bins_2_avx2(
    const double* x, std::size_t m, const ByteBinConstants<double>& c0,
    const ByteBinConstants<double>& c1, std::uint8_t* b0, std::uint8_t* b1) {
  return interleaved_sixteens_avx2(x, m, _mm256_setr_pd(c0.lo, c1.lo, c0.lo, c1.lo),
                                   _mm256_setr_pd(c0.inv, c1.inv, c0.inv, c1.inv),
                                   _mm256_setr_pd(c0.last, c1.last, c0.last, c1.last), b0, b1);
}

HBOS_DETAIL_TARGET_AVX2 inline std::size_t interleaved_byte_bins_2_avx2(
    const float* x, std::size_t m, const ByteBinConstants<float>& c0,
    const ByteBinConstants<float>& c1, std::uint8_t* b0, std::uint8_t* b1) {
  return interleaved_sixteens_avx2(
      x, m, _mm256_setr_ps(c0.lo, c1.lo, c0.lo, c1.lo, c0.lo, c1.lo, c0.lo, c1.lo),
      _mm256_setr_ps(c0.inv, c1.inv, c0.inv, c1.inv, c0.inv, c1.inv, c0.inv, c1.inv),
      _mm256_setr_ps(c0.last, c1.last, c0.last, c1.last, c0.last, c1.last, c0.last, c1.last), b0,
      b1);
}
#endif

/// The bins of uniform_byte_bins for two features stored row by row, as a row-major matrix with
/// two columns (numpy's C order) stores them: for r < m, x[2 r] is feature 0's value and
/// x[2 r + 1] feature 1's; b0[r] and b1[r] get their bins. Each value takes the same arithmetic
/// as in uniform_byte_bins, so the bytes are the same; the two features are parted only as int32
/// bins, in registers, instead of gathering each strided column into a buffer first.
template <class Scalar>
void interleaved_byte_bins_2(const Scalar* x, std::size_t m, const ByteBinConstants<Scalar>& c0,
                             const ByteBinConstants<Scalar>& c1, std::uint8_t* b0, std::uint8_t* b1,
                             Isa isa = active_isa()) {
  std::size_t r = 0;
#if defined(HBOS_DETAIL_ISA_DISPATCH) && defined(HBOS_DETAIL_BYTE_BINS_SSE2)
  if (isa == Isa::Avx2) r = interleaved_byte_bins_2_avx2(x, m, c0, c1, b0, b1);
#endif
  (void)isa;
#ifdef HBOS_DETAIL_BYTE_BINS_SSE2
  // r > 0: the AVX2 body did every whole group of 16 rows already.
  if (r == 0) {
    if constexpr (std::is_same_v<Scalar, double>) {
      // One row per vector: lane 0 is feature 0, lane 1 feature 1.
      const __m128d vlo = _mm_set_pd(c1.lo, c0.lo), vinv = _mm_set_pd(c1.inv, c0.inv),
                    vlast = _mm_set_pd(c1.last, c0.last);
      auto row = [&](const double* p) {  // {bin 0, bin 1, 0, 0} as int32
        return _mm_cvttpd_epi32(
            _mm_min_pd(_mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(p), vlo), vinv), vlast));
      };
      // Four rows from p: feature 0's four bins in `first`, feature 1's in `second`.
      auto four = [&](const double* p, __m128i& first, __m128i& second) {
        const __m128i r01 = _mm_unpacklo_epi32(row(p), row(p + 2));      // a0 a1 b0 b1
        const __m128i r23 = _mm_unpacklo_epi32(row(p + 4), row(p + 6));  // a2 a3 b2 b3
        first = _mm_unpacklo_epi64(r01, r23);
        second = _mm_unpackhi_epi64(r01, r23);
      };
      r = interleaved_sixteens(x, m, four, b0, b1);
    } else if constexpr (std::is_same_v<Scalar, float>) {
      // Two rows per vector: lanes 0 and 2 are feature 0, lanes 1 and 3 feature 1.
      const __m128 vlo = _mm_set_ps(c1.lo, c0.lo, c1.lo, c0.lo),
                   vinv = _mm_set_ps(c1.inv, c0.inv, c1.inv, c0.inv),
                   vlast = _mm_set_ps(c1.last, c0.last, c1.last, c0.last);
      auto rows =
          [&](const float* p) {  // {a, b, a', b'} bins as int32, viewed as floats to shuffle
            return _mm_castsi128_ps(_mm_cvttps_epi32(
                _mm_min_ps(_mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(p), vlo), vinv), vlast)));
          };
      auto four = [&](const float* p, __m128i& first, __m128i& second) {
        const __m128 r01 = rows(p), r23 = rows(p + 4);
        first = _mm_castps_si128(_mm_shuffle_ps(r01, r23, _MM_SHUFFLE(2, 0, 2, 0)));
        second = _mm_castps_si128(_mm_shuffle_ps(r01, r23, _MM_SHUFFLE(3, 1, 3, 1)));
      };
      r = interleaved_sixteens(x, m, four, b0, b1);
    }
  }
#endif
  for (; r < m; ++r) {
    const Scalar u0 = (x[2 * r] - c0.lo) * c0.inv, u1 = (x[2 * r + 1] - c1.lo) * c1.inv;
    b0[r] = static_cast<std::uint8_t>(static_cast<std::int32_t>(u0 < c0.last ? u0 : c0.last));
    b1[r] = static_cast<std::uint8_t>(static_cast<std::int32_t>(u1 < c1.last ? u1 : c1.last));
  }
}

/// Most bins the compare-and-count path takes: it costs k compares per 16 values, which beyond
/// about 16 bins is more than the scalar increments it replaces (docs/benchmarks.md).
inline constexpr std::size_t kCompareCountMaxBins = 16;

#if defined(HBOS_DETAIL_ISA_DISPATCH) && defined(HBOS_DETAIL_BYTE_BINS_SSE2)
/// The AVX2 body of count_byte_indices: 32 indices per compare. Returns the indices counted.
HBOS_DETAIL_TARGET_AVX2 inline std::size_t count_byte_indices_avx2(const std::uint8_t* index,
                                                                   std::size_t m, std::size_t k,
                                                                   std::uint64_t* counts) {
  constexpr std::size_t max_vectors = 255;  // no byte lane can overflow in a round
  const __m256i zero = _mm256_setzero_si256();
  std::size_t i = 0;
  while (m - i >= 32) {
    const std::size_t vectors = std::min((m - i) / 32, max_vectors);
    const std::uint8_t* p = index + i;
    std::uint64_t counted = 0;
    for (std::size_t b = 0; b + 1 < k; ++b) {
      const __m256i bin = _mm256_set1_epi8(static_cast<char>(b));
      __m256i lanes0 = zero, lanes1 = zero;
      std::size_t v = 0;
      for (; v + 2 <= vectors; v += 2) {
        const __m256i x0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + 32 * v));
        const __m256i x1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + 32 * v + 32));
        lanes0 = _mm256_sub_epi8(lanes0, _mm256_cmpeq_epi8(x0, bin));
        lanes1 = _mm256_sub_epi8(lanes1, _mm256_cmpeq_epi8(x1, bin));
      }
      if (v < vectors) {
        const __m256i x0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + 32 * v));
        lanes0 = _mm256_sub_epi8(lanes0, _mm256_cmpeq_epi8(x0, bin));
      }
      const __m256i sums =
          _mm256_add_epi64(_mm256_sad_epu8(lanes0, zero), _mm256_sad_epu8(lanes1, zero));
      const __m128i half =
          _mm_add_epi64(_mm256_castsi256_si128(sums), _mm256_extracti128_si256(sums, 1));
      const std::uint64_t c =
          static_cast<std::uint64_t>(_mm_cvtsi128_si64(half)) +
          static_cast<std::uint64_t>(_mm_cvtsi128_si64(_mm_unpackhi_epi64(half, half)));
      counts[b] += c;
      counted += c;
    }
    counts[k - 1] += 32 * vectors - counted;
    i += 32 * vectors;
  }
  return i;
}
#endif

/// Adds to counts[b] the number of entries of `index[0, m)` equal to b, for every b < k, where
/// k <= kCompareCountMaxBins and every entry is below k.
inline void count_byte_indices(const std::uint8_t* index, std::size_t m, std::size_t k,
                               std::uint64_t* counts, Isa isa = active_isa()) {
  std::size_t i = 0;
#if defined(HBOS_DETAIL_ISA_DISPATCH) && defined(HBOS_DETAIL_BYTE_BINS_SSE2)
  if (isa == Isa::Avx2) i = count_byte_indices_avx2(index, m, k, counts);
#endif
  (void)isa;
#ifdef HBOS_DETAIL_BYTE_BINS_SSE2
  // At most 255 vectors per round, so no byte lane can overflow.
  constexpr std::size_t max_vectors = 255;
  const __m128i zero = _mm_setzero_si128();
  while (m - i >= 16) {
    const std::size_t vectors = std::min((m - i) / 16, max_vectors);
    const std::uint8_t* p = index + i;
    auto matches = [&](std::size_t v, __m128i bin) {  // -1 in each lane equal to bin
      return _mm_cmpeq_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 16 * v)), bin);
    };
    // Every bin but the last is counted; the last gets what the others leave of the round.
    std::uint64_t counted = 0;
    for (std::size_t b = 0; b + 1 < k; ++b) {
      const __m128i bin = _mm_set1_epi8(static_cast<char>(b));
      // Two sets of lanes, so that each vector's subtraction does not wait on the previous one.
      __m128i lanes0 = zero, lanes1 = zero;
      std::size_t v = 0;
      for (; v + 2 <= vectors; v += 2) {
        lanes0 = _mm_sub_epi8(lanes0, matches(v, bin));
        lanes1 = _mm_sub_epi8(lanes1, matches(v + 1, bin));
      }
      if (v < vectors) lanes0 = _mm_sub_epi8(lanes0, matches(v, bin));
      // One sum per 8 lanes, in 64-bit halves.
      const __m128i sums = _mm_add_epi64(_mm_sad_epu8(lanes0, zero), _mm_sad_epu8(lanes1, zero));
      const std::uint64_t c =
          static_cast<std::uint64_t>(_mm_cvtsi128_si32(sums)) +
          static_cast<std::uint64_t>(_mm_cvtsi128_si32(_mm_unpackhi_epi64(sums, sums)));
      counts[b] += c;
      counted += c;
    }
    counts[k - 1] += 16 * vectors - counted;
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

#if defined(HBOS_DETAIL_ISA_DISPATCH) && defined(HBOS_DETAIL_BYTE_BINS_SSE2)
/// Eight int32 pair indices first[r] * k1 + second[r]: the bytes interleaved as int16 pairs
/// and multiplied by (k1, 1) with one multiply-add of integers (exact: each is below 256).
HBOS_DETAIL_TARGET_AVX2 inline __m256i eight_pair_indices_avx2(const std::uint8_t* first,
                                                               const std::uint8_t* second,
                                                               __m256i weights) {
  const __m128i a = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(first));
  const __m128i b = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(second));
  return _mm256_madd_epi16(_mm256_cvtepu8_epi16(_mm_unpacklo_epi8(a, b)), weights);
}

// Eight entries table[q] into out. The masked gathers take a zeroed source: the plain ones
// leave it undefined, which GCC 12 reports as maybe uninitialised.
HBOS_DETAIL_TARGET_AVX2 inline void gather_eight_avx2(const double* table, __m256i q, double* out) {
  const __m256d all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  _mm256_storeu_pd(
      out, _mm256_mask_i32gather_pd(_mm256_setzero_pd(), table, _mm256_castsi256_si128(q), all, 8));
  _mm256_storeu_pd(out + 4, _mm256_mask_i32gather_pd(_mm256_setzero_pd(), table,
                                                     _mm256_extracti128_si256(q, 1), all, 8));
}

HBOS_DETAIL_TARGET_AVX2 inline void gather_eight_avx2(const float* table, __m256i q, float* out) {
  const __m256 all = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
  _mm256_storeu_ps(out, _mm256_mask_i32gather_ps(_mm256_setzero_ps(), table, q, all, 4));
}

/// The AVX2 body of lookup_byte_pairs: eight pair indices computed in registers and their
/// entries gathered, with no buffer of pair indices and one store per four doubles or eight
/// floats instead of one per entry. A gather copies the entries' bits. Returns the rows done.
template <class Scalar>
HBOS_DETAIL_TARGET_AVX2 std::size_t lookup_byte_pairs_avx2(const Scalar* table,
                                                           const std::uint8_t* first,
                                                           const std::uint8_t* second,
                                                           std::size_t k1, std::size_t m,
                                                           Scalar* out) {
  const __m256i weights = _mm256_set1_epi32(static_cast<int>((1U << 16) | k1));
  std::size_t i = 0;
  for (; m - i >= 8; i += 8)
    gather_eight_avx2(table, eight_pair_indices_avx2(first + i, second + i, weights), out + i);
  return i;
}
#endif

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

/// out[r] = table[first[r] * k1 + second[r]] for r < m, where every pair index is below 256:
/// the pair-table scoring of two features' bins (one byte each, or the 16-bit indices of a
/// Workspace). The pair indices are computed a block at a time in a loop the compiler
/// vectorises, then looked up (lookup_byte_indices, streamed with `stream_out`). For one-byte
/// bins the AVX2 body, taken when nothing is to be streamed (its gathers were slower than the
/// baseline's streaming stores there), computes and gathers eight at a time.
template <class Scalar, class BinIndex>
void lookup_byte_pairs(const Scalar* table, const BinIndex* first, const BinIndex* second,
                       std::size_t k1, std::size_t m, Scalar* out, bool stream_out,
                       Isa isa = active_isa()) {
  std::size_t i = 0;
#if defined(HBOS_DETAIL_ISA_DISPATCH) && defined(HBOS_DETAIL_BYTE_BINS_SSE2)
  // Floats are never streamed (lookup_byte_indices).
  if constexpr (std::is_same_v<BinIndex, std::uint8_t>) {
    if (isa == Isa::Avx2 && (!stream_out || !std::is_same_v<Scalar, double>))
      i = lookup_byte_pairs_avx2(table, first, second, k1, m, out);
  }
#endif
  (void)isa;
  std::array<std::uint8_t, 2048> pair;
  const auto k1_byte = static_cast<std::uint8_t>(k1);
  while (i < m) {
    const std::size_t ms = std::min(pair.size(), m - i);
    for (std::size_t r = 0; r < ms; ++r)
      pair[r] = static_cast<std::uint8_t>(static_cast<std::uint8_t>(first[i + r] * k1_byte) +
                                          second[i + r]);
    lookup_byte_indices(table, pair.data(), ms, out + i, stream_out);
    i += ms;
  }
}

/// Orders the non-temporal stores of lookup_byte_indices before any later store (they are
/// weakly ordered): called once after the last of them.
inline void fence_streaming_stores() {
#ifdef HBOS_DETAIL_BYTE_BINS_SSE2
  _mm_sfence();
#endif
}

}  // namespace hbos::detail
