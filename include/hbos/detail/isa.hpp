#pragma once
/// \file
/// Run-time choice of the instruction set for the hot fitting and scoring kernels.
///
/// The library is compiled for whatever the user's flags allow, usually baseline x86-64 (SSE2).
/// On GCC and Clang for x86-64 the kernels of column_view.hpp and byte_bins.hpp also have AVX2
/// bodies (compiled with `__attribute__((target("avx2")))`, without FMA, so that no multiply
/// and add can be contracted into one rounding), taken when the CPU supports AVX2. Each AVX2
/// body does per value the IEEE operations the SSE2 body does, in an order that gives the same
/// bits (see each kernel), so the choice changes the speed and never a result.
///
/// Define HBOS_NO_ISA_DISPATCH to compile only the baseline bodies. Other compilers and
/// architectures get them anyway.

#if !defined(HBOS_NO_ISA_DISPATCH) && defined(__x86_64__) && \
    (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define HBOS_DETAIL_ISA_DISPATCH 1
/// Compiles a function for AVX2 (no FMA: avx2 alone does not enable it).
#define HBOS_DETAIL_TARGET_AVX2 __attribute__((target("avx2")))
#endif

namespace hbos::detail {

/// The instruction sets a kernel can run with.
enum class Isa : unsigned char {
  Baseline,  ///< what the compiler flags allow (SSE2 on x86-64)
  Avx2       ///< AVX2 bodies (only with HBOS_DETAIL_ISA_DISPATCH)
};

/// The best instruction set of this CPU among those compiled in (asked once).
[[nodiscard]] inline Isa best_isa() noexcept {
#ifdef HBOS_DETAIL_ISA_DISPATCH
  static const Isa isa = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") ? Isa::Avx2 : Isa::Baseline;
  }();
  return isa;
#else
  return Isa::Baseline;
#endif
}

/// This thread's choice when set by ScopedIsa: tests compare the paths with it.
inline thread_local int isa_override = -1;

/// The instruction set the kernels use on this thread: best_isa(), or what a ScopedIsa set,
/// lowered to Baseline when the CPU lacks it.
[[nodiscard]] inline Isa active_isa() noexcept {
  if (isa_override < 0) return best_isa();
  const auto wanted = static_cast<Isa>(isa_override);
  return wanted == Isa::Avx2 && best_isa() == Isa::Avx2 ? Isa::Avx2 : Isa::Baseline;
}

/// Makes this thread's kernels use `isa` (or Baseline, where the CPU lacks it) while it lives.
class ScopedIsa {
 public:
  explicit ScopedIsa(Isa isa) noexcept : previous_(isa_override) {
    isa_override = static_cast<int>(isa);
  }
  ~ScopedIsa() { isa_override = previous_; }
  ScopedIsa(const ScopedIsa&) = delete;
  ScopedIsa& operator=(const ScopedIsa&) = delete;
  ScopedIsa(ScopedIsa&&) = delete;
  ScopedIsa& operator=(ScopedIsa&&) = delete;

 private:
  int previous_;
};

}  // namespace hbos::detail
