#include "writers.hpp"

#include <charconv>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "top_sim/format.hpp"
#include "top_sim/trajectory.hpp"

namespace top_sim {

namespace {

std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream os;
  os << std::setprecision(17) << v;
  return os.str();
}
std::string vec(std::initializer_list<double> v) {
  std::string s = "[";
  for (double x : v) s += (s.size() > 1 ? ", " : "") + num(x);
  return s + "]";
}
std::string quoted(const std::string& text) {
  std::string s = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') s += '\\';
    if (c == '\n') { s += "\\n"; continue; }
    s += c;
  }
  return s + "\"";
}

// One JSON object's members in order. A member its source cannot give is null, and "unavailable" (the last
// member, present only then) maps it to the reason.
class JsonObject {
 public:
  explicit JsonObject(std::string indent = "  ") : indent_(std::move(indent)) {}
  JsonObject& add(const std::string& key, const std::string& json) {
    members_.emplace_back(key, json);
    return *this;
  }
  JsonObject& missing(const std::string& key, const std::string& why) {
    reasons_.emplace_back(key, quoted(why));
    return add(key, "null");
  }
  std::string str() const {
    std::vector<std::pair<std::string, std::string>> all = members_;
    if (!reasons_.empty()) all.emplace_back("unavailable", JsonObject(indent_ + "  ").add_all(reasons_).str());
    std::string out = "{\n";
    for (std::size_t i = 0; i < all.size(); ++i)
      out += indent_ + top_sim::quoted(all[i].first) + ": " + all[i].second + (i + 1 < all.size() ? ",\n" : "\n");
    return out + indent_.substr(2) + "}";
  }

 private:
  JsonObject& add_all(const std::vector<std::pair<std::string, std::string>>& members) {
    members_.insert(members_.end(), members.begin(), members.end());
    return *this;
  }
  std::string indent_;
  std::vector<std::pair<std::string, std::string>> members_, reasons_;
};

std::string optional_number(const std::optional<double>& v) { return v ? num(*v) : "null"; }

// {"name": value, ...} over an enumeration's names (Regime, ContactMode).
template <class Enum, std::size_t N>
std::string per_name(const std::array<double, N>& seconds) {
  std::string s = "{";
  for (std::size_t i = 0; i < N; ++i)
    s += (i ? ", " : "") + quoted(to_string(static_cast<Enum>(i))) + ": " + num(seconds[i]);
  return s + "}";
}

}  // namespace

CsvWriter::CsvWriter(std::ostream& os)
    : os_(os), buf_(new char[kBlock + kField * trajectory_columns().size() + 1]) {  // a block and one more row
  for (const TrajectoryColumn& c : trajectory_columns())
    if (std::char_traits<char>::length(c.name) >= kField) throw std::logic_error(std::string("CSV name: ") + c.name);
}

namespace {

// One field: the name of an enumeration (at most 13 characters: regime.cpp, contact_modes.cpp), or the number's
// text (format.hpp).
char* put_field(char* p, const TrajectoryColumn& c, const Snapshot& s) {
  if (c.text) {
    for (const char* t = c.text(s); *t; ++t) *p++ = *t;
    return p;
  }
  return put_number(p, c.value(s));
}

}  // namespace

void CsvWriter::header() {
  char* p = buf_.get() + used_;
  for (const TrajectoryColumn& c : trajectory_columns()) {
    p = std::copy_n(c.name, std::char_traits<char>::length(c.name), p);
    *p++ = ',';
  }
  p[-1] = '\n';
  used_ = static_cast<std::size_t>(p - buf_.get());
  if (used_ >= kBlock) flush();
}

void CsvWriter::row(const Snapshot& s) {
  char* p = buf_.get() + used_;
  for (const TrajectoryColumn& c : trajectory_columns()) {
    p = put_field(p, c, s);
    *p++ = ',';
  }
  p[-1] = '\n';
  used_ = static_cast<std::size_t>(p - buf_.get());
  if (used_ >= kBlock) flush();
}

void CsvWriter::flush() {
  if (used_ == 0) return;
  os_.write(buf_.get(), static_cast<std::streamsize>(used_));
  used_ = 0;
}

bool write_text_file(const std::string& tool, const std::string& flag, const std::string& path,
                     const std::string& text) {
  const std::string what = tool + ": " + flag + " = '" + path + "': ";
  if (path == "-") {
    std::cout << text << std::flush;
    if (!std::cout) std::cerr << what << "writing to standard output failed\n";
    return static_cast<bool>(std::cout);
  }
  if (path.empty()) return true;
  std::ofstream out(path);
  if (!out) {
    std::cerr << what << "cannot open for writing\n";
    return false;
  }
  out << text << std::flush;
  if (!out) std::cerr << what << "writing failed (disk full?)\n";
  return static_cast<bool>(out);
}

