// What each simulated second of a scene costs (issue 46: the end of Euler's disk in real time): the scene advanced
// one second at a time, the thread CPU time of each, as the node would spend it at real-time factor 1. Prints the
// seconds that cost the most, the last second before the run's end and the median; several rounds, medians of each.
//   build/bin/second_costs config/scenes/euler_disk.yaml [rounds=3]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

#include "top_sim/contact.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {

double cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// One run: the CPU seconds of each simulated second until the run stops or reaches the scene's duration.
std::vector<double> second_costs(const top_sim::Scene& scene, double& end_time, std::string& end) {
  top_sim::Simulator sim(scene);
  std::vector<double> costs;
  for (double t = 1.0; t <= scene.duration + 1e-9 && !sim.stopped(); t += 1.0) {
    const double c = cpu();
    sim.advance_to(t);
    costs.push_back(cpu() - c);
  }
  end_time = sim.time();
  end = sim.end_state() != top_sim::EndState::none ? top_sim::to_string(sim.end_state())
        : sim.fault() != top_sim::ContactFault::none ? top_sim::to_string(sim.fault())
                                                     : "duration";
  return costs;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: second_costs SCENE.yaml [rounds]\n");
    return 2;
  }
  const top_sim::Scene scene = top_sim::load_scene(argv[1]);
  const int rounds = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  std::vector<std::vector<double>> runs;
  double end_time = 0.0;
  std::string end;
  for (int r = 0; r < rounds; ++r) runs.push_back(second_costs(scene, end_time, end));
  const std::size_t n = runs.front().size();
  std::vector<double> per_second(n), total(rounds, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    std::vector<double> at;
    for (int r = 0; r < rounds; ++r) at.push_back(runs[r][k]);
    per_second[k] = median(at);
  }
  for (int r = 0; r < rounds; ++r)
    for (double c : runs[r]) total[r] += c;
  std::printf("scene %s: ends at t = %.3f s (%s); %d rounds, medians of each second's CPU [s]\n", argv[1], end_time,
              end.c_str(), rounds);
  std::printf("total CPU %.4f s (median of rounds), median second %.5f s, last second (t in (%zu, %.3f]) %.5f s\n",
              median(total), median(per_second), n - 1, end_time, per_second.back());
  std::vector<std::size_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return per_second[a] > per_second[b]; });
  for (std::size_t i = 0; i < std::min<std::size_t>(5, n); ++i)
    std::printf("  second %zu-%zu: %.5f s\n", order[i], order[i] + 1, per_second[order[i]]);
  return 0;
}
