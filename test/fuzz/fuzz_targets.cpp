// The fuzz targets of fuzz_targets.hpp: byte decoding, the simulator's invariants, the three targets.
#include "fuzz_targets.hpp"

#include <cxxabi.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>
#include <memory>
#include <typeinfo>
#include <vector>

#include "../core/finite_fields.hpp"
#include "top_sim/command.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace top_sim::fuzz {

namespace {

std::string config_dir() {
#ifdef TOP_SIM_FUZZ_CONFIG_DIR
  return TOP_SIM_FUZZ_CONFIG_DIR;
#else
  return default_config_dir();
#endif
}

std::string text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string type_name(const std::exception& e) {
  int status = 0;
  std::unique_ptr<char, void (*)(void*)> name(abi::__cxa_demangle(typeid(e).name(), nullptr, nullptr, &status),
                                              std::free);
  return status == 0 && name ? name.get() : typeid(e).name();
}

// With TOP_SIM_FUZZ_TRACE set, each decision is printed (to see what an input does: replay it with the variable set).
void trace(const std::string& line) {
  static const bool on = std::getenv("TOP_SIM_FUZZ_TRACE") != nullptr;
  if (on) std::fprintf(stderr, "[fuzz] %s\n", line.c_str());
}

std::string state_text(const StateVector& y) {
  std::string s;
  for (double v : y) s += (s.empty() ? "[" : ", ") + text(v);
  return s + "]";
}

// Values the number encoding can name in two bytes: the edges of double and of the inputs' ranges.
const double kSpecial[] = {0.0, -0.0, 1.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                           DBL_MAX, -DBL_MAX, DBL_MIN, std::numeric_limits<double>::denorm_min(),
                           -std::numeric_limits<double>::denorm_min(), 1.0e-300, 1.0e300, M_PI / 2,
                           std::nextafter(M_PI / 2, 0.0), M_PI, 1.0e-12, 1.0e-9, 0.5, 2.0, 1.0e-6};

// Reads an input front to back; past its end every byte is 0, so every input decodes to something.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }

  // A tag byte picks the encoding: raw IEEE bits, a special value, a decimal m 10^e, or a multiple of 1/16.
  double number() {
    switch (byte() % 4) {
      case 0: return raw_bits();
      case 1: return kSpecial[byte() % std::size(kSpecial)];
      case 2: return decimal();
      default: return static_cast<std::int8_t>(byte()) / 16.0;
    }
  }

  std::string word(std::size_t max_length) {
    std::string s(byte() % (max_length + 1), '\0');
    for (char& c : s) c = static_cast<char>(byte());
    return s;
  }

 private:
  double raw_bits() {
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits |= static_cast<std::uint64_t>(byte()) << (8 * i);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }

  // m 10^e with m a signed 16-bit integer and e in [-24, 23]: every physical value of the scenes, exactly rounded.
  double decimal() {
    const std::uint8_t lo = byte();
    const std::uint8_t hi = byte();
    const double m = static_cast<std::int16_t>(lo | (hi << 8));
    const int e = byte() % 48 - 24;
    return e < 0 ? m / std::pow(10.0, -e) : m * std::pow(10.0, e);
  }

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

// ---- the simulator's invariants ---------------------------------------------------------------------------

// "" when the simulator may publish its state: stopped with a named fault, or finite everywhere without one.
std::string check_simulator(const Simulator& sim, double t_begin, double t_end) {
  const double t = sim.time();
  if (!(t >= t_begin && t <= t_end))
    return "time " + text(t) + " s outside [" + text(t_begin) + ", " + text(t_end) + "]";
  const Snapshot s = sim.snapshot();
  if (sim.fault() != ContactFault::none) {
    if (sim.fault_message().empty()) return std::string("fault ") + to_string(sim.fault()) + " without a message";
    if (s.regime != Regime::contact_fault)
      return std::string("fault ") + to_string(sim.fault()) + " but regime " + to_string(s.regime);
    return "";
  }
  if (!all_finite(sim.state())) return "non-finite state without a fault at t = " + text(t) + ": " + state_text(sim.state());
  const std::string bad = top_sim_test::nonfinite_fields(s);
  if (!bad.empty())
    return "non-finite snapshot without a fault at t = " + text(t) + ": " + bad + "; state " + state_text(sim.state());
  if (s.fault != ContactFault::none)
    return std::string("the snapshot shows fault ") + to_string(s.fault) + " but the simulator has none at t = " +
           text(t);
  return "";
}

// Advances towards t_end one step or event per call (a budget of 0 s), at most kMaxSteps calls, checking after each.
std::string advance_checked(Simulator& sim, double t_end) {
  const double t_begin = sim.time();
  int calls = 0;
  while (calls < kMaxSteps && sim.fault() == ContactFault::none) {
    ++calls;
    const double before = sim.time();
    const bool done = sim.advance_to(t_end, 0.0);
    const std::string bad = check_simulator(sim, t_begin, t_end);
    if (!bad.empty()) return bad;
    if (done) break;
    if (!(sim.time() > before)) return "advance_to stopped short at t = " + text(before) + " without advancing";
  }
  trace("advanced to t = " + text(sim.time()) + " s in " + std::to_string(calls) + " calls, mode " +
        to_string(sim.contact_mode()) + ", fault " + to_string(sim.fault()) + " " + sim.fault_message());
  return "";
}

// A scene the loader admitted: a finite initial state, and a Simulator that runs it briefly to an admissible end.
std::string run_scene(const Scene& scene, double horizon) {
  const StateVector y0 = initial_state(scene);
  if (!all_finite(y0)) return "the loader admitted a non-finite initial state " + state_text(y0);
  try {
    Simulator sim(scene);
    std::string bad = check_simulator(sim, 0.0, 0.0);
    if (bad.empty()) bad = advance_checked(sim, std::min(horizon, scene.duration));
    return bad.empty() ? "" : "running the scene: " + bad;
  } catch (const std::exception& e) {
    return "the simulator threw " + type_name(e) + ": " + e.what();
  }
}

// A SceneError must say what is wrong beyond naming the file.
std::string check_scene_error(const SceneError& e) {
  const std::string message = e.what();
  if (e.file.empty() || message.size() <= e.file.size() + 2) return "SceneError without a problem: '" + message + "'";
  return "";
}

// parse_scene's outcome: "" for a SceneError with a message or a scene that runs; else the broken invariant.
std::string parse_and_run(const YAML::Node& root, const std::string& source, double horizon = kMaxSimulatedTime) {
  trace("scene:\n" + YAML::Dump(root));
  Scene scene;
  try {
    scene = parse_scene(root, source, config_dir());
  } catch (const SceneError& e) {
    trace(std::string("SceneError: ") + e.what());
    return check_scene_error(e);
  } catch (const std::exception& e) {
    return "parse_scene threw " + type_name(e) + " (not a SceneError): " + e.what();
  } catch (...) {
    return "parse_scene threw something that is not a std::exception";
  }
  return run_scene(scene, horizon);
}

// ---- the scenes the command and step targets start from ----------------------------------------------------

// `top:` and `friction:` given by file name become the file's mapping, so the step target can change their keys.
void inline_named(YAML::Node root, const char* key, const char* folder) {
  if (root[key] && root[key].IsScalar())
    root[key] = YAML::LoadFile(config_dir() + "/" + folder + "/" + root[key].Scalar() + ".yaml");
}

// The tilt at which a two-shape body stands on both shapes (h_0(c) = h_1(c), physics.md 13.4), shapes[1] not below
// the plane: a start on the pair solve's stuck and slipping pairs instead of a fall onto them.
double tilt_on_both(const ShapeSet& shapes) {
  auto below = [&shapes](double c) { return shape_height(shapes.shape[0], c) - shape_height(shapes.shape[1], c); };
  double hi = 1.0;  // scan down from upright for the first sign change, then bisect it
  for (double lo = 0.99; lo >= -1.0; lo -= 0.01, hi -= 0.01) {
    if ((below(lo) > 0.0) == (below(hi) > 0.0)) continue;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      ((below(mid) > 0.0) == (below(lo) > 0.0) ? lo : hi) = mid;
    }
    return std::acos(below(lo) <= 0.0 ? lo : hi);
  }
  return 0.0;
}

// Every scene of config/scenes (kSceneNames; the first seven in the order of the first corpus, which names them by
// index), then variants: the default with the adiabatic model, the static normal force and the auto model, the
// Hertz patch of spin_down under the auto model (a handover on a patch), and the two-shape tops started on both.
const char* const kSceneFiles[] = {
    "default", "gyro_reversal", "coulomb", "hopping", "ball", nullptr, nullptr, "euler_disk", "fig2_spin100",
    "fig2_spin200", "fig2_spin400", "fig5_linearized", "frictionless", "phase_reversed200", "phase_spin100",
    "phase_spin200", "phase_spin400", "reversed_spin", "spin_down", "supercritical", "tippe_top",
    "tippe_top_contensou", "tippe_top_rolling", "tippe_top_stem", "tippe_top_tumbling", "top_life", "upright"};

const std::vector<YAML::Node>& base_nodes() {
  static const std::vector<YAML::Node> nodes = [] {
    std::vector<YAML::Node> out;
    auto file = [](const char* name) {
      YAML::Node n = YAML::LoadFile(config_dir() + "/scenes/" + name + ".yaml");
      inline_named(n, "top", "tops");
      inline_named(n, "friction", "planes");
      return n;
    };
    auto variant = [&out, &file](const char* name, const char* section, const char* key, const char* value) {
      out.push_back(file(name));
      out.back()[section][key] = value;
    };
    for (const char* name : kSceneFiles) {
      if (name) out.push_back(file(name));
      else if (out.size() == 5) variant("default", "model", "kind", "adiabatic");
      else variant("default", "model", "normal_force", "static");
    }
    variant("default", "model", "kind", "auto");
    variant("spin_down", "model", "kind", "auto");
    out.back()["model"]["auto_tolerance"] = 1.0e-4;
    for (const char* name : {"top_life", "tippe_top_stem"}) {
      out.push_back(file(name));
      const Scene scene = parse_scene(out.back(), name, config_dir());
      out.back()["initial"]["tilt"] = tilt_on_both(scene.model.shapes);
    }
    return out;
  }();
  return nodes;
}

const std::vector<Scene>& base_scenes() {
  static const std::vector<Scene> scenes = [] {
    std::vector<Scene> out;
    for (const YAML::Node& node : base_nodes()) out.push_back(parse_scene(node, "base_scene.yaml", config_dir()));
    return out;
  }();
  return scenes;
}

// ---- command target ---------------------------------------------------------------------------------------

// A friction law as a TopCommand carries it: a law name (an unknown one is refused by the adapter: false), every
// scalar parameter of every law, and up to 7 table points.
bool read_friction(Bytes& in, FrictionLaw& law) {
  const std::uint8_t pick = in.byte();
  const std::string name = pick < 0xE0 ? kFrictionLawNames[pick % std::size(kFrictionLawNames)].name : in.word(12);
  if (!parse_friction_law_kind(name, law.kind)) return false;
  for (const FrictionParameter& p : kFrictionParameters) law.*p.member = in.number();
  if (law.kind == kFrictionPointsLaw) {
    const int n = in.byte() % 8;
    for (int i = 0; i < n; ++i) {
      const double s = in.number();
      law.points.emplace_back(s, in.number());
    }
  }
  return true;
}

