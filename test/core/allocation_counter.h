// Counts every heap allocation of a test binary, so that a test can show that a steady-state
// cycle allocates nothing. Replaces the global operator new and delete: include it from exactly
// one translation unit of a test binary (each test/core/test_*.cpp is its own binary).
#pragma once

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace arm_collision_monitor {
namespace test {

inline std::atomic<std::uint64_t> g_allocation_count{0};

/// Number of operator new / new[] calls since the process started.
inline std::uint64_t AllocationCount() { return g_allocation_count.load(); }

}  // namespace test
}  // namespace arm_collision_monitor

// GCC cannot see that the replaced operator new allocates with malloc, and flags the matching
// free() in the replaced operator delete as a mismatch.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  arm_collision_monitor::test::g_allocation_count.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop
