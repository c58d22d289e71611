#pragma once
// Counts heap allocations (replaces global operator new) so tests can check
// that per-frame runtime code allocates nothing. Include it in exactly one
// .cpp of a test executable.
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
}  // namespace legwork::alloc_count

void* operator new(std::size_t n) {
  legwork::alloc_count::g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