namespace {

JsonObject final_json(const Snapshot& f) {
  JsonObject o("    ");
  o.add("t", num(f.t))
      .add("alpha", num(f.alpha))
      .add("position", vec({f.contact_point.x(), f.contact_point.y()}))
      .add("velocity", vec({f.tip_velocity.x(), f.tip_velocity.y()}))
      .add("f_hat", vec({f.figure_axis.x(), f.figure_axis.y(), f.figure_axis.z()}))
      .add("omega", vec({f.angular_velocity.x(), f.angular_velocity.y(), f.angular_velocity.z()}))
      .add("spin", num(f.spin))
      .add("rotor_spin", f.has_rotor ? num(f.rotor_spin) : "null")
      .add("slip", num(f.slip))
      .add("phi", num(f.phi))
      .add("drilling_torque", num(f.drilling_torque))
      .add("patch_radius", num(f.patch_radius));
  return o;
}

// The scene's names of the method and the models.
void add_scene(JsonObject& o, const Scene& scene) {
  o.add("scene", quoted(scene.source))
      .add("method", quoted(to_string(scene.integrator.method)))
      .add("model", quoted(kind_name(scene.model)))
      .add("normal_force", quoted(to_string(scene.model.normal_force)));
}

// The members both summaries have, from "regime" to "contact_mode", in that order.
struct Outcome {
  const Snapshot& final;
  std::optional<std::array<double, kRegimeCount>> regime_seconds;
  std::string no_regime_seconds;  // why regime_seconds is absent
  std::optional<double> phi_measured, phi_star;
  std::string stationary_note, phi_star_source;  // "" = none (phi_star_source: a recording's only)
  double max_energy_residual;
};

void add_outcome(JsonObject& o, const Outcome& c) {
  const Snapshot& f = c.final;
  o.add("regime", quoted(to_string(f.regime)));
  if (c.regime_seconds)
    o.add("regime_seconds", per_name<Regime>(*c.regime_seconds));
  else
    o.missing("regime_seconds", c.no_regime_seconds);
  o.add("phi_measured", optional_number(c.phi_measured)).add("phi_star", optional_number(c.phi_star));
  if (!c.phi_star_source.empty()) o.add("phi_star_source", quoted(c.phi_star_source));
  o.add("stationary_note", c.stationary_note.empty() ? "null" : quoted(c.stationary_note))
      .add("final", final_json(f).str())
      .add("energy_balance_residual", num(c.max_energy_residual))
      .add("contact_fault", faulted(f) ? quoted(f.fault_message) : "null");
  if (f.fault != ContactFault::none || !faulted(f))
    o.add("contact_fault_kind", f.fault == ContactFault::none ? "null" : quoted(to_string(f.fault)));
  else
    o.missing("contact_fault_kind", "TopState carries the fault's text (contact_fault), not its kind");
  o.add("contact_mode", faulted(f) ? "null" : quoted(to_string(f.contact_mode)));
}

// [{"t", "kind", "from", "to", "energy_change"}, ...]; kind and energy_change only for located switches.
std::string switches_json(const std::vector<ModeSwitch>& list, bool located) {
  std::string s = "[";
  for (std::size_t i = 0; i < list.size(); ++i) {
    const ModeSwitch& m = list[i];
    s += std::string(i ? ",\n    " : "\n    ") + "{\"t\": " + num(m.t);
    if (located) s += ", \"kind\": " + quoted(to_string(m.kind));
    s += ", \"from\": " + quoted(to_string(m.from)) + ", \"to\": " + quoted(to_string(m.to));
    if (located) s += ", \"energy_change\": " + num(m.energy_change);
    s += "}";
  }
  return s + (list.empty() ? "]" : "\n  ]");
}

}  // namespace

std::string summary_json(const Scene& scene, const RunResult& r) {
  JsonObject o;
  add_scene(o, scene);
  o.add("sim_seconds", num(r.sim_seconds))
      .add("cpu_seconds", num(r.cpu_seconds))
      .add("real_time_factor", num(r.cpu_seconds > 0 ? r.sim_seconds / r.cpu_seconds : NAN))
      .add("steps", std::to_string(r.stats.steps))
      .add("rhs_evaluations", std::to_string(r.stats.rhs_evaluations))
      .add("samples", std::to_string(r.sampled.samples));
  // regime_seconds from the simulator's regime cadence: the same whatever the sample rate.
  add_outcome(o, {r.final, r.regime_seconds, "", r.phi_measured, r.phi_star, r.stationary_note, "",
                  r.max_energy_residual});
  o.add("mode_seconds", per_name<ContactMode>(r.mode_seconds))
      .add("mode_switch_count", std::to_string(r.mode_switch_count))
      .add("mode_switches", switches_json(r.mode_switches, true));
  if (scene.model.automatic.enabled)
    o.add("handovers", std::to_string(r.handovers)).add("reduced_seconds", num(r.reduced_seconds));
  return o.str() + "\n";
}

std::string summary_json(const RecordedSource& src, const SampledSummary& s) {
  const char* not_recorded = "not in TopState: the node's CPU time and integrator counts are not recorded";
  JsonObject o;
  o.add("bag", quoted(src.bag)).add("topic", quoted(src.topic)).add("top", quoted(src.top));
  if (src.scene) {
    add_scene(o, *src.scene);
  } else {
    o.add("scene", "null");
    for (const char* key : {"method", "model", "normal_force"})
      o.missing(key, "a bag holds no scene (give --scene FILE)");
  }
  o.add("t_first", num(s.t_first)).add("t_last", num(s.t_last)).add("sim_seconds", num(s.t_last - s.t_first));
  for (const char* key : {"cpu_seconds", "real_time_factor", "steps", "rhs_evaluations"}) o.missing(key, not_recorded);
  o.add("samples", std::to_string(s.samples)).add("skipped", std::to_string(src.skipped));
  add_outcome(o, {s.last, s.regime_seconds, "", s.phi_measured, src.phi_star, src.stationary_note, src.phi_star_source,
                  s.max_energy_residual});
  o.add("mode_seconds", per_name<ContactMode>(s.mode_seconds))
      .missing("mode_switch_count", "a bag holds samples: switches between two samples are not seen (mode_changes)")
      .missing("mode_switches", "a bag holds samples: switches between two samples are not seen (mode_changes)")
      .add("mode_change_count", std::to_string(s.mode_change_count))
      .add("mode_changes", switches_json(s.mode_changes, false));
  return o.str() + "\n";
}

}  // namespace top_sim
