// top_sim_run SCENE.yaml [--duration S] [--csv FILE] [--rate HZ] [--summary FILE]
// Runs one scene without ROS; exit 0 ok, 2 bad scene or argument, 3 contact fault.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "run_output.hpp"
#include "top_sim/scene.hpp"

namespace {

const char* kUsage =
    "usage: top_sim_run SCENE.yaml [--duration S] [--csv FILE] [--rate HZ] [--summary FILE|-]\n"
    "  --duration S    simulated seconds (default: the scene's duration)\n"
    "  --csv FILE      write the state at --rate samples per simulated second\n"
    "  --rate HZ       CSV sample rate (default 100)\n"
    "  --summary FILE  write the JSON summary (- for standard output)\n";

struct BadArgument {
  std::string message;
};

double positive_number(const std::string& flag, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(v) || v <= 0.0)
    throw BadArgument{flag + " = '" + text + "': must be a number > 0"};
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace top_sim;
  std::string scene_path, csv_path, summary_path;
  double duration = -1.0, rate = 100.0;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> const char* {
        if (i + 1 >= argc) throw BadArgument{a + ": needs a value"};
        return argv[++i];
      };
      if (a == "-h" || a == "--help") {
        std::cout << kUsage;
        return 0;
      } else if (a == "--duration") {
        duration = positive_number(a, value());
      } else if (a == "--rate") {
        rate = positive_number(a, value());
      } else if (a == "--csv") {
        csv_path = value();
      } else if (a == "--summary") {
        summary_path = value();
      } else if (!a.empty() && a[0] == '-') {
        throw BadArgument{"unknown option '" + a + "'"};
      } else if (scene_path.empty()) {
        scene_path = a;
      } else {
        throw BadArgument{"more than one scene file ('" + scene_path + "', '" + a + "')"};
      }
    }
    if (scene_path.empty()) throw BadArgument{"no scene file given"};
  } catch (const BadArgument& e) {
    std::cerr << "top_sim_run: " << e.message << "\n" << kUsage;
    return 2;
  }

  Scene scene;
  try {
    scene = load_scene(scene_path);
  } catch (const SceneError& e) {
    std::cerr << "top_sim_run: bad scene: " << e.what() << "\n";
    return 2;
  }
  for (const auto& w : scene.warnings) std::cerr << "top_sim_run: warning: " << w << "\n";

  std::ofstream csv;
  if (!csv_path.empty()) {
    csv.open(csv_path);
    if (!csv) {
      std::cerr << "top_sim_run: --csv = '" << csv_path << "': cannot open for writing\n";
      return 2;
    }
    write_csv_header(csv);
  }

  Simulator sim(scene);
  RunOptions opt;
  opt.duration = duration > 0.0 ? duration : scene.duration;
  if (csv.is_open()) {
    opt.sample_rate = rate;
    opt.on_sample = [&csv](const Snapshot& s) { write_csv_row(csv, s); };
  }
  const RunResult r = run(sim, opt);
  const std::string json = summary_json(scene, r);
  if (summary_path == "-") {
    std::cout << json;
  } else if (!summary_path.empty()) {
    std::ofstream out(summary_path);
    if (!out) {
      std::cerr << "top_sim_run: --summary = '" << summary_path << "': cannot open for writing\n";
      return 2;
    }
    out << json;
  }
  if (summary_path != "-") {
    std::cout << scene.source << ": " << r.sim_seconds << " s simulated in " << r.cpu_seconds << " s CPU ("
              << r.stats.steps << " steps, " << r.stats.rhs_evaluations << " right-hand sides), regime "
              << to_string(r.final.regime);
    if (r.phi_measured) std::cout << ", phi_measured " << *r.phi_measured;
    if (r.phi_star) std::cout << ", phi_star " << *r.phi_star;
    if (r.phi_measured && r.phi_star) std::cout << " (difference " << std::abs(*r.phi_measured - *r.phi_star) << ")";
    std::cout << ", energy residual " << r.max_energy_residual << "\n";
    if (!r.stationary_note.empty()) std::cout << "  stationary state: " << r.stationary_note << "\n";
  }
  if (r.final.fault != ContactFault::none) {
    std::cerr << "top_sim_run: contact fault: " << r.final.fault_message << "\n";
    return 3;
  }
  return 0;
}
