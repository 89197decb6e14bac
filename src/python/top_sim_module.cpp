// The compiled part of the Python package `top_sim` (top_sim._core, re-exported by top_sim/__init__.py): a thin
// adapter over the core (scenes, Simulator, stationary state, trajectories, the sweep's points).
// Simulation runs with the GIL released; each Simulator is owned by one thread at a time (a second thread gets
// RuntimeError instead of a data race), so many simulators run in parallel threads.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "top_sim/command_fields.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/format.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/stationary.hpp"
#include "top_sim/trajectory.hpp"

namespace py = pybind11;
using namespace top_sim;

namespace {

// ---- scenes -----------------------------------------------------------------------------------------------

// A Python value as YAML (the scene parser then checks every key exactly as for a file).
YAML::Node to_yaml(const py::handle& value) {
  if (py::isinstance<py::dict>(value)) {
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& item : py::reinterpret_borrow<py::dict>(value)) map[py::str(item.first).cast<std::string>()] = to_yaml(item.second);
    return map;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    YAML::Node seq(YAML::NodeType::Sequence);
    for (const auto& item : value) seq.push_back(to_yaml(item));
    return seq;
  }
  if (value.is_none()) return YAML::Node(YAML::NodeType::Null);
  if (py::isinstance<py::bool_>(value)) return YAML::Node(value.cast<bool>() ? "true" : "false");
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value))
    return YAML::Node(format_number(value.cast<double>()));  // reads back as the same double
  return YAML::Node(py::str(value).cast<std::string>());
}

// A path, a shipped scene's name ("default" -> <config>/scenes/default.yaml; the core's scene_path), or a dict.
Scene scene_from(const py::object& source) {
  if (py::isinstance<Scene>(source)) return source.cast<Scene>();
  if (py::isinstance<py::dict>(source)) return parse_scene(to_yaml(source), "<dict>", default_config_dir());
  return load_scene(scene_path(py::str(source).cast<std::string>()));  // also pathlib.Path
}

// ---- values -----------------------------------------------------------------------------------------------

// A NumPy copy of any indexable vector (Eigen vectors, the StateVector).
template <class V>
py::array_t<double> array(const V& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  for (py::ssize_t i = 0; i < a.size(); ++i) a.mutable_at(i) = v[i];
  return a;
}

py::object optional_fault(ContactFault f) { return f == ContactFault::none ? py::object(py::none()) : py::str(to_string(f)); }
py::object optional_end(EndState e) { return e == EndState::none ? py::object(py::none()) : py::str(to_string(e)); }

// Every field of the Snapshot (docs/interfaces.md), vectors as NumPy arrays in the plane frame.
py::dict snapshot_dict(const Snapshot& s) {
  py::dict d;
  d["t"] = s.t;
  d["alpha"] = s.alpha;
  d["tip_center"] = array(s.tip_center);
  d["com"] = array(s.com);
  d["orientation"] = array(Eigen::Vector4d(s.orientation.x(), s.orientation.y(), s.orientation.z(), s.orientation.w()));
  d["com_velocity"] = array(s.com_velocity);
  d["tip_velocity"] = array(s.tip_velocity);
  d["contact_point"] = array(s.contact_point);
  d["figure_axis"] = array(s.figure_axis);
  d["angular_velocity"] = array(s.angular_velocity);
  d["spin"] = s.spin;
  d["has_rotor"] = s.has_rotor;
  d["rotor_spin"] = s.rotor_spin;
  d["spin_phase"] = s.spin_phase;
  d["slip"] = s.slip;
  d["mu"] = s.mu;
  d["normal_force"] = s.normal_force;
  d["friction_force"] = array(s.friction_force);
  d["drilling_torque"] = s.drilling_torque;
  d["patch_radius"] = s.patch_radius;
  d["com_acceleration"] = array(s.com_acceleration);
  d["phi"] = s.phi;
  d["has_stationary_state"] = s.has_stationary_state;
  d["phi_star"] = s.has_stationary_state ? py::object(py::float_(s.phi_star)) : py::object(py::none());
  d["regime"] = to_string(s.regime);
  d["contact_mode"] = to_string(s.contact_mode);
  d["gap"] = s.gap;
  d["touching"] = s.touching;
  d["energy"] = s.energy;
  d["dissipated_work"] = s.dissipated_work;
  d["energy_residual"] = s.energy_balance_residual;
  d["fault"] = optional_fault(s.fault);
  d["fault_message"] = s.fault_message;
  d["end_state"] = optional_end(s.end_state);
  d["end_state_message"] = s.end_message;
  return d;
}

