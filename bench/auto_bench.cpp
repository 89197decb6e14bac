// model.kind auto against the full model (physics.md section 7.1, docs/analysis.md "model.kind auto"):
//   auto_bench table [CONFIG_DIR]  the error grid (tops x planes x inclinations x spins): markdown on stdout
//   auto_bench speed [CONFIG_DIR]  a 3000 s relaxation, full and auto, medians of 7 runs: markdown on stdout
//   auto_bench patch [CONFIG_DIR]  the same relaxation on a Hertz patch (exact and elliptic), medians of 5 runs
// Both run each point twice from the same scene, with model.kind full and auto, and compare them in lock-step.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "../src/output/run.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/stationary.hpp"

namespace {

using namespace top_sim;

// kind "full", or "auto" with model.auto_tolerance `tolerance` (0: the default); `contact` a contact section.
std::string scene_text(const std::string& top, const std::string& plane, double alpha, double spin,
                       const std::string& kind, double tolerance = 0.0, const std::string& contact = "") {
  char model[128], buf[512];
  if (tolerance > 0.0) std::snprintf(model, sizeof model, "{kind: %s, auto_tolerance: %.17g}", kind.c_str(), tolerance);
  else std::snprintf(model, sizeof model, "{kind: %s}", kind.c_str());
  std::snprintf(buf, sizeof buf,
                "top: %s\nfriction: %s\nplane: {inclination: %.17g}\nmodel: %s\n"
                "initial: {start: tilted, tilt: 0.1, spin: %.17g}\n",
                top.c_str(), plane.c_str(), alpha, model, spin);
  return buf + contact;
}

struct Comparison {
  double handover_t = NAN;        // first handover (NaN: none within the run)
  double max_contact = 0.0;       // max |contact point auto - full| over the checkpoints after the handover [m]
  double phi_auto = 0.0, phi_full = 0.0, phi_star = 0.0;  // at the end
  double cpu_full = 0.0, cpu_auto = 0.0;
  std::string fault;
};

// Advances `sim` to t and returns the thread CPU seconds it took.
double timed_advance(Simulator& sim, double t) {
  const double c0 = thread_cpu_seconds();
  sim.advance_to(t);
  return thread_cpu_seconds() - c0;
}

Comparison compare(const std::string& config, const std::string& top, const std::string& plane, double alpha,
                   double spin, double duration, double checkpoint) {
  Simulator full(parse_scene_text(scene_text(top, plane, alpha, spin, "full"), "full.yaml", config));
  Simulator automatic(parse_scene_text(scene_text(top, plane, alpha, spin, "auto"), "auto.yaml", config));
  Comparison c;
  for (double t = checkpoint; t <= duration + 1e-9; t += checkpoint) {
    c.cpu_full += timed_advance(full, t);
    c.cpu_auto += timed_advance(automatic, t);
    if (full.fault() != ContactFault::none || automatic.fault() != ContactFault::none) {
      c.fault = full.fault_message() + automatic.fault_message();
      return c;
    }
    if (automatic.handovers() > 0 && std::isnan(c.handover_t)) c.handover_t = t - automatic.reduced_seconds();
    c.max_contact = std::max(c.max_contact, (full.snapshot().contact_point - automatic.snapshot().contact_point).norm());
  }
  c.phi_auto = automatic.snapshot().phi;
  c.phi_full = full.snapshot().phi;
  c.phi_star = automatic.snapshot().phi_star;
  return c;
}

void table(const std::string& config) {
  const double duration = 3000.0, checkpoint = 100.0;
  std::printf("| top | plane | alpha / alpha_c | alpha [rad] | spin [rad/s] | handover [s] | max contact diff [m] | "
              "phi auto - phi* | phi full - phi* | CPU full [s] | CPU auto [s] | speed-up |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const char* plane : {"pmma", "steel"}) {
    const Scene probe = parse_scene_text(scene_text("aluminium", plane, 0.1, 200.0, "full"), "p.yaml", config);
    const double alpha_c = critical_inclination(probe.model.friction);
    for (const char* top : {"aluminium", "steel", "wood"})
      for (double fraction : {0.3, 0.6, 0.9})
        for (double spin : {100.0, 200.0, 400.0}) {
          const double alpha = fraction * alpha_c;
          const Comparison c = compare(config, top, plane, alpha, spin, duration, checkpoint);
          if (!c.fault.empty()) {
            std::printf("| %s | %s | %.1f | %.4f | %.0f | fault: %s |||||||\n", top, plane, fraction, alpha, spin,
                        c.fault.c_str());
            continue;
          }
          std::printf("| %s | %s | %.1f | %.4f | %.0f | %s | %.2e | %.1e | %.1e | %.3f | %.3f | %.1f |\n", top, plane,
                      fraction, alpha, spin,
                      std::isnan(c.handover_t) ? "none" : std::to_string(std::lround(c.handover_t)).c_str(),
                      c.max_contact, c.phi_auto - c.phi_star, c.phi_full - c.phi_star, c.cpu_full, c.cpu_auto,
                      c.cpu_full / c.cpu_auto);
          std::fflush(stdout);
        }
  }
  std::printf("\n%.0f s runs from a 0.1 rad tilt; contact points compared every %.0f s.\n", duration, checkpoint);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Thread CPU seconds of a 3000 s run of the speed scene, and its final snapshot.
double timed_run(const std::string& config, const std::string& kind, double tolerance, double duration, Snapshot& last,
                 double& reduced_seconds) {
  Simulator sim(parse_scene_text(scene_text("aluminium", "pmma", 0.1, 200.0, kind, tolerance), "speed.yaml", config));
  const double cpu = timed_advance(sim, duration);
  last = sim.snapshot();
  reduced_seconds = sim.reduced_seconds();
  return cpu;
}

void speed(const std::string& config) {
  const double duration = 3000.0;
  const int runs = 7;
  std::printf("| model | auto_tolerance [m] | handover [s] | CPU median of %d [s] | real-time factor | "
              "phi - phi* [rad] | contact point vs full [m] |\n|---|---|---|---|---|---|---|\n", runs);
  Snapshot full_last;
  std::vector<double> cpu;
  double reduced = 0.0;
  for (int i = 0; i < runs; ++i) cpu.push_back(timed_run(config, "full", 0.0, duration, full_last, reduced));
  double t = median(cpu);
  std::printf("| full | - | - | %.4f | %.0f | %.2e | 0 |\n", t, duration / t, full_last.phi - full_last.phi_star);
  for (double tolerance : {1e-5, 3e-5, 1e-4}) {
    Snapshot last;
    cpu.clear();
    for (int i = 0; i < runs; ++i) cpu.push_back(timed_run(config, "auto", tolerance, duration, last, reduced));
    t = median(cpu);
    std::printf("| auto | %.0e | %.1f | %.4f | %.0f | %.2e | %.2e |\n", tolerance, duration - reduced, t, duration / t,
                last.phi - last.phi_star, (last.contact_point - full_last.contact_point).norm());
  }
  std::printf("\naluminium top on PMMA, alpha 0.1 rad, 200 rad/s from a 0.1 rad tilt, %.0f s (one thread).\n",
              duration);
}

// A 3000 s relaxation of the speed scene on a Hertz patch: the top spins down while it sleeps.
void patch(const std::string& config) {
  const double duration = 3000.0;
  const int runs = 5;
  std::printf("| drilling law | model | full-model seconds | CPU median of %d [s] | real-time factor | phi - phi* [rad] | "
              "phi auto - full [rad] | contact point auto - full [m] | final spin [rad/s] | spin auto - full "
              "[rad/s] | end |\n|---|---|---|---|---|---|---|---|---|---|---|\n", runs);
  for (const char* law : {"exact", "elliptic"}) {
    const std::string contact = std::string("contact: {patch_radius: hertz, drilling_law: ") + law + "}\n";
    Snapshot last[2];
    std::string end[2];
    for (int k = 0; k < 2; ++k) {
      const char* kind = k == 0 ? "full" : "auto";
      std::vector<double> cpu;
      double reduced = 0.0;
      for (int i = 0; i < runs; ++i) {
        Simulator sim(parse_scene_text(scene_text("aluminium", "pmma", 0.1, 200.0, kind, 0.0, contact), "patch.yaml",
                                       config));
        cpu.push_back(timed_advance(sim, duration));
        last[k] = sim.snapshot();
        reduced = sim.reduced_seconds();
        // A top that wakes below its critical spin falls: the run ends with the fault (docs/results.md).
        end[k] = sim.fault() == ContactFault::none ? "asleep" : "fault " + std::string(to_string(sim.fault())) +
                                                                    " at " + std::to_string(sim.snapshot().t) + " s";
      }
      const double t = median(cpu);
      const Snapshot& s = last[k];
      std::printf("| %s | %s | %s | %.4f | %.0f | %.2e | %.2e | %.2e | %.4f | %.2e | %s |\n", law, kind,
                  k == 0 ? "-" : std::to_string(s.t - reduced).c_str(), t, s.t / t, s.phi - s.phi_star,
                  s.phi - last[0].phi, (s.contact_point - last[0].contact_point).norm(), s.spin, s.spin - last[0].spin,
                  end[k].c_str());
    }
  }
  std::printf("\naluminium top on PMMA with a Hertz patch, alpha 0.1 rad, 200 rad/s from a 0.1 rad tilt, %.0f s (one "
              "thread).\n", duration);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string what = argc > 1 ? argv[1] : "";
  const std::string config = argc > 2 ? argv[2] : default_config_dir();
  if (what == "table") table(config);
  else if (what == "speed") speed(config);
  else if (what == "patch") patch(config);
  else {
    std::fprintf(stderr, "usage: auto_bench table|speed|patch [CONFIG_DIR]\n");
    return 2;
  }
  return 0;
}
