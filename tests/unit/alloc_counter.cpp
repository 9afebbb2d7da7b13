// The one allocation hook of hbos_unit_tests. Two routes reach the heap from our code:
//  - operator new (std::vector and friends): replaced below, forwarding to std::malloc;
//  - std::malloc directly (Eigen's aligned_malloc never calls operator new).
// tests/CMakeLists.txt links this executable with `-Wl,--wrap=malloc,...`, so every call to
// malloc/calloc/realloc/aligned_alloc/posix_memalign made from the test's own object files —
// including inlined Eigen code and the operator new below — lands in a __wrap_ function that
// bumps a per-thread counter and forwards to the real allocator (__real_, which under ASan is
// the sanitizer's). Counting at the malloc level means nothing is counted twice.

#include <cstdlib>
#include <new>

#include "../support/alloc_counter.hpp"

namespace hbos_test::detail {
std::size_t& thread_allocations() {
  thread_local std::size_t count = 0;
  return count;
}
bool& thread_counting() {
  thread_local bool counting = false;
  return counting;
}
}  // namespace hbos_test::detail

namespace {
void count_one() {
  if (hbos_test::detail::thread_counting()) ++hbos_test::detail::thread_allocations();
}
}  // namespace

// The linker's --wrap contract: __real_X is the original symbol, __wrap_X replaces references.
extern "C" {
void* __real_malloc(std::size_t size);
void* __real_calloc(std::size_t n, std::size_t size);
void* __real_realloc(void* p, std::size_t size);
void* __real_aligned_alloc(std::size_t alignment, std::size_t size);
int __real_posix_memalign(void** p, std::size_t alignment, std::size_t size);

void* __wrap_malloc(std::size_t size) {
  count_one();
  return __real_malloc(size);
}
void* __wrap_calloc(std::size_t n, std::size_t size) {
  count_one();
  return __real_calloc(n, size);
}
void* __wrap_realloc(void* p, std::size_t size) {
  count_one();
  return __real_realloc(p, size);
}
void* __wrap_aligned_alloc(std::size_t alignment, std::size_t size) {
  count_one();
  return __real_aligned_alloc(alignment, size);
}
int __wrap_posix_memalign(void** p, std::size_t alignment, std::size_t size) {
  count_one();
  return __real_posix_memalign(p, alignment, size);
}
}

namespace {
void* allocate(std::size_t size) {
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* allocate_aligned(std::size_t size, std::align_val_t alignment) {
  const auto align = static_cast<std::size_t>(alignment);
  const std::size_t rounded = (size + align - 1) / align * align;
  if (void* p = std::aligned_alloc(align, rounded == 0 ? align : rounded)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return allocate(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return allocate(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t size, std::align_val_t a) { return allocate_aligned(size, a); }
void* operator new[](std::size_t size, std::align_val_t a) { return allocate_aligned(size, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