py::dict stationary_dict(const StationaryState& st) {
  py::dict d;
  d["exists"] = st.exists;
  d["reason"] = st.reason;
  d["phi_defined"] = st.phi_defined;
  d["slip"] = st.slip;
  d["slip_unstable"] = st.slip_unstable >= 0.0 ? py::object(py::float_(st.slip_unstable)) : py::object(py::none());
  d["phi"] = st.phi;
  d["rolling_speed"] = st.rolling_speed;
  d["sliding_speed"] = st.sliding_speed;
  d["figure_axis"] = array(st.f_hat);
  d["angular_velocity"] = array(st.omega);
  d["velocity"] = array(st.velocity);
  return d;
}

// ---- commands ---------------------------------------------------------------------------------------------

double number(const py::handle& v, const std::string& key) {
  if (!py::isinstance<py::float_>(v) && !py::isinstance<py::int_>(v))
    throw py::value_error(key + " = " + py::repr(v).cast<std::string>() + ": must be a number");
  return v.cast<double>();
}

// {"law": name, parameter: value, ...} with the scene file's keys (friction.hpp's table): a change the core applies
// over the law in force, where omitted parameters keep their values (top_sim::changed_law, the rule of every adapter).
FrictionChange friction_from(const py::handle& value) {
  if (!py::isinstance<py::dict>(value)) throw py::value_error("friction must be a dict {'law': ..., parameters}");
  FrictionChange change;
  const py::dict d = py::reinterpret_borrow<py::dict>(value);
  const std::string name = d.contains("law") ? py::str(d["law"]).cast<std::string>() : "";
  FrictionLawKind kind;
  if (!parse_friction_law_kind(name, kind))
    throw py::value_error("friction.law = '" + name + "': must be one of " + friction_law_names(", "));
  change.kind = kind;
  for (const auto& item : d) {
    const std::string key = py::str(item.first).cast<std::string>();
    if (key == "law") continue;
    const FrictionParameter* p = find_friction_parameter(key);
    if (key == kFrictionPointsKey && kind == kFrictionPointsLaw) {
      change.points.emplace();
      for (const auto& point : item.second) change.points->push_back(point.cast<std::pair<double, double>>());
    } else if (p != nullptr && p->law == kind) {
      change.given.emplace_back(p, number(item.second, "friction." + key));
    } else {
      throw py::key_error("friction." + key + ": law " + name + " reads " + friction_parameter_names(kind));
    }
  }
  return change;
}

// The keys of the command schema (command_fields.hpp) and friction; the core validates the values.
Command command_from(const py::dict& d) {
  Command c;
  for (const auto& item : d) {
    const std::string key = py::str(item.first).cast<std::string>();
    if (key == "friction") {
      c.friction = friction_from(item.second);
      continue;
    }
    const CommandField* field = find_command_field(key);
    if (field == nullptr)
      throw py::key_error("unknown command key '" + key + "' (allowed: " + command_field_names() + ", friction)");
    c.*(field->member) = number(item.second, key);
  }
  return c;
}

// ---- the simulator ----------------------------------------------------------------------------------------

class PySimulator {
 public:
  explicit PySimulator(const Scene& scene) : sim_(std::make_unique<Simulator>(scene)) {}

  // Exclusive use of the simulator by the calling thread; another thread's call raises instead of racing.
  std::unique_lock<std::mutex> own() {
    std::unique_lock<std::mutex> lock(busy_, std::try_to_lock);
    if (!lock.owns_lock()) throw std::runtime_error("this Simulator is in use by another thread (one thread owns it)");
    return lock;
  }

  py::dict step_to(double t) {
    auto lock = own();
    return advance(t);
  }

  py::dict run(double duration) {
    check_duration(duration);
    auto lock = own();  // one ownership for reading the time and advancing: no other thread in between
    return advance(sim_->time() + duration);
  }

