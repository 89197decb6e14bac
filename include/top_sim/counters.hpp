// Work counters of the core (issue 21's guard): how often the expensive derived quantities are computed. Read by
// test/core/counters_test.cpp; relaxed atomics, one uncontended add per counted call (no timing, no lock).
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

inline void count(std::atomic<std::uint64_t>& counter) { counter.fetch_add(1, std::memory_order_relaxed); }

}  // namespace top_sim