// One Command: a byte of set_ flags, then the value of each set field; false when the adapter would refuse it.
bool read_command(Bytes& in, Command& c) {
  const std::uint8_t set = in.byte();
  if (set & 0x01) c.inclination = in.number();
  if (set & 0x02) c.spin = in.number();
  if (set & 0x04) c.rotor_spin = in.number();
  if (set & 0x08) c.rotor_coupling = in.number();
  if (set & 0x10) {
    FrictionLaw law;
    if (!read_friction(in, law)) return false;
    FrictionChange change;  // the law's own parameters, as a TopCommand gives them
    change.kind = law.kind;
    for (const FrictionParameter& p : kFrictionParameters)
      if (p.law == law.kind) change.given.emplace_back(&p, law.*p.member);
    if (law.kind == kFrictionPointsLaw) change.points = law.points;
    c.friction = change;
  }
  if (set & 0x20) c.static_friction = in.number();
  if (set & 0x40) c.restitution = in.number();
  if (set & 0x80) {  // a second flag byte: the finite contact's and the air's fields (physics.md section 12)
    const std::uint8_t more = in.byte();
    if (more & 0x01) c.patch_radius = in.number();
    if (more & 0x02) c.rolling_resistance = in.number();
    if (more & 0x04) c.spin_drag = in.number();
    if (more & 0x08) c.drag = in.number();
  }
  return true;
}

// The model after an accepted command, applied alone, holds the command's values.
std::string check_applied(const Command& c, const Model& m) {
  auto same = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  if (c.inclination && !same(m.plane.inclination, *c.inclination)) return "inclination not applied";
  if (c.friction && c.friction->kind && m.friction.kind != *c.friction->kind) return "friction law not applied";
  if (c.static_friction && !(m.contact.static_friction && same(*m.contact.static_friction, *c.static_friction)))
    return "static_friction not applied";
  if (c.restitution && !same(m.contact.restitution, *c.restitution)) return "restitution not applied";
  if (c.rotor_coupling && !same(m.top.rotor.coupling, *c.rotor_coupling)) return "rotor_coupling not applied";
  if (c.patch_radius && (m.finite_contact.hertz || !same(m.finite_contact.patch_radius, *c.patch_radius)))
    return "patch_radius not applied";
  if (c.rolling_resistance && !same(m.finite_contact.rolling_resistance, *c.rolling_resistance))
    return "rolling_resistance not applied";
  if (c.spin_drag && !same(m.air.spin_drag, *c.spin_drag)) return "spin_drag not applied";
  if (c.drag && !same(m.air.drag, *c.drag)) return "drag not applied";
  return "";
}

bool same_state(const StateVector& a, const StateVector& b) { return std::memcmp(a.data(), b.data(), sizeof a) == 0; }

// A simulator that gets the commands and a twin that gets only the accepted ones: rejected ones must change nothing.
struct CommandRun {
  explicit CommandRun(const Scene& scene) : sim(scene), twin(scene) {}
  Simulator sim, twin;

  // Both advance to t_end in the same steps; the commanded one is checked, then they must agree bit for bit.
  std::string advance(double t_end) {
    std::string bad = advance_checked(sim, t_end);
    advance_checked(twin, t_end);
    if (bad.empty() && (!same_state(sim.state(), twin.state()) || sim.time() != twin.time() ||
                        sim.fault() != twin.fault()))
      bad = "a rejected command changed the run: state " + state_text(sim.state()) + " against " +
            state_text(twin.state());
    return bad;
  }

  // submit() gives validate()'s verdict; a rejection has a message and leaves the state as it was.
  std::string submit(const Command& c, bool& accepted) {
    const StateVector before = sim.state();
    const std::string expected = validate(c, sim.model());
    const bool stopped = sim.stopped();
    const std::string error = sim.submit(c);
    accepted = error.empty();
    trace("command " + std::string(accepted ? "accepted" : "rejected: " + error));
    if (stopped) {  // a stopped run refuses every command with why (its time no longer moves)
      if (accepted || error.find("reset it before commanding it") == std::string::npos)
        return "a stopped run answered '" + error + "' to a command";
    } else if (error != expected) {
      return "submit() said '" + error + "' but validate() '" + expected + "'";
    }
    if (!error.empty()) return same_state(before, sim.state()) ? "" : "a rejected command changed the state at once";
    const std::string twin_error = twin.submit(c);
    return twin_error.empty() ? "" : "the twin rejected an accepted command: " + twin_error;
  }
};

