// Scene files (docs/interfaces.md): strict loading, every key checked, errors name file, key, value and range.
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <sstream>

#include "top_sim/adiabatic.hpp"
#include "top_sim/command_fields.hpp"
#include "top_sim/contact_modes.hpp"
#include "top_sim/contact_shapes.hpp"
#include "energy.hpp"
#include "top_sim/format.hpp"
#include "top_sim/limits.hpp"
#include "shape_motion.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

namespace {

bool is_dir(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_directory(path, ec);
}

std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

std::string show(const YAML::Node& n) {
  if (n.IsScalar()) return "'" + n.Scalar() + "'";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a mapping";
  return "null";
}

std::string fmt(double v) { return format_number(v); }  // full precision: "6e-06 must be <= 6e-06" never again

// Reads one YAML mapping, remembering which keys were consumed so leftovers are reported as unknown.
class Section {
 public:
  Section(const YAML::Node& node, std::string file, std::string path)
      : node_(node), file_(std::move(file)), path_(std::move(path)) {
    if (node_ && !node_.IsNull() && !node_.IsMap())
      throw SceneError(file_, path_, show(node_) + " is not a mapping of keys");
    check_keys();
  }

  bool has(const char* key) {
    seen_.insert(key);
    return node_ && node_.IsMap() && node_[key] && !node_[key].IsNull();
  }
  YAML::Node raw(const char* key) {
    seen_.insert(key);
    return node_ && node_.IsMap() ? node_[key] : YAML::Node();
  }

  double number(const char* key, double def, const std::function<bool(double)>& ok, const std::string& range) {
    if (!has(key)) return def;
    return to_number(node_[key], join(path_, key), ok, range);
  }

  double to_number(const YAML::Node& n, const std::string& key, const std::function<bool(double)>& ok,
                   const std::string& range) const {
    double v;
    try {
      if (!n.IsScalar()) throw YAML::BadConversion(n.Mark());
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      throw SceneError(file_, key, show(n) + " is not a number; must be " + range);
    }
    if (!std::isfinite(v) || !ok(v)) throw SceneError(file_, key, fmt(v) + " is out of range; must be " + range);
    if (std::fpclassify(v) == FP_SUBNORMAL)  // below 2.2e-308: products underflow to 0 (a mass 1e-310 gives N = 0)
      throw SceneError(file_, key, fmt(v) + " is subnormal (0 < |v| < " + fmt(DBL_MIN) + "); must be " + range +
                                       " and 0 or at least " + fmt(DBL_MIN) + " in magnitude");
    return v;
  }

  std::string word(const char* key, const std::string& def, const std::vector<std::string>& allowed) {
    if (!has(key)) return def;
    const YAML::Node n = node_[key];
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : " | ") + a;
    if (!n.IsScalar()) throw SceneError(file_, join(path_, key), show(n) + " is not one of " + list);
    const std::string v = n.Scalar();
    for (const auto& a : allowed)
      if (v == a) return v;
    throw SceneError(file_, join(path_, key), "'" + v + "' is not one of " + list);
  }

  Eigen::Vector2d pair(const char* key, const Eigen::Vector2d& def,
                       const std::function<bool(double)>& ok = [](double) { return true; },
                       const std::string& range = "a finite number") {
    if (!has(key)) return def;
    const YAML::Node n = node_[key];
    const std::string k = join(path_, key);
    if (!n.IsSequence() || n.size() != 2) throw SceneError(file_, k, show(n) + " must be a list of 2 numbers");
    return {to_number(n[0], k + "[0]", ok, range), to_number(n[1], k + "[1]", ok, range)};
  }

  // Every key present must have been read by now.
  void finish() const {
    if (!node_ || !node_.IsMap()) return;
    for (const auto& kv : node_) {
      const std::string key = kv.first.Scalar();
      if (!seen_.count(key)) {
        std::string known;
        for (const auto& s : seen_) known += (known.empty() ? "" : ", ") + s;
        throw SceneError(file_, join(path_, key), "unknown key (known here: " + known + ")");
      }
    }
  }

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }

 private:
  // Keys are words, each given once (YAML readers disagree on which duplicate wins: refuse them all).
  void check_keys() const {
    if (!node_ || !node_.IsMap()) return;
    std::set<std::string> keys;
    for (const auto& kv : node_) {
      if (!kv.first.IsScalar())
        throw SceneError(file_, path_, show(kv.first) + " is not a valid key (keys are words, e.g. mass)");
      if (!keys.insert(kv.first.Scalar()).second)
        throw SceneError(file_, join(path_, kv.first.Scalar()), "given twice (each key once)");
    }
  }

  YAML::Node node_;
  std::string file_, path_;
  std::set<std::string> seen_;
};

const auto positive = [](double v) { return v > 0.0; };
const auto non_negative = [](double v) { return v >= 0.0; };
const auto finite = [](double) { return true; };
const auto spin_range = [](double v) { return std::abs(v) <= kMaxSpin; };
const std::string kSpinRange = "in [-" + format_number(kMaxSpin) + ", " + format_number(kMaxSpin) + "] [rad/s] (top_sim's spin limit)";

