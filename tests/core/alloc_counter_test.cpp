// tests/alloc_counter.hpp replaces every form of operator new/delete: the
// nothrow form (std::stable_sort's buffer) and the aligned forms used to go
// to the library's allocator and come back to this free(), which
// AddressSanitizer reports as alloc-dealloc-mismatch.
#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

using legwork::alloc_count::count_allocations;

namespace {
struct alignas(64) Line {
  double v[8];
};
// Escapes each pointer so the compiler cannot elide a new/delete pair.
void* volatile g_sink = nullptr;
template <class T>
T* keep(T* p) {
  g_sink = p;
  return p;
}
}  // namespace

TEST(AllocCounter, CountsEveryFormOfNew) {
  EXPECT_EQ(count_allocations([] { delete keep(new int(1)); }), 1);
  EXPECT_EQ(count_allocations([] { delete[] keep(new int[4]); }), 1);
  EXPECT_EQ(count_allocations([] { ::operator delete(keep(::operator new(8, std::nothrow)), std::nothrow); }), 1);
  EXPECT_EQ(count_allocations([] {
              auto* l = keep(new Line());
              EXPECT_EQ(reinterpret_cast<std::uintptr_t>(l) % 64, 0u);
              delete l;
            }),
            1);
  EXPECT_EQ(count_allocations([] { delete[] keep(new Line[3]); }), 1);
}

TEST(AllocCounter, StableSortBufferIsCountedAndFreedByTheSameAllocator) {
  std::vector<int> v(1000);
  for (int i = 0; i < 1000; ++i) v[static_cast<std::size_t>(i)] = (i * 7919) % 1000;
  const long n = count_allocations([&] { std::stable_sort(v.begin(), v.end()); });
  EXPECT_GE(n, 1) << "std::stable_sort's temporary buffer (nothrow new) was not counted";
  EXPECT_TRUE(std::is_sorted(v.begin(), v.end()));
}

TEST(AllocCounter, NothingCountedWhenNothingAllocates) {
  int x = 0;
  EXPECT_EQ(count_allocations([&] { x += 1; }), 0);
  EXPECT_EQ(x, 1);
}