// Submits one command and, unless queued with the next ones, advances to t_end and checks that it was applied.
std::string command_round(CommandRun& run, const Command& c, bool queued, double t_end) {
  bool accepted = false;
  std::string bad = run.submit(c, accepted);
  if (!bad.empty() || queued) return bad;
  const bool running = !run.sim.stopped();  // a fault or an end state (at_rest, lying_flat): nothing is applied
  bad = run.advance(t_end);
  if (bad.empty() && accepted && running) bad = check_applied(c, run.sim.model());
  return bad;
}

// ---- step target ------------------------------------------------------------------------------------------

const char* const kMethods[] = {"euler",       "semi_implicit_euler", "rk4",           "dopri5",
                                "rosenbrock4", "switching",           "implicit_midpoint", "fitted_midpoint"};

// Overwrites the keys of initial:, top.rotor.spin and integrator: that the two flag bytes select; flag 0x8000 adds
// two more flag bytes for the keys of bodies of shapes, the patch, the air and the auto model (write_contact).
unsigned write_state(Bytes& in, YAML::Node root) {
  const unsigned set = in.byte() | (static_cast<unsigned>(in.byte()) << 8);
  YAML::Node ic = root["initial"];
  auto pair = [&in] { return std::vector<double>{in.number(), in.number()}; };
  if (set & 0x0001) ic["start"] = in.byte() % 2 ? "stationary" : "tilted";
  if (set & 0x0002) ic["tilt"] = in.number();
  if (set & 0x0004) ic["tilt_azimuth"] = in.number();
  if (set & 0x0008) ic["spin"] = in.number();
  if (set & 0x0010) ic["angular_velocity_transverse"] = pair();
  if (set & 0x0020) ic["position"] = pair();
  if (set & 0x0040) ic["velocity"] = pair();
  if (set & 0x0080) ic["gap"] = in.number();
  if (set & 0x0100) ic["gap_rate"] = in.number();
  if ((set & 0x0200) && root["top"].IsMap() && root["top"]["rotor"]) root["top"]["rotor"]["spin"] = in.number();
  YAML::Node integrator = root["integrator"];
  if (set & 0x0400) integrator["method"] = kMethods[in.byte() % std::size(kMethods)];
  if (set & 0x0800) integrator["dt"] = in.number();
  if (set & 0x1000) integrator["rtol"] = in.number();
  if (set & 0x2000) integrator["atol"] = in.number();
  if (set & 0x4000) integrator["max_dt"] = in.number();
  return set & 0x8000 ? in.byte() | (static_cast<unsigned>(in.byte()) << 8) : 0u;
}

const char* const kModelKinds[] = {"full", "adiabatic", "auto"};

// top.shapes anew: 1-3 spheres or rims (the loader takes 1-4, the simulator 1-2), each offset and radius fuzzed.
void write_shapes(Bytes& in, YAML::Node top) {
  top.remove("tip_radius");
  top.remove("com_offset");
  YAML::Node list(YAML::NodeType::Sequence);
  const int n = 1 + in.byte() % 3;
  for (int i = 0; i < n; ++i) {
    YAML::Node shape, item;
    const bool rim = in.byte() % 2;
    shape["offset"] = in.number();
    shape["radius"] = in.number();
    item[rim ? "rim" : "sphere"] = shape;
    list.push_back(item);
  }
  top["shapes"] = list;
}

// One key (offset or radius) of one of the body's shapes; a top without shapes is left as it is.
void write_shape_key(Bytes& in, YAML::Node top, const char* key) {
  const std::uint8_t pick = in.byte();
  const double value = in.number();
  YAML::Node list = top["shapes"];
  if (!list.IsSequence() || list.size() == 0) return;
  YAML::Node item = list[pick % list.size()];
  if (item.IsMap() && item.size() == 1) item.begin()->second[key] = value;
}

