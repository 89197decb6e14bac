// A global operator new that counts heap allocations (issue 21's guard): include it in exactly one translation unit
// of a program (the replacement functions may not be inline); read heap_allocations() before and after the work.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace top_sim_counting {
inline std::atomic<std::uint64_t> g_allocations{0};
inline std::uint64_t heap_allocations() { return g_allocations.load(std::memory_order_relaxed); }
inline void* counted_malloc(std::size_t n) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n ? n : 1);
}
}  // namespace top_sim_counting

// Every unaligned form is replaced, so that new and delete always pair malloc with free (AddressSanitizer checks
// the pairing: a nothrow new left to the runtime and freed here is a mismatch, seen in std::stable_sort's buffer).
void* operator new(std::size_t n) {
  if (void* p = top_sim_counting::counted_malloc(n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return top_sim_counting::counted_malloc(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return top_sim_counting::counted_malloc(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
