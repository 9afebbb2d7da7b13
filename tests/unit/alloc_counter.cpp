// The one replacement of the global allocation functions in hbos_unit_tests: every form of
// operator new bumps a per-thread counter (while an AllocationCounter is alive) and forwards to
// malloc, so tests can prove that hot paths allocate nothing after warm-up.

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
void* counted_allocate(std::size_t size) {
  if (hbos_test::detail::thread_counting()) ++hbos_test::detail::thread_allocations();
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* counted_allocate_aligned(std::size_t size, std::align_val_t alignment) {
  if (hbos_test::detail::thread_counting()) ++hbos_test::detail::thread_allocations();
  const auto align = static_cast<std::size_t>(alignment);
  const std::size_t rounded = (size + align - 1) / align * align;
  if (void* p = std::aligned_alloc(align, rounded == 0 ? align : rounded)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t size) { return counted_allocate(size); }
void* operator new[](std::size_t size) { return counted_allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return counted_allocate(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return counted_allocate(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t size, std::align_val_t a) {
  return counted_allocate_aligned(size, a);
}
void* operator new[](std::size_t size, std::align_val_t a) {
  return counted_allocate_aligned(size, a);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
