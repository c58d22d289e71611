#pragma once
// Counts heap allocations (replaces global operator new) so tests can check
// that per-frame runtime code allocates nothing. Include it in exactly one
// .cpp of a test executable.
//
// Every replaceable form is replaced (plain, nothrow, aligned, aligned
// nothrow, and the matching deletes): replacing only some would pair, e.g.,
// the library's nothrow new (used by std::stable_sort's temporary buffer)
// with this free(), which AddressSanitizer reports as alloc-dealloc-mismatch.
#include <atomic>
#include <cstdlib>
#include <new>

namespace legwork::alloc_count {
inline std::atomic<long> g_allocations{0};

// Allocations made while `fn` runs.
template <class Fn>
long count_allocations(Fn&& fn) {
  const long before = g_allocations.load();
  fn();
  return g_allocations.load() - before;
}

inline void* counted_malloc(std::size_t n) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n ? n : 1);
}
inline void* counted_aligned(std::size_t n, std::align_val_t al) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  std::size_t a = static_cast<std::size_t>(al);
  if (a < sizeof(void*)) a = sizeof(void*);
  void* p = nullptr;
  return ::posix_memalign(&p, a, n ? n : 1) == 0 ? p : nullptr;
}
}  // namespace legwork::alloc_count

void* operator new(std::size_t n) {
  if (void* p = legwork::alloc_count::counted_malloc(n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  if (void* p = legwork::alloc_count::counted_malloc(n)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return legwork::alloc_count::counted_malloc(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return legwork::alloc_count::counted_malloc(n); }
void* operator new(std::size_t n, std::align_val_t al) {
  if (void* p = legwork::alloc_count::counted_aligned(n, al)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n, std::align_val_t al) {
  if (void* p = legwork::alloc_count::counted_aligned(n, al)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t n, std::align_val_t al, const std::nothrow_t&) noexcept {
  return legwork::alloc_count::counted_aligned(n, al);
}
void* operator new[](std::size_t n, std::align_val_t al, const std::nothrow_t&) noexcept {
  return legwork::alloc_count::counted_aligned(n, al);
}
// GCC cannot see that the replaced operator new above allocates with
// malloc: where it inlines a `delete` of a `new` into this free() it warns
// -Wmismatched-new-delete (a false positive here; the pairs do match).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
