// Work counters of the core (issue 21's guard): how often the expensive derived quantities are computed. Read by
// test/core/counters_test.cpp; no timing, no lock.
#pragma once

#include <atomic>
#include <cstdint>

namespace top_sim {

struct WorkCounters {
  std::atomic<std::uint64_t> sample_analyses{0};    // analyse_sample(): dynamics, stationary solve, indicators, energy
  std::atomic<std::uint64_t> stationary_solves{0};  // stationary_state()
};

// The process-wide counters (never reset by the core: tests take differences).
WorkCounters& work_counters();

// A relaxed load and store, not a locked add (measured 6.6 ns per add against 0.7 ns): exact in one thread (the tests),
// it may lose counts when threads count at once, and it costs nothing measurable next to what it counts.
inline void count(std::atomic<std::uint64_t>& counter) {
  counter.store(counter.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
}

}  // namespace top_sim