  // Samples every 1/rate from now to now + duration (both included); stops early at a contact fault.
  py::dict trajectory(double duration, double rate) {
    check_duration(duration);
    if (!std::isfinite(rate) || rate <= 0.0)
      throw py::value_error("rate = " + format_number(rate) + ": must be finite and > 0 [1/s]");
    const auto& columns = trajectory_columns();
    std::vector<double> values;
    auto lock = own();
    {
      py::gil_scoped_release release;
      sample(duration, rate, values);
    }
    const std::size_t n = values.size() / columns.size();
    py::dict out;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      py::array_t<double> a(n);
      for (std::size_t k = 0; k < n; ++k) a.mutable_at(k) = values[k * columns.size() + c];
      out[columns[c].name] = a;
    }
    return out;
  }

  void apply(const py::dict& d) {
    const std::string error = sim_->submit(command_from(d));  // submit() may be called from any thread
    if (!error.empty()) throw py::value_error(error);
  }

  py::dict snapshot() {
    auto lock = own();
    return snapshot_dict(sim_->snapshot());
  }

  void reset() {
    auto lock = own();
    sim_->reset();
  }

  // Reads the simulator under ownership (another thread may be advancing it with the GIL released).
  template <class F>
  auto read(F f) {
    auto lock = own();
    return f(*sim_);
  }

 private:
  // Advances to t (the caller owns the simulator) with the GIL released; returns the snapshot.
  py::dict advance(double t) {
    if (!std::isfinite(t) || t < sim_->time())
      throw py::value_error("t = " + format_number(t) + ": must be finite and >= the current time " +
                            format_number(sim_->time()) + " [s]");
    {
      py::gil_scoped_release release;
      sim_->advance_to(t);
    }
    return snapshot_dict(sim_->snapshot());
  }

  static void check_duration(double duration) {
    if (!std::isfinite(duration) || duration < 0.0)
      throw py::value_error("duration = " + format_number(duration) + ": must be finite and >= 0 [s]");
  }

  void sample(double duration, double rate, std::vector<double>& values) {
    const auto& columns = trajectory_columns();
    const double t0 = sim_->time();
    const long n = last_sample_index(duration, rate);
    values.reserve(static_cast<std::size_t>(n + 1) * columns.size());
    for (long k = 0; k <= n; ++k) {
      if (k > 0) sim_->advance_to(sample_time(t0, k, rate));
      const Snapshot s = sim_->snapshot();
      for (const TrajectoryColumn& c : columns) values.push_back(c.value(s));
      if (sim_->stopped()) break;
    }
  }

  std::unique_ptr<Simulator> sim_;
  std::mutex busy_;
};

py::dict mode_seconds(PySimulator& p) {
  const auto seconds = p.read([](Simulator& s) { return s.mode_seconds(); });
  py::dict d;
  for (int m = 0; m < kContactModeCount; ++m) d[to_string(static_cast<ContactMode>(m))] = seconds[m];
  return d;
}

py::dict stats(PySimulator& p) {
  const StepperStats s = p.read([](Simulator& sim) { return sim.stats(); });
  py::dict d;
  d["steps"] = s.steps;
  d["rejected"] = s.rejected;
  d["rhs_evaluations"] = s.rhs_evaluations;
  d["layer_steps"] = p.read([](Simulator& sim) { return sim.layer_steps(); });
  return d;
}

// A read-only property: the getter's value, read under ownership of the simulator.
template <class R>
auto reader(R (Simulator::*get)() const) {
  return [get](PySimulator& p) { return p.read([get](Simulator& s) { return (s.*get)(); }); };
}

py::list command_field_list() {
  py::list out;
  for (const CommandField& f : command_fields()) {
    py::dict d;
    d["name"] = f.name;
    d["unit"] = f.unit;
    d["lower"] = f.range.lower;
    d["upper"] = f.range.upper;
    d["lower_open"] = f.range.lower_open;
    d["upper_open"] = f.range.upper_open;
    d["range"] = f.range_text;
    d["doc"] = f.doc;
    out.append(d);
  }
  return out;
}

void bind_scenes(py::module_& m) {
  py::register_exception<SceneError>(m, "SceneError", PyExc_ValueError);
  py::class_<Scene>(m, "Scene", "A validated scene (load it with top_sim.load_scene)")
      .def_readonly("source", &Scene::source)
      .def_readonly("duration", &Scene::duration)
      .def_readonly("warnings", &Scene::warnings)
      .def_property_readonly("method", [](const Scene& s) { return to_string(s.integrator.method); })
      .def_property_readonly("inclination", [](const Scene& s) { return s.model.plane.inclination; })
      .def_property_readonly("spin", [](const Scene& s) { return s.initial.spin; })
      .def("__repr__", [](const Scene& s) { return "<top_sim.Scene " + s.source + ">"; });

  m.def("load_scene", &scene_from, py::arg("source"),
        "A scene from a YAML file path, a scene name of the installed data ('default'), or a dict with the keys "
        "of a scene file; raises top_sim.SceneError naming the file, key, value and allowed range.");
  m.def("command_fields", &command_field_list,
        "The command schema (command_fields.hpp): one dict per field of Simulator.apply with its name, unit, limits "
        "(lower, upper, lower_open, upper_open; +-inf = none), the range as errors give it, and a doc line.");
  m.def("config_dir", &default_config_dir, "The data directory (tops/, planes/, scenes/) the module uses.");
  m.def("stationary_state",
        [](const py::object& source, const py::object& spin) {
          const Scene scene = scene_from(source);
          const double w = spin.is_none() ? scene.initial.spin : spin.cast<double>();
          return stationary_dict(stationary_state(scene.model, w));
        },
        py::arg("scene"), py::arg("spin") = py::none(),
        "The analytic sleeping state (physics.md section 5) of a scene at its initial spin or at `spin` [rad/s].");
}

