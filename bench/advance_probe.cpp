// What advancing costs without a reader (issue 21, docs/performance.md): 300 s of a scene in one advance, in 300,000
// unread advances of 1 ms, and in 300,000 advances each read with snapshot(); then one stationary solve against
// one work-counter increment. Medians (min-max) of 5 interleaved rounds, thread CPU time. Built with the other
// bench/*.cpp where Google Benchmark is found:   build/bin/advance_probe config/scenes/default.yaml
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <ctime>
#include <functional>
#include <vector>

#include "../src/core/counters.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/stationary.hpp"

namespace {

double cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double timed(const std::function<void()>& f) {
  const double c = cpu();
  f();
  return cpu() - c;
}

void print(const char* what, std::vector<double> v, double scale, const char* unit) {
  std::sort(v.begin(), v.end());
  std::printf("%-40s median %.4g %s (%.4g-%.4g)\n", what, scale * v[v.size() / 2], unit, scale * v.front(),
              scale * v.back());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const top_sim::Scene scene = top_sim::load_scene(argv[1]);
  constexpr int kRounds = 5, kSlices = 300000;
  std::vector<double> one, unread, read, solve, add;
  double sink = 0.0;
  for (int k = 0; k < kRounds; ++k) {
    one.push_back(timed([&] { top_sim::Simulator s(scene); s.advance_to(300.0); }));
    unread.push_back(timed([&] {
      top_sim::Simulator s(scene);
      for (int i = 1; i <= kSlices; ++i) s.advance_to(1e-3 * i);
    }));
    read.push_back(timed([&] {
      top_sim::Simulator s(scene);
      for (int i = 1; i <= kSlices; ++i) {
        s.advance_to(1e-3 * i);
        sink += s.snapshot().energy;
      }
    }));
    solve.push_back(timed([&] {
      for (int i = 0; i < 200000; ++i) sink += top_sim::stationary_state(scene.model, 200.0 + 1e-6 * i).slip;
    }) / 200000);
    std::atomic<std::uint64_t> counter{0};
    add.push_back(timed([&] {
      for (int i = 0; i < 20000000; ++i) top_sim::count(counter);
    }) / 20000000);
  }
  print("300 s in one advance", one, 1e3, "ms");
  print("300 s in 300000 unread 1 ms advances", unread, 1e3, "ms");
  print("the same, snapshot() after each", read, 1e3, "ms");
  print("one stationary_state()", solve, 1e9, "ns");
  print("one work-counter increment", add, 1e9, "ns");
  return sink == 0.123 ? 1 : 0;
}
