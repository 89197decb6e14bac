// What one top costs a node per tick, without ROS (issue 21, docs/node_benchmark.md): TOPS copies of a scene
// advanced in ticks of 1 / RATE s, each read with snapshot() after its advance (what a `top_states` reader asks),
// the tops taken in turn as the node takes them. Prints the CPU time per top per tick and the steps and right-hand
// sides per tick of the first top. The CPU time on a shared machine moves with its neighbours; run it under
// valgrind twice with different SECONDS and divide the difference of the counts by the extra top-ticks:
//   valgrind --tool=callgrind  build/bin/tick_footprint config/scenes/default.yaml 50 1    (then 2: instructions)
//   valgrind --tool=cachegrind --cache-sim=yes --LL=3145728,12,64 build/bin/tick_footprint SCENE 1000 0.1 (0.3)
// (D1 misses: the cache lines a top touches per tick, its data long evicted when its turn comes again).
// READ says what is read after each advance: `snapshot` (the default), `pose` (what tf and a top not read by a
// `top_states` subscriber cost the node) or `none` (the physics alone).
//   build/bin/tick_footprint SCENE TOPS SECONDS [WARMUP_TICKS=200] [RATE=200] [READ=snapshot|pose|none]
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {

double cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

int usage() {
  std::fprintf(stderr, "usage: tick_footprint SCENE TOPS SECONDS [WARMUP_TICKS=200] [RATE=200] [READ=snapshot|pose|none]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4 || argc > 7) return usage();
  const int tops = std::atoi(argv[2]);
  const double seconds = std::atof(argv[3]);
  const int warmup = argc > 4 ? std::atoi(argv[4]) : 200;
  const double rate = argc > 5 ? std::atof(argv[5]) : 200.0;
  const std::string read = argc > 6 ? argv[6] : "snapshot";
  if (tops < 1 || !(seconds > 0.0) || warmup < 0 || !(rate > 0.0)) return usage();
  if (read != "snapshot" && read != "pose" && read != "none") return usage();
  const int reading = read == "snapshot" ? 0 : read == "pose" ? 1 : 2;  // no string compare per top
  const top_sim::Scene scene = top_sim::load_scene(argv[1]);
  std::vector<std::unique_ptr<top_sim::Simulator>> sims;
  for (int i = 0; i < tops; ++i) sims.push_back(std::make_unique<top_sim::Simulator>(scene));
  double t = 0.0, sink = 0.0;
  const auto tick = [&] {
    t += 1.0 / rate;
    for (auto& s : sims) {
      s->advance_to(t);
      if (reading == 0) sink += s->snapshot().energy;  // read, so the sample is built
      else if (reading == 1) sink += s->pose().tip_center.x();
      else sink += s->time();
    }
  };
  for (int k = 0; k < warmup; ++k) tick();
  const int ticks = static_cast<int>(seconds * rate);
  const double c0 = cpu();
  for (int k = 0; k < ticks; ++k) tick();
  const double used = cpu() - c0;
  const auto& stats = sims.front()->stats();
  const double all_ticks = static_cast<double>(warmup + ticks);
  std::printf("%d tops, %d + %d ticks at %g Hz, read %s: %.3f us CPU per top per tick; first top: %.3f steps, %.2f right-hand "
              "sides per tick (checksum %.6g)\n",
              tops, warmup, ticks, rate, read.c_str(), 1e6 * used / (static_cast<double>(tops) * ticks),
              static_cast<double>(stats.steps) / all_ticks, static_cast<double>(stats.rhs_evaluations) / all_ticks,
              sink);
  return 0;
}