// The trajectory columns and the names behind the regime and contact-mode codes.
void bind_constants(py::module_& m) {
  std::vector<std::string> names, units, regimes, modes;
  for (const TrajectoryColumn& c : trajectory_columns()) {
    names.push_back(c.name);
    units.push_back(c.unit);
  }
  for (int r = 0; r < kRegimeCount; ++r) regimes.push_back(to_string(static_cast<Regime>(r)));
  for (int c = 0; c < kContactModeCount; ++c) modes.push_back(to_string(static_cast<ContactMode>(c)));
  m.attr("COLUMNS") = names;
  m.attr("UNITS") = units;
  m.attr("REGIMES") = regimes;      // trajectory()['regime'] codes index this list
  m.attr("CONTACT_MODES") = modes;  // trajectory()['contact_mode'] codes index this list
}

void bind_simulator(py::module_& m) {
  py::class_<PySimulator>(m, "Simulator", "One top. Owned by one thread at a time; simulation releases the GIL.")
      .def(py::init([](const py::object& source) { return std::make_unique<PySimulator>(scene_from(source)); }),
           py::arg("scene"))
      .def("run", &PySimulator::run, py::arg("duration"), "Advances by `duration` [s]; returns the snapshot.")
      .def("step_to", &PySimulator::step_to, py::arg("t"), "Advances to simulated time t [s]; returns the snapshot.")
      .def("trajectory", &PySimulator::trajectory, py::arg("duration"), py::arg("rate"),
           "Samples every 1/rate [s] over `duration` (the current instant first): a dict of NumPy arrays, one per "
           "CSV column (top_sim.COLUMNS); regime and contact_mode as codes into REGIMES and CONTACT_MODES.")
      .def("apply", &PySimulator::apply, py::arg("command"),
           "Queues a command dict (inclination, spin, rotor_spin, rotor_coupling, static_friction, restitution, "
           "patch_radius, rolling_resistance, spin_drag, drag, friction={'law': ..., parameters}); "
           "it takes effect at the next step boundary. Raises ValueError naming the field, value and range.")
      .def("snapshot", &PySimulator::snapshot, "Every derived quantity of the current instant, as a dict.")
      .def("reset", &PySimulator::reset, "Back to the scene's initial state; time keeps running forward.")
      .def("stationary_state", [](PySimulator& p) { return stationary_dict(reader(&Simulator::stationary)(p)); },
           "The analytic sleeping state for the current inclination and spin.")
      .def_property_readonly("time", reader(&Simulator::time))
      .def_property_readonly("state", [](PySimulator& p) { return array(reader(&Simulator::state)(p)); })
      .def_property_readonly("contact_mode", [](PySimulator& p) { return to_string(reader(&Simulator::contact_mode)(p)); })
      .def_property_readonly("fault", [](PySimulator& p) { return optional_fault(reader(&Simulator::fault)(p)); })
      .def_property_readonly("fault_message", reader(&Simulator::fault_message))
      .def_property_readonly("end_state", [](PySimulator& p) { return optional_end(reader(&Simulator::end_state)(p)); })
      .def_property_readonly("end_message", reader(&Simulator::end_message))
      .def_property_readonly("mode_switch_count", reader(&Simulator::mode_switch_count))
      .def_property_readonly("mode_seconds", &mode_seconds)
      .def_property_readonly("stats", &stats)
      .def_property_readonly("max_energy_residual", reader(&Simulator::max_energy_residual));
}

}  // namespace

void bind_sweep(py::module_& m);  // sweep_module.cpp

PYBIND11_MODULE(_core, m) {
  m.doc() = "top_sim: a spinning top with a spherical tip on an inclined plane (the physics core of top_sim)";
  bind_scenes(m);
  bind_constants(m);
  bind_simulator(m);
  bind_sweep(m);
}
