#pragma once
// Counts heap allocations (operator new and malloc alike) made by the current thread while a
// scope is active. The hooks that feed it live once per test executable, in
// tests/unit/alloc_counter.cpp.
//
//     hbos_test::AllocationCounter counter;   // starts counting
//     work();
//     CHECK(counter.count() == 0);

#include <cstddef>

namespace hbos_test {

namespace detail {
/// Allocations seen on this thread while counting is on (defined in alloc_counter.cpp).
std::size_t& thread_allocations();
bool& thread_counting();
}  // namespace detail

class AllocationCounter {
 public:
  AllocationCounter() : start_(detail::thread_allocations()) { detail::thread_counting() = true; }
  ~AllocationCounter() { detail::thread_counting() = false; }
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;

  /// Heap allocations on this thread since construction.
  [[nodiscard]] std::size_t count() const { return detail::thread_allocations() - start_; }

 private:
  std::size_t start_;
};

/// Makes `p` observable, so the optimiser cannot elide the allocation that produced it (C++14
/// lets compilers drop a new/delete or malloc/free pair whose memory never escapes).
inline void escape(const void* p) { asm volatile("" : : "g"(p) : "memory"); }

}  // namespace hbos_test
