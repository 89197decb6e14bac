// The sweep of top_sim_sweep for Python (python3 -m top_sim.sweep): the same parser of the flags, the same
// per-point simulation and the same CSV row, bound as plain dicts so that they pickle to a cluster's workers.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "arguments.hpp"
#include "sweep_options.hpp"
#include "sweep_point.hpp"

namespace py = pybind11;
using namespace top_sim;

namespace {

py::object optional_number(const std::optional<double>& v) { return v ? py::object(py::float_(*v)) : py::none(); }

std::optional<double> number_or_none(const py::dict& d, const char* key) {
  if (!d.contains(key) || d[key].is_none()) return std::nullopt;
  return d[key].cast<double>();
}

// A patch radius as a plain value that pickles: "hertz", or the number [m].
py::object patch_object(const PatchRadius& patch) {
  return patch.hertz ? py::object(py::str("hertz")) : py::object(py::float_(patch.metres));
}

PatchRadius patch_from(const py::dict& d) {
  if (!d.contains("patch_radius")) return PatchRadius{};  // a point dict of an older caller: the point contact
  const py::object v = d["patch_radius"];
  if (py::isinstance<py::str>(v)) {
    if (v.cast<std::string>() != "hertz") throw py::value_error("patch_radius: a number >= 0 [m], or 'hertz'");
    return PatchRadius{0.0, true};
  }
  return PatchRadius{v.cast<double>(), false};
}

py::dict point_dict(const SweepPoint& p) {
  return py::dict(py::arg("top") = p.top, py::arg("plane") = p.plane, py::arg("alpha") = p.alpha,
                  py::arg("spin") = p.spin, py::arg("mu_c") = optional_number(p.mu_c),
                  py::arg("s_c") = optional_number(p.s_c), py::arg("patch_radius") = patch_object(p.patch));
}

SweepPoint point_from(const py::dict& d) {
  SweepPoint p;
  p.top = d["top"].cast<std::string>();
  p.plane = d["plane"].cast<std::string>();
  p.alpha = d["alpha"].cast<double>();
  p.spin = d["spin"].cast<double>();
  p.mu_c = number_or_none(d, "mu_c");
  p.s_c = number_or_none(d, "s_c");
  p.patch = patch_from(d);
  return p;
}

// The numeric fields of SweepSettings by name: one list for both directions of the conversion.
const std::pair<const char*, double SweepSettings::*> kSettingsNumbers[] = {
    {"tilt", &SweepSettings::tilt},
    {"launch_perturbation", &SweepSettings::launch_perturbation},
    {"max_path", &SweepSettings::max_path},
    {"min_duration", &SweepSettings::min_duration},
    {"max_duration", &SweepSettings::max_duration},
    {"slide_duration", &SweepSettings::slide_duration},
    {"phi_tolerance", &SweepSettings::phi_tolerance},
    {"window_path", &SweepSettings::window_path}};

py::dict settings_dict(const SweepSettings& s) {
  py::dict d;
  d["config_dir"] = s.config_dir;
  d["start"] = s.start == SweepStart::launched ? "launched" : "tilted";
  for (const auto& [name, field] : kSettingsNumbers) d[name] = s.*field;
  return d;
}

SweepSettings settings_from(const py::dict& d) {
  SweepSettings s;
  s.config_dir = d["config_dir"].cast<std::string>();
  s.start = d["start"].cast<std::string>() == "launched" ? SweepStart::launched : SweepStart::tilted;
  for (const auto& [name, field] : kSettingsNumbers) s.*field = d[name].cast<double>();
  return s;
}

// The flags of top_sim_sweep: None after -h/--help, else the grid's points, the settings, --out and --threads.
py::object parse_options(const std::vector<std::string>& args, const py::object& error_type) {
  SweepOptions o;
  try {
    if (!parse_sweep_options(args, o)) return py::none();
  } catch (const top_sim_cli::BadArgument& e) {
    PyErr_SetString(error_type.ptr(), e.message.c_str());
    throw py::error_already_set();
  }
  py::list points;
  for (const SweepPoint& p : make_sweep_grid(o)) points.append(point_dict(p));
  py::dict d;
  d["points"] = points;
  d["settings"] = settings_dict(o.settings);
  d["out"] = o.out_path;
  d["threads"] = o.threads;
  return d;
}

py::dict result_dict(const SweepResult& r) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::ostringstream row;
  write_sweep_row(row, r);
  std::string text = row.str();
  if (!text.empty() && text.back() == '\n') text.pop_back();
  py::dict d;
  d["row"] = text;
  d["outcome"] = r.outcome;
  d["note"] = r.note;
  d["phi_star"] = r.phi_star.value_or(nan);
  d["phi_measured"] = r.phi.value_or(nan);
  d["tan_half_phi_measured"] = r.tan_half.value_or(nan);
  d["sim_seconds"] = r.sim_seconds;
  d["cpu_seconds"] = r.cpu_seconds;
  return d;
}

}  // namespace

void bind_sweep(py::module_& m) {
  std::ostringstream header;
  write_sweep_header(header);
  std::string h = header.str();
  h.pop_back();
  m.attr("SWEEP_HEADER") = h;  // the CSV header of top_sim_sweep, without the newline
  m.attr("SWEEP_USAGE") = std::string(kSweepOptionsUsage);
  const py::object error = py::reinterpret_borrow<py::object>(PyExc_ValueError);
  const py::object arg_error = py::exception<top_sim_cli::BadArgument>(m, "SweepArgumentError", error.ptr());
  m.def("parse_sweep_options", [arg_error](const std::vector<std::string>& args) { return parse_options(args, arg_error); },
        py::arg("args"),
        "top_sim_sweep's flags (no program name): None for -h/--help, else a dict of points (the grid, in "
        "top_sim_sweep's order), settings, out and threads (0 = all cores); raises SweepArgumentError.");
  m.def("sweep_scene_law",
        [](const py::dict& point, const py::dict& settings) {
          const Scene scene = make_sweep_scene(point_from(point), settings_from(settings));
          const FrictionLaw& law = scene.model.friction;
          const double nan = std::numeric_limits<double>::quiet_NaN();
          const bool paper = law.kind == FrictionLawKind::paper;
          return std::make_pair(paper ? law.mu_c : nan, paper ? law.s_c : nan);
        },
        py::arg("point"), py::arg("settings"),
        "Builds the point's scene (raises SceneError naming the key): the paper law's (mu_c, s_c) in effect, "
        "NaN for other laws (the row's mu_c and s_c columns).");
  m.def("run_sweep_point",
        [](const py::dict& point, const py::dict& settings) {
          const SweepPoint p = point_from(point);
          const SweepSettings s = settings_from(settings);
          SweepResult r;
          {
            py::gil_scoped_release release;
            r = run_sweep_point(p, s);
          }
          return result_dict(r);
        },
        py::arg("point"), py::arg("settings"),
        "Simulates one point as top_sim_sweep does: a dict with its CSV row (no newline), outcome, note, phi_star, "
        "phi_measured, tan_half_phi_measured, sim_seconds, cpu_seconds.");
}
