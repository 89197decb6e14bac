#include "writers.hpp"

#include <charconv>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "top_sim/format.hpp"
#include "top_sim/trajectory.hpp"

namespace top_sim {

namespace {

using Json = nlohmann::ordered_json;  // members in the order they are added (docs/interfaces.md)

// A JSON object's members in order. A member its source cannot give is null, and "unavailable" (the last member,
// present only then) maps it to the reason.
class JsonObject {
 public:
  Json& operator[](const std::string& key) { return members_[key]; }
  void missing(const std::string& key, const std::string& why) {
    members_[key] = nullptr;
    reasons_[key] = why;
  }
  Json json() const {
    Json all = members_;
    if (!reasons_.empty()) all["unavailable"] = reasons_;
    return all;
  }

 private:
  Json members_ = Json::object(), reasons_ = Json::object();
};

Json optional_number(const std::optional<double>& v) { return v ? Json(*v) : Json(nullptr); }
Json text_or_null(const std::string& text) { return text.empty() ? Json(nullptr) : Json(text); }

// {"name": value, ...} over an enumeration's names (Regime, ContactMode).
template <class Enum, std::size_t N>
Json per_name(const std::array<double, N>& seconds) {
  Json o = Json::object();
  for (std::size_t i = 0; i < N; ++i) o[to_string(static_cast<Enum>(i))] = seconds[i];
  return o;
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

Json final_json(const Snapshot& f) {
  Json o = Json::object();
  o["t"] = f.t;
  o["alpha"] = f.alpha;
  o["position"] = {f.contact_point.x(), f.contact_point.y()};
  o["velocity"] = {f.tip_velocity.x(), f.tip_velocity.y()};
  o["f_hat"] = {f.figure_axis.x(), f.figure_axis.y(), f.figure_axis.z()};
  o["omega"] = {f.angular_velocity.x(), f.angular_velocity.y(), f.angular_velocity.z()};
  o["spin"] = f.spin;
  o["rotor_spin"] = f.has_rotor ? Json(f.rotor_spin) : Json(nullptr);
  o["slip"] = f.slip;
  o["phi"] = f.phi;
  o["drilling_torque"] = f.drilling_torque;
  o["patch_radius"] = f.patch_radius;
  o["touching"] = f.touching;
  return o;
}

// The scene's names of the method and the models.
void add_scene(JsonObject& o, const Scene& scene) {
  o["scene"] = scene.source;
  o["method"] = to_string(scene.integrator.method);
  o["model"] = kind_name(scene.model);
  o["normal_force"] = to_string(scene.model.normal_force);
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
  o["regime"] = to_string(f.regime);
  if (c.regime_seconds)
    o["regime_seconds"] = per_name<Regime>(*c.regime_seconds);
  else
    o.missing("regime_seconds", c.no_regime_seconds);
  o["phi_measured"] = optional_number(c.phi_measured);
  o["phi_star"] = optional_number(c.phi_star);
  if (!c.phi_star_source.empty()) o["phi_star_source"] = c.phi_star_source;
  o["stationary_note"] = text_or_null(c.stationary_note);
  o["final"] = final_json(f);
  o["energy_balance_residual"] = c.max_energy_residual;
  o["contact_fault"] = faulted(f) ? Json(f.fault_message) : Json(nullptr);
  if (f.fault != ContactFault::none || !faulted(f))
    o["contact_fault_kind"] = f.fault == ContactFault::none ? Json(nullptr) : Json(to_string(f.fault));
  else
    o.missing("contact_fault_kind", "TopState carries the fault's text (contact_fault), not its kind");
  o["contact_mode"] = faulted(f) ? Json(nullptr) : Json(to_string(f.contact_mode));
  o["end_state"] = f.end_state == EndState::none ? Json(nullptr) : Json(to_string(f.end_state));
  o["end_state_message"] = text_or_null(f.end_message);
}

// [{"t", "kind", "from", "to", "energy_change"}, ...]; kind and energy_change only for located switches.
Json switches_json(const std::vector<ModeSwitch>& list, bool located) {
  Json a = Json::array();
  for (const ModeSwitch& m : list) {
    Json s = Json::object();
    s["t"] = m.t;
    if (located) s["kind"] = to_string(m.kind);
    s["from"] = to_string(m.from);
    s["to"] = to_string(m.to);
    if (located) s["energy_change"] = m.energy_change;
    a.push_back(std::move(s));
  }
  return a;
}

// The summary's text: indented by 2, a text that is not UTF-8 (a scene's path) with U+FFFD in place of its bytes.
std::string summary_text(const JsonObject& o) {
  return o.json().dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace

std::string summary_json(const Scene& scene, const RunResult& r) {
  JsonObject o;
  add_scene(o, scene);
  o["sim_seconds"] = r.sim_seconds;
  o["cpu_seconds"] = r.cpu_seconds;
  o["real_time_factor"] = r.cpu_seconds > 0 ? r.sim_seconds / r.cpu_seconds : NAN;  // NaN is written as null
  o["steps"] = r.stats.steps;
  o["rhs_evaluations"] = r.stats.rhs_evaluations;
  o["samples"] = r.sampled.samples;
  // regime_seconds from the simulator's regime cadence: the same whatever the sample rate.
  add_outcome(o, {r.final, r.regime_seconds, "", r.phi_measured, r.phi_star, r.stationary_note, "",
                  r.max_energy_residual});
  o["mode_seconds"] = per_name<ContactMode>(r.mode_seconds);
  o["mode_switch_count"] = r.mode_switch_count;
  o["mode_switches"] = switches_json(r.mode_switches, true);
  if (scene.model.automatic.enabled) {
    o["handovers"] = r.handovers;
    o["reduced_seconds"] = r.reduced_seconds;
  }
  return summary_text(o);
}

std::string summary_json(const RecordedSource& src, const SampledSummary& s) {
  const char* not_recorded = "not in TopState: the node's CPU time and integrator counts are not recorded";
  const char* not_seen = "a bag holds samples: switches between two samples are not seen (mode_changes)";
  JsonObject o;
  o["bag"] = src.bag;
  o["topic"] = src.topic;
  o["top"] = src.top;
  if (src.scene) {
    add_scene(o, *src.scene);
  } else {
    o["scene"] = nullptr;
    for (const char* key : {"method", "model", "normal_force"})
      o.missing(key, "a bag holds no scene (give --scene FILE)");
  }
  o["t_first"] = s.t_first;
  o["t_last"] = s.t_last;
  o["sim_seconds"] = s.t_last - s.t_first;
  for (const char* key : {"cpu_seconds", "real_time_factor", "steps", "rhs_evaluations"}) o.missing(key, not_recorded);
  o["samples"] = s.samples;
  o["skipped"] = src.skipped;
  add_outcome(o, {s.last, s.regime_seconds, "", s.phi_measured, src.phi_star, src.stationary_note, src.phi_star_source,
                  s.max_energy_residual});
  o["mode_seconds"] = per_name<ContactMode>(s.mode_seconds);
  o.missing("mode_switch_count", not_seen);
  o.missing("mode_switches", not_seen);
  o["mode_change_count"] = s.mode_change_count;
  o["mode_changes"] = switches_json(s.mode_changes, false);
  return summary_text(o);
}

}  // namespace top_sim
