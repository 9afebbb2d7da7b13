#pragma once
// Counts heap allocations made by the current thread while a scope is active. The global
// operator new that feeds it is defined once per test executable, in tests/unit/alloc_counter.cpp.
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

}  // namespace hbos_test