// `top:` and `friction:` may name a file in <config>/tops or <config>/planes instead of giving a mapping.
YAML::Node resolve_named(const YAML::Node& n, const std::string& file, const std::string& key,
                         const std::string& config_dir, const std::string& folder, std::string& source) {
  source = file;
  if (!n || !n.IsScalar()) return n;
  const std::string name = n.Scalar();
  const std::string dir = config_dir.empty() ? default_config_dir() : config_dir;
  if (dir.empty())
    throw SceneError(file, key, "'" + name + "' names a file in " + folder +
                                    "/ but no data directory was found (set TOP_SIM_CONFIG_DIR or give a mapping)");
  const std::string path = dir + "/" + folder + "/" + name + ".yaml";
  if (is_dir(path)) throw SceneError(file, key, "'" + name + "' names " + path + ", a directory, not a file");
  try {
    source = path;
    return YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw SceneError(file, key, "'" + name + "' names no file " + path + " (give a mapping or a file name in " +
                                    dir + "/" + folder + "/)");
  } catch (const YAML::Exception& e) {
    throw SceneError(path, "", std::string("not valid YAML: ") + e.what());
  } catch (const std::exception& e) {  // e.g. an unreadable file
    throw SceneError(path, "", std::string("cannot read: ") + e.what());
  }
}

// young_modulus and poisson_ratio of a top or a plane file (physics.md section 12): both or neither.
Material read_material(Section& s) {
  Material m;
  m.young_modulus = s.number("young_modulus", 0.0, positive, "> 0 [Pa]");
  m.poisson_ratio = s.number("poisson_ratio", 0.0, [](double v) { return v > -1.0 && v <= 0.5; }, "in (-1, 0.5]");
  if (s.has("poisson_ratio") != s.has("young_modulus"))
    throw SceneError(s.file(), join(s.path(), s.has("young_modulus") ? "poisson_ratio" : "young_modulus"),
                     "required with " + join(s.path(), s.has("young_modulus") ? "young_modulus" : "poisson_ratio") +
                         " (a material needs both)");
  return m;
}

// A shape's name: a plain identifier (letters, digits, '_', not starting with a digit) of at most 15 characters.
ShapeName read_shape_name(const YAML::Node& n, const std::string& file, const std::string& key) {
  const std::string v = n.IsScalar() ? n.Scalar() : "";
  const bool plain = !v.empty() && v.size() < kShapeNameSize && !std::isdigit(static_cast<unsigned char>(v[0])) &&
                     std::all_of(v.begin(), v.end(), [](char c) {
                       return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                     });
  if (!plain)
    throw SceneError(file, key, (n.IsScalar() ? "'" + v + "'" : show(n)) + " is not a plain identifier; must be 1 to " +
                                    std::to_string(kShapeNameSize - 1) +
                                    " letters, digits or '_', not starting with a digit (e.g. crown)");
  ShapeName name{};
  std::copy(v.begin(), v.end(), name.begin());
  return name;
}

// One item of top.shapes: {sphere: {offset, radius, name}} or {rim: {offset, radius, name}}.
ContactShape read_shape(const YAML::Node& item, const std::string& file, const std::string& key) {
  if (!item.IsMap() || item.size() != 1)
    throw SceneError(file, key, show(item) + " must be a mapping of one key, sphere or rim");
  const std::string kind = item.begin()->first.IsScalar() ? item.begin()->first.Scalar() : "";
  if (kind != "sphere" && kind != "rim")
    throw SceneError(file, join(key, kind.empty() ? show(item.begin()->first) : kind), "unknown shape kind (known: sphere, rim)");
  Section s(item.begin()->second, file, join(key, kind));
  for (const char* k : {"offset", "radius"})
    if (!s.has(k)) throw SceneError(file, join(s.path(), k), "required");
  ContactShape shape;
  shape.kind = kind == "sphere" ? ShapeKind::sphere : ShapeKind::rim;
  shape.offset = s.number("offset", 0.0, finite, "a finite number [m] (the centre's distance from the centre of mass "
                                                 "along the figure axis)");
  shape.radius = s.number("radius", 0.0, positive, "> 0 [m]");
  if (s.has("name")) shape.name = read_shape_name(s.raw("name"), file, join(s.path(), "name"));
  s.finish();
  return shape;
}

// top.shapes (physics.md section 13) replaces tip_radius and com_offset; a first sphere is the tip sphere itself.
ShapeSet read_shapes(Section& s, const std::string& file, Top& top) {
  ShapeSet shapes;
  const std::string key = join(s.path(), "shapes");
  for (const char* k : {"tip_radius", "com_offset"})
    if (s.has(k)) throw SceneError(file, join(s.path(), k), "not with " + key + " (the shapes replace tip_radius and com_offset)");
  const YAML::Node list = s.raw("shapes");
  if (!list.IsSequence() || list.size() == 0 || list.size() > kMaxShapes)
    throw SceneError(file, key, (list.IsSequence() ? "a list of " + std::to_string(list.size()) + " shapes" : show(list)) +
                                    " is out of range; must be a list of 1 to " + std::to_string(kMaxShapes) +
                                    " shapes, each {sphere: {offset, radius}} or {rim: {offset, radius}}");
  for (std::size_t i = 0; i < list.size(); ++i)
    shapes.shape[i] = read_shape(list[i], file, key + "[" + std::to_string(i) + "]");
  shapes.count = list.size();
  shapes.active = shapes_active(shapes);
  // The state's reference point (shape_motion.hpp): the first sphere's centre, else the centre of mass.
  const bool tip = shapes.shape[0].kind == ShapeKind::sphere;
  top.tip_radius = tip ? shapes.shape[0].radius : 0.0;
  top.com_offset = tip ? -shapes.shape[0].offset : 0.0;
  return shapes;
}

// A rim marks the body's widest reach: all its mass lies within rho_max of the axis, so I_f <= m rho_max^2.
void check_inertia_within_shapes(const Top& top, const ShapeSet& shapes, const std::string& file) {
  double reach = 0.0;
  bool rim = false;
  for (std::size_t k = 0; k < shapes.count; ++k) {
    reach = std::max(reach, shapes.shape[k].radius);
    rim = rim || shapes.shape[k].kind == ShapeKind::rim;
  }
  if (rim && top.inertia_axial > top.mass * reach * reach)
    throw SceneError(file, "top.inertia_axial",
                     fmt(top.inertia_axial) + " is out of range; must be <= mass * rho_max^2 = " +
                         fmt(top.mass * reach * reach) + " (no body within its shapes' reach of " + fmt(reach) +
                         " m from the axis has more)");
}

Top read_top(const YAML::Node& node, const std::string& file, double& rotor_spin, ShapeSet& shapes) {
  Section s(node, file, "top");
  Top top;
  top.mass = s.number("mass", top.mass, positive, "> 0 [kg]");
  if (s.has("shapes")) {
    shapes = read_shapes(s, file, top);
  } else {
    top.tip_radius = s.number("tip_radius", top.tip_radius, non_negative, ">= 0 [m]");
    top.com_offset = s.number("com_offset", top.com_offset, finite, "a finite number [m] (0: a ball)");
  }
  top.inertia_axial = s.number("inertia_axial", top.inertia_axial, positive, "> 0 [kg m^2]");
  top.inertia_transverse = s.number("inertia_transverse", top.inertia_transverse, positive, "> 0 [kg m^2]");
  if (top.inertia_axial > 2.0 * top.inertia_transverse)
    throw SceneError(file, "top.inertia_axial",
                     fmt(top.inertia_axial) + " is out of range; must be <= 2 * inertia_transverse = " +
                         fmt(2.0 * top.inertia_transverse) + " for a rigid axisymmetric body");
  check_inertia_within_shapes(top, shapes, file);
  // pi: the body is only its sphere and nothing else can touch the plane (a tippe top turns over).
  top.max_tilt = s.number("max_tilt", top.max_tilt, [](double v) { return v > 0.0 && v <= M_PI; }, "in (0, pi] [rad]");
  if (s.has("rotor")) {
    Section r(s.raw("rotor"), file, "top.rotor");
    top.has_rotor = true;
    const double I_f = top.inertia_axial;
    top.rotor.inertia_axial = r.number("inertia_axial", 0.0, [I_f](double v) { return v > 0.0 && v < I_f; },
                                       "in (0, top.inertia_axial = " + fmt(I_f) + ") [kg m^2]");
    if (!r.has("inertia_axial")) throw SceneError(file, "top.rotor.inertia_axial", "required when top.rotor is given");
    top.rotor.coupling = r.number("coupling", 0.0, non_negative, ">= 0 [N m s]");
    rotor_spin = r.number("spin", 0.0, spin_range, kSpinRange);
    r.finish();
  }
  top.material = read_material(s);
  s.finish();
  return top;
}

Plane read_plane(Section& root, const std::string& file) {
  Section p(root.raw("plane"), file, "plane");
  const double alpha = p.number("inclination", 0.1, admissible_inclination,
                                "in (-pi/2, pi/2) [rad]");
  const double g = p.number("gravity", 9.81, positive, "> 0 [m/s^2]");
  p.finish();
  return make_plane(alpha, g);
}

// model.normal_force and model.kind; the adiabatic model is checked against the plane and friction already read.
void read_model_options(Section& root, const std::string& file, Model& model) {
  Section m(root.raw("model"), file, "model");
  model.normal_force = m.word("normal_force", "constrained", {"constrained", "static"}) == "static"
                           ? NormalForceModel::static_approximation
                           : NormalForceModel::constrained;
  const std::string kind = m.word("kind", "full", {"full", "adiabatic", "auto"});
  model.kind = kind == "adiabatic" ? ModelKind::adiabatic : ModelKind::full;
  model.automatic.enabled = kind == "auto";
  if (m.has("auto_tolerance") && !model.automatic.enabled)
    throw SceneError(file, "model.auto_tolerance", "only with model.kind: auto (kind is " + kind + ")");
  model.automatic.position_tolerance = m.number("auto_tolerance", model.automatic.position_tolerance, positive,
                                                "> 0 and finite [m]");
  m.finish();
  if (model.kind == ModelKind::adiabatic) {
    const std::string e = adiabatic_validity(model);
    if (!e.empty()) throw SceneError(file, "model.kind", e);
  }
}

// contact.* of physics.md section 9, checked against the normal-force model and friction.static already read.
void read_contact(Section& root, const std::string& file, Model& model) {
  Section c(root.raw("contact"), file, "contact");
  ContactSettings& cs = model.contact;
  cs.restitution = c.number("restitution", cs.restitution, [](double v) { return v >= 0.0 && v <= 1.0; }, "in [0, 1]");
  cs.stick_speed = c.number("stick_speed", cs.stick_speed, positive, "> 0 [m/s]");
  cs.settle_speed = c.number("settle_speed", cs.settle_speed, positive, "> 0 [m/s]");
  FiniteContact& fc = model.finite_contact;
  if (c.has("patch_radius") && c.raw("patch_radius").IsScalar() && c.raw("patch_radius").Scalar() == "hertz") {
    fc.hertz = true;
    fc.effective_modulus = effective_modulus(model.top.material, model.plane_material);
    if (!model.top.material.given() || !model.plane_material.given())
      throw SceneError(file, "contact.patch_radius",
                       "'hertz' needs both materials: top.young_modulus and top.poisson_ratio (given: " +
                           std::string(model.top.material.given() ? "yes" : "no") +
                           "), and the plane file's (friction's) young_modulus and poisson_ratio (given: " +
                           (model.plane_material.given() ? "yes" : "no") + ")");
  } else {
    fc.patch_radius = c.number("patch_radius", 0.0, [](double v) { return v >= 0.0 && v <= kMaxPatchRadius; },
                               "in [0, 1] [m], or hertz");
  }
  fc.pressure = c.word("patch_pressure", "hertz", {"hertz", "uniform"}) == "uniform" ? PatchPressure::uniform
                                                                                     : PatchPressure::hertz;
  fc.law = c.word("drilling_law", "exact", {"exact", "elliptic"}) == "elliptic" ? DrillingLaw::elliptic
                                                                                : DrillingLaw::exact;
  fc.rolling_resistance = c.number("rolling_resistance", 0.0, non_negative, ">= 0 [m]");
  c.finish();
  // The static normal force keeps the paper's permanent slipping contact: no rolling, no bounce.
  if (model.normal_force == NormalForceModel::static_approximation) {
    if (cs.static_friction && *cs.static_friction > 0.0)
      throw SceneError(file, "friction.static",
                       fmt(*cs.static_friction) + " > 0 needs rolling, but model.normal_force = static keeps a "
                       "permanent slipping contact (physics.md section 9); use model.normal_force: constrained "
                       "or friction.static: 0");
    if (cs.restitution > 0.0)
      throw SceneError(file, "contact.restitution",
                       fmt(cs.restitution) + " > 0 needs flight and impacts, but model.normal_force = static "
                       "keeps a permanent contact (physics.md section 9); use model.normal_force: constrained "
                       "or contact.restitution: 0");
  }
}

// air.* (physics.md section 12); a finite contact or air needs the full model (the reduced one has no drilling).
ViewHint read_view(Section& root, const std::string& file) {
  Section v(root.raw("view"), file, "view");
  ViewHint view;
  const std::string camera = v.word("camera", "unset", {"low", "top", "follow"});
  view.camera = camera == "low" ? ViewCamera::low : camera == "top" ? ViewCamera::top
              : camera == "follow" ? ViewCamera::follow : ViewCamera::unset;
  view.distance = v.number("distance", 0.0, [](double d) { return d > 0.0 && d <= 100.0; }, "in (0, 100] [m]");
  view.real_time_factor = v.number("real_time_factor", 0.0, [](double f) { return f > 0.0 && f <= 1000.0; },
                                   "in (0, 1000] (simulated seconds per wall second)");
  v.finish();
  return view;
}

void read_air(Section& root, const std::string& file, Model& model) {
  Section a(root.raw("air"), file, "air");
  model.air.spin_drag = a.number("spin_drag", 0.0, non_negative, ">= 0 [N m s]");
  model.air.drag = a.number("drag", 0.0, non_negative, ">= 0 [N s/m]");
  a.finish();
  const FiniteContact& fc = model.finite_contact;
  const bool reduced = model.kind == ModelKind::adiabatic || model.automatic.enabled;
  if (reduced && (fc.rolling_resistance > 0.0 || model.air.drag > 0.0)) {
    const char* key = fc.rolling_resistance > 0.0 ? "contact.rolling_resistance" : "air.drag";
    throw SceneError(file, key, std::string("0 with model.kind ") + kind_name(model) + " (the reduced model of "
                                "physics.md section 7 carries a patch and air spin drag, not rolling resistance or "
                                "air drag); use model.kind: full");
  }
  // The patch's sleeping state (physics.md section 12.1) has a critical inclination of its own.
  if (model.kind == ModelKind::adiabatic && fc.has_patch()) {
    const std::string e = adiabatic_validity(model);
    if (!e.empty()) throw SceneError(file, "model.kind", e);
  }
}

RegimeThresholds read_regime_thresholds(Section& root, const std::string& file) {
  Section r(root.raw("regime"), file, "regime");
  RegimeThresholds th;
  th.nutation_angle = r.number("nutation_angle", th.nutation_angle, positive, "> 0 [rad]");
  th.nutation_rate = r.number("nutation_rate", th.nutation_rate, positive, "> 0 [rad/s]");
  th.sleep_turn_rate = r.number("sleep_turn_rate", th.sleep_turn_rate, positive, "> 0 [1/s]");
  th.sleep_acceleration = r.number("sleep_acceleration", th.sleep_acceleration, positive, "> 0 [m/s^2]");
  r.finish();
  return th;
}

// initial.*, checked against the model (a flight start needs contact modes; a stationary start a sleeping state).
void read_initial(Section& root, const std::string& file, const Model& model, InitialConditions& ic) {
  Section i(root.raw("initial"), file, "initial");
  ic.start = i.word("start", "tilted", {"tilted", "stationary"}) == "stationary" ? StartKind::stationary : StartKind::tilted;
  ic.tilt = i.number("tilt", ic.tilt, [](double v) { return v >= 0.0 && v < M_PI; }, "in [0, pi) [rad]");
  ic.tilt_azimuth = i.number("tilt_azimuth", ic.tilt_azimuth, finite, "a finite number [rad]");
  ic.spin = i.number("spin", ic.spin, spin_range, kSpinRange);
  ic.angular_velocity_transverse =
      i.pair("angular_velocity_transverse", ic.angular_velocity_transverse, spin_range, kSpinRange);
  ic.position = i.pair("position", ic.position);
  ic.velocity = i.pair("velocity", ic.velocity);
  ic.gap = i.number("gap", ic.gap, non_negative, ">= 0 [m] (height of the tip sphere above the plane)");
  ic.gap_rate = i.number("gap_rate", ic.gap_rate, finite, "a finite number [m/s] (normal velocity of the tip sphere)");
  i.finish();
  if ((ic.gap > 0.0 || ic.gap_rate != 0.0) && !has_contact_modes(model))
    throw SceneError(file, ic.gap > 0.0 ? "initial.gap" : "initial.gap_rate",
                     "a flight start needs model.normal_force: constrained and model.kind: full "
                     "(the other models keep a permanent contact)");
  if (ic.gap == 0.0 && ic.gap_rate < 0.0)
    throw SceneError(file, "initial.gap_rate", fmt(ic.gap_rate) + " < 0 at gap 0 would start inside the plane; "
                     "must be >= 0 when initial.gap is 0");
  if (ic.start == StartKind::stationary) {
    const StationaryState st = stationary_state(model, ic.spin);
    if (!st.exists) throw SceneError(file, "initial.start", "'stationary' is impossible: " + st.reason);
  }
}

IntegratorSettings read_integrator(Section& root, const std::string& file) {
  Section g(root.raw("integrator"), file, "integrator");
  IntegratorSettings is;
  const std::string method = g.word("method", "dopri5", {"euler", "semi_implicit_euler", "rk4", "dopri5", "rosenbrock4",
                                                         "switching", "implicit_midpoint", "fitted_midpoint"});
  parse_method(method, is.method);
  // Below 1e-12 s a step no longer changes t (double resolution at t ~ 1e4 s): a run that cannot progress.
  is.dt = g.number("dt", is.dt, [](double v) { return v >= kMinStep && v <= 10.0; }, "in [1e-12, 10] [s]");
  is.rtol = g.number("rtol", is.rtol, [](double v) { return v > 0.0 && v < 1.0; }, "in (0, 1)");
  is.atol = g.number("atol", is.atol, positive, "> 0");
  is.max_dt = g.number("max_dt", is.max_dt, [](double v) { return v == 0.0 || v >= kMinStep; },
                       "0 (unbounded) or >= 1e-12 [s]");
  is.max_energy_residual = g.number("max_energy_residual", is.max_energy_residual, positive,
                                    "> 0 (relative drift of E + W_diss that stops the run; 1e300 = never)");
  g.finish();
  return is;
}

std::vector<std::pair<double, double>> read_friction_points(Section& s, const std::string& file) {
  std::vector<std::pair<double, double>> points;
  const YAML::Node pts = s.raw(kFrictionPointsKey);
  const std::string key = join(s.path(), kFrictionPointsKey);
  if (!pts || !pts.IsSequence()) throw SceneError(file, key, "required for law table: a list of [s, mu] pairs");
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const std::string k = key + "[" + std::to_string(i) + "]";
    if (!pts[i].IsSequence() || pts[i].size() != 2) throw SceneError(file, k, show(pts[i]) + " must be [s, mu]");
    points.emplace_back(s.to_number(pts[i][0], k + "[0]", finite, "a number in [0, 1]"),
                        s.to_number(pts[i][1], k + "[1]", finite, "a finite number"));
  }
  return points;
}

// An event's `friction:` as a change over the law in force: `law` (default: the scene's law) and the parameters
// of that law it names (a table's points), as TopCommand and Python's apply give them.
FrictionChange read_friction_change(Section& f, const std::string& file, FrictionLawKind in_force) {
  FrictionChange change;
  if (f.has("law")) {
    std::vector<std::string> names;
    for (const FrictionLawName& n : kFrictionLawNames) names.push_back(n.name);
    FrictionLawKind kind;
    parse_friction_law_kind(f.word("law", "", names), kind);  // word() admitted only the laws' names
    change.kind = kind;
  }
  const FrictionLawKind kind = change.kind ? *change.kind : in_force;
  for (const FrictionParameter& p : kFrictionParameters) {
    if (p.law != kind || !f.has(p.name)) continue;
    const ParameterRange range = p.range;
    change.given.emplace_back(&p, f.number(p.name, 0.0, [range](double v) { return range.admits(v); }, range.text()));
  }
  if (kind == kFrictionPointsLaw && f.has(kFrictionPointsKey)) change.points = read_friction_points(f, file);
  f.finish();  // another law's parameter is an unknown key here
  return change;
}

// One entry of `events:`: any field of the command schema (command_fields.hpp) and `friction:`, validated as a
// command against the scene's model; `last_t` keeps them in time order.
ScriptedEvent read_event(const YAML::Node& node, const std::string& file, const std::string& path, const Model& model,
                         double& last_t) {
  Section e(node, file, path);
  ScriptedEvent event;
  if (!e.has("t")) throw SceneError(file, path + ".t", "required: the event time [s]");
  const double previous = last_t;
  event.t = e.number("t", 0.0, [previous](double v) { return v >= previous; },
                     ">= 0 and >= the previous event's t = " + fmt(previous) + " [s]");
  last_t = event.t;
  Command& c = event.command;
  for (const CommandField& f : command_fields()) {
    if (!e.has(f.name)) continue;
    const ParameterRange range = f.range;
    c.*f.member = e.number(f.name, 0.0, [range](double v) { return range.admits(v); }, f.range_text);
  }
  if (e.has("friction")) {
    Section f(e.raw("friction"), file, join(path, "friction"));
    c.friction = read_friction_change(f, file, model.friction.kind);
  }
  e.finish();
  if (c.empty()) throw SceneError(file, path, "changes nothing (give one of " + command_field_names() + ", friction)");
  const std::string err = validate(c, model);
  if (!err.empty()) throw SceneError(file, path, err);
  return event;
}

std::vector<ScriptedEvent> read_events(Section& root, const std::string& file, const Model& model) {
  std::vector<ScriptedEvent> events;
  const YAML::Node ev = root.raw("events");
  if (!ev || ev.IsNull()) return events;
  if (!ev.IsSequence()) throw SceneError(file, "events", show(ev) + " must be a list of {t: ..., ...} entries");
  double last_t = 0.0;
  for (std::size_t k = 0; k < ev.size(); ++k)
    events.push_back(read_event(ev[k], file, "events[" + std::to_string(k) + "]", model, last_t));
  return events;
}

}  // namespace

// A key of another law is an error that names both laws and the keys this law takes.
static void reject_foreign_parameter(Section& s, const std::string& file, const char* key, FrictionLawKind owner,
                                     FrictionLawKind kind) {
  if (kind == owner || !s.has(key)) return;
  const std::string name = to_string(kind);
  throw SceneError(file, join(s.path(), key),
                   show(s.raw(key)) + " is not a parameter of law " + name + " (it belongs to law " +
                       to_string(owner) + "); law " + name + " takes: " + friction_parameter_names(kind) +
                       ", regularization_speed, static, young_modulus, poisson_ratio");
}

static FrictionLaw read_friction_law(Section& s, const std::string& file, double& v_eps,
                                     std::optional<double>& static_friction) {
  FrictionLaw law;
  std::vector<std::string> names;
  for (const FrictionLawName& n : kFrictionLawNames) names.push_back(n.name);
  const std::string kind = s.word("law", "paper", names);
  parse_friction_law_kind(kind, law.kind);  // word() admitted only the laws' names
  v_eps = s.number("regularization_speed", 1.0e-9, positive, "> 0 [m/s]");
  for (const FrictionParameter& p : kFrictionParameters) reject_foreign_parameter(s, file, p.name, p.law, law.kind);
  reject_foreign_parameter(s, file, kFrictionPointsKey, kFrictionPointsLaw, law.kind);
  for (const FrictionParameter& p : kFrictionParameters) {
    if (p.law != law.kind) continue;
    const ParameterRange range = p.range;
    law.*p.member = s.number(p.name, law.*p.member, [range](double v) { return range.admits(v); }, range.text());
  }
  if (law.kind == kFrictionPointsLaw) law.points = read_friction_points(s, file);
  const std::string e = validate(law);
  if (!e.empty()) throw SceneError(file, "", e);
  if (s.has("static")) {
    const double mu0 = friction_coefficient(law, 0.0);
    static_friction = s.number("static", 0.0, [mu0](double v) { return v >= mu0; },
                               ">= mu(0) = " + fmt(mu0) + " of law " + kind + " (the static coefficient mu_s)");
  }
  return law;
}

namespace {

// The start places shapes[0] on the plane (initial.gap above it): no other shape may start below the plane.
void check_shapes_at_start(const Model& model, const StateVector& y, const std::string& file) {
  const ShapeSet& shapes = model.shapes;
  const double c = figure_axis(y).normalized().z();
  for (std::size_t k = 1; k < shapes.count; ++k) {
    const double below = shape_height(shapes.shape[0], c) - y[idx::gap] - shape_height(shapes.shape[k], c);
    if (below > 1e-12)
      throw SceneError(file, "top.shapes[" + std::to_string(k) + "]",
                       std::string("the ") + to_string(shapes.shape[k].kind) + " starts " + fmt(below) +
                           " m below the plane at the initial tilt " + fmt(std::acos(std::clamp(c, -1.0, 1.0))) +
                           " rad (shapes[0] is placed on the plane); start less tilted, or list first the shape that "
                           "touches");
  }
}

// A state the simulation can start from: finite energy, the figure axis within max_tilt of the plane normal (a top
// beyond it has fallen: bad input, exit 2, not a fault at t = 0).
void check_initial_state(const Scene& scene, const std::string& file) {
  const StateVector y = initial_state(scene);
  const double c = figure_axis(y).normalized().z(), sine = std::sqrt(std::max(0.0, 1.0 - c * c));
  for (std::size_t k = 0; k < scene.model.shapes.count; ++k)  // a rim lying flat has no lowest point to start on
    if (scene.model.shapes.shape[k].kind == ShapeKind::rim && sine < kFlatEndSine)
      throw SceneError(file, scene.initial.start == StartKind::tilted ? "initial.tilt" : "initial.start",
                       "top.shapes[" + std::to_string(k) + "], a rim, starts lying flat (the tilt's sine " +
                           fmt(sine) + " from the plane normal); must be >= " + fmt(kFlatEndSine));
  const double energy = mechanical_energy(scene.model, y);
  if (!all_finite(y) || !std::isfinite(energy))
    throw SceneError(file, "initial", "the initial energy is " + fmt(energy) +
                                          " J: a speed, spin or position too large for double precision");
  const double max_tilt = scene.model.top.max_tilt;
  const double tilt = std::acos(std::clamp(figure_axis(y).normalized().z(), -1.0, 1.0));  // from the plane normal
  if (tilt >= max_tilt && !has_shapes(scene.model))  // a body with a rim has no max_tilt: the rim touches
    throw SceneError(file, scene.initial.start == StartKind::tilted ? "initial.tilt" : "initial.start",
                     "the figure axis starts " + fmt(tilt) + " rad from the plane normal; must be < top.max_tilt = " +
                         fmt(max_tilt) + " rad (a top tilted further has fallen over)");
  check_shapes_at_start(scene.model, y, file);
}

// The Simulator steps a body of one or two shapes (two touching at once at most, physics.md 13.4): more are
// refused, not run wrong; so are shapes with what only the tip sphere has.
void check_simulated_shapes(const Model& model, const std::string& file) {
  if (!has_shapes(model)) return;
  if (model.shapes.count > 2)
    throw SceneError(file, "top.shapes", std::to_string(model.shapes.count) +
                                             " shapes: at most 2 are simulated (two in contact at once)");
  // A body of shapes runs the full model with the constrained normal force: the rest is the tip sphere's alone.
  const char* refused = model.top.has_rotor                                     ? "top.rotor"
                        : model.kind != ModelKind::full || model.automatic.enabled ? "model.kind"
                        : model.normal_force != NormalForceModel::constrained    ? "model.normal_force"
                                                                                 : nullptr;
  if (refused)
    throw SceneError(file, refused, "not with top.shapes yet (a body of shapes runs the full model with the "
                                    "constrained normal force, a patch, air and rolling resistance)");
}

}  // namespace