// The keys of physics.md sections 12 and 13 that the flags of write_state's third and fourth bytes select;
// returns the simulated time to run (flag 0x4000: 1 ms to 10 s, still at most kMaxSteps steps).
double write_contact(Bytes& in, YAML::Node root, unsigned set) {
  YAML::Node top = root["top"], contact = root["contact"], air = root["air"], model = root["model"];
  if (set & 0x0001) write_shapes(in, top);
  if (set & 0x0002) write_shape_key(in, top, "offset");
  if (set & 0x0004) write_shape_key(in, top, "radius");
  if (set & 0x0008) {
    if (in.byte() % 2) contact["patch_radius"] = in.number();
    else contact["patch_radius"] = "hertz";
  }
  if (set & 0x0010) contact["patch_pressure"] = in.byte() % 2 ? "uniform" : "hertz";
  if (set & 0x0020) contact["drilling_law"] = in.byte() % 2 ? "elliptic" : "exact";
  if (set & 0x0040) contact["rolling_resistance"] = in.number();
  if (set & 0x0080) air["spin_drag"] = in.number();
  if (set & 0x0100) air["drag"] = in.number();
  if (set & 0x0200) model["kind"] = kModelKinds[in.byte() % std::size(kModelKinds)];
  if (set & 0x0400) model["auto_tolerance"] = in.number();
  if (set & 0x0800) {
    top["young_modulus"] = in.number();
    top["poisson_ratio"] = in.number();
  }
  if (set & 0x1000) contact["restitution"] = in.number();
  if (set & 0x2000) {
    top["inertia_axial"] = in.number();
    top["inertia_transverse"] = in.number();
  }
  const double horizon = set & 0x4000 ? kMaxSimulatedTime * std::pow(10.0, in.byte() % 5) : kMaxSimulatedTime;
  if (set & 0x8000) root["friction"]["static"] = in.number();
  return horizon;
}

}  // namespace

std::string scene_loader(const std::uint8_t* data, std::size_t size) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const std::exception& e) {
    trace(std::string("not YAML: ") + e.what());
    return "";  // not YAML: load_scene() reports it as a SceneError before parse_scene is reached
  }
  return parse_and_run(root, "fuzz_scene.yaml");
}

std::string command(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const std::vector<Scene>& scenes = base_scenes();
  const Scene& scene = scenes[in.byte() % scenes.size()];
  const double warmup = in.byte() / 255.0;    // fraction of a slice simulated before the first command
  const std::uint8_t plan = in.byte();
  const int count = 1 + plan % 3;
  const bool queued = (plan & 0x80) != 0;     // all submitted before one advance, each checked alone
  const double slice = kMaxSimulatedTime / 4;  // of simulated time per command
  try {
    CommandRun run(scene);
    std::string bad;
    if (warmup > 0.0) bad = run.advance(warmup * slice);
    for (int i = 0; i < count && bad.empty(); ++i) {
      Command c;
      if (read_command(in, c))
        bad = command_round(run, c, queued, (i + 2) * slice);
      else
        trace("command refused by its friction law's name");
    }
    if (bad.empty() && queued) bad = run.advance(kMaxSimulatedTime);
    return bad;
  } catch (const std::exception& e) {
    return "the simulator threw " + type_name(e) + ": " + e.what();
  }
}

std::string step(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const std::vector<YAML::Node>& nodes = base_nodes();
  YAML::Node root = YAML::Clone(nodes[in.byte() % nodes.size()]);
  const unsigned more = write_state(in, root);
  const double horizon = write_contact(in, root, more);
  return parse_and_run(root, "fuzz_step.yaml", horizon);
}

std::vector<std::string> scene_files() {
  std::vector<std::string> names;
  for (const char* name : kSceneFiles)
    if (name) names.push_back(name);
  return names;
}

void require(const char* target, const std::string& verdict) {
  if (verdict.empty()) return;
  std::fprintf(stderr, "top_sim fuzz target %s: invariant broken: %s\n", target, verdict.c_str());
  std::abort();
}

}  // namespace top_sim::fuzz