Scene parse_scene(const YAML::Node& root, const std::string& source, const std::string& config_dir) {
  Scene scene;
  scene.source = source;
  const std::string& file = source;
  if (!root || !root.IsMap()) throw SceneError(file, "", "a scene must be a YAML mapping with at least the key 'top'");
  Section s(root, file, "");
  if (s.has("description") && !s.raw("description").IsScalar())
    throw SceneError(file, "description", "must be a text");

  // top (required)
  if (!s.has("top")) throw SceneError(file, "top", "required (a mapping, or the name of a file in config/tops/)");
  std::string top_source;
  const YAML::Node top_node = resolve_named(s.raw("top"), file, "top", config_dir, "tops", top_source);
  scene.model.top = read_top(top_node, top_source, scene.initial.rotor_spin, scene.model.shapes);

  scene.model.plane = read_plane(s, file);

  // friction
  {
    std::string fsource;
    const YAML::Node fnode = resolve_named(s.raw("friction"), file, "friction", config_dir, "planes", fsource);
    Section f(fnode, fsource, "friction");
    scene.model.friction = read_friction_law(f, fsource, scene.model.regularization_speed,
                                             scene.model.contact.static_friction);
    scene.model.plane_material = read_material(f);
    f.finish();
    if (clamp_is_active(scene.model.friction))
      scene.warnings.push_back(fsource + ": friction law " + to_string(scene.model.friction.kind) +
                               " gives mu(s) < 0 for part of s in [0, 1]; it is clamped to 0 there (friction never propels)");
  }

  read_model_options(s, file, scene.model);
  read_contact(s, file, scene.model);
  read_air(s, file, scene.model);
  scene.model.regime = read_regime_thresholds(s, file);
  read_initial(s, file, scene.model, scene.initial);
  scene.integrator = read_integrator(s, file);
  scene.duration = s.number("duration", scene.duration, positive, "> 0 [s]");
  scene.view = read_view(s, file);

  scene.events = read_events(s, file, scene.model);
  s.finish();
  check_initial_state(scene, file);
  check_simulated_shapes(scene.model, file);
  return scene;
}

Scene load_scene(const std::string& path) {
  YAML::Node root;
  if (is_dir(path)) throw SceneError(path, "", "is a directory, not a scene file");
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw SceneError(path, "", "cannot open the scene file");
  } catch (const YAML::Exception& e) {
    throw SceneError(path, "", std::string("not valid YAML: ") + e.what());
  } catch (const std::exception& e) {  // e.g. an unreadable file
    throw SceneError(path, "", std::string("cannot read the scene file: ") + e.what());
  }
  // A scene in <config>/scenes/ finds its tops and planes in <config>/.
  std::string dir = path.find('/') == std::string::npos ? "." : path.substr(0, path.rfind('/'));
  std::string config_dir = dir + "/..";
  if (!is_dir(config_dir + "/tops")) config_dir = is_dir(dir + "/tops") ? dir : "";
  return parse_scene(root, path, config_dir);
}

Scene parse_scene_text(const std::string& text, const std::string& source, const std::string& config_dir) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw SceneError(source, "", std::string("not valid YAML: ") + e.what());
  }
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);  // "" or "~": the defaults
  return parse_scene(root, source, config_dir);
}

StateVector initial_state(const Scene& scene) {
  const Model& model = scene.model;
  const InitialConditions& ic = scene.initial;
  if (ic.start == StartKind::stationary) {
    const StationaryState st = stationary_state(model, ic.spin);
    return stationary_state_vector(model, st, ic.spin, ic.position, ic.rotor_spin);
  }
  // The initial keys are world-frame.
  auto to_plane = [&model](const Eigen::Vector3d& v) { return world_to_plane(model.plane.inclination, v); };
  const Eigen::Vector3d f_hat = to_plane(Eigen::Vector3d(std::sin(ic.tilt) * std::cos(ic.tilt_azimuth),
                                                         std::sin(ic.tilt) * std::sin(ic.tilt_azimuth), std::cos(ic.tilt)));
  const Eigen::Vector3d w_t = to_plane(Eigen::Vector3d(ic.angular_velocity_transverse.x(), ic.angular_velocity_transverse.y(), 0.0));
  StateVector y{};
  set_position(y, ic.position);
  set_velocity(y, ic.velocity);
  set_figure_axis(y, f_hat);
  set_angular_velocity(y, ic.spin * f_hat + (w_t - w_t.dot(f_hat) * f_hat));
  y[idx::nu] = model.top.has_rotor ? ic.rotor_spin - ic.spin : 0.0;
  y[idx::gap] = ic.gap;
  y[idx::gap_rate] = ic.gap_rate;
  return y;
}

const char* to_string(ViewCamera camera) {
  switch (camera) {
    case ViewCamera::low: return "low";
    case ViewCamera::top: return "top";
    case ViewCamera::follow: return "follow";
    case ViewCamera::unset: break;
  }
  return "unset";
}

}  // namespace top_sim
