// Friction laws mu(s) (physics.md section 4).
#include "top_sim/friction.hpp"
#include "top_sim/format.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace top_sim {

namespace {
std::string format_bound(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}
}  // namespace

bool ParameterRange::admits(double v) const {
  return std::isfinite(v) && (lower_open ? v > lower : v >= lower) && (upper_open ? v < upper : v <= upper);
}

std::string ParameterRange::text() const {
  const bool bounded_below = std::isfinite(lower), bounded_above = std::isfinite(upper);
  if (!bounded_below && !bounded_above) return "a finite number";
  if (!bounded_above) return (lower_open ? "> " : ">= ") + format_bound(lower);
  if (!bounded_below) return (upper_open ? "< " : "<= ") + format_bound(upper);
  return std::string("in ") + (lower_open ? "(" : "[") + format_bound(lower) + ", " + format_bound(upper) +
         (upper_open ? ")" : "]");
}

FrictionLaw changed_law(const FrictionLaw& in_force, const FrictionChange& change) {
  FrictionLaw law = in_force;
  if (change.kind) law.kind = *change.kind;
  for (const auto& [parameter, value] : change.given) law.*(parameter->member) = value;
  if (change.points) law.points = *change.points;
  return law;
}

std::string validate(const FrictionChange& change, const FrictionLaw& in_force) {
  const FrictionLawKind kind = change.kind ? *change.kind : in_force.kind;
  for (const auto& [parameter, value] : change.given)
    if (parameter->law != kind)
      return std::string("friction.") + parameter->name + ": law " + to_string(kind) + " reads " +
             friction_parameter_names(kind);
  if (change.points && kind != kFrictionPointsLaw)
    return std::string("friction.") + kFrictionPointsKey + ": law " + to_string(kind) + " reads " +
           friction_parameter_names(kind);
  return "";
}

const FrictionParameter* find_friction_parameter(const std::string& name) {
  for (const FrictionParameter& p : kFrictionParameters)
    if (name == p.name) return &p;
  return nullptr;
}

std::string friction_parameter_names(FrictionLawKind kind) {
  std::string names;
  for (const FrictionParameter& p : kFrictionParameters)
    if (p.law == kind) names += (names.empty() ? "" : ", ") + std::string(p.name);
  if (kind == kFrictionPointsLaw) names += (names.empty() ? "" : ", ") + std::string(kFrictionPointsKey);
  return names;
}

const char* to_string(FrictionLawKind kind) {
  for (const FrictionLawName& n : kFrictionLawNames)
    if (n.kind == kind) return n.name;
  return "?";
}

bool parse_friction_law_kind(const std::string& name, FrictionLawKind& out) {
  for (const FrictionLawName& n : kFrictionLawNames)
    if (name == n.name) {
      out = n.kind;
      return true;
    }
  return false;
}

std::string friction_law_names(const char* separator) {
  std::string names;
  for (const FrictionLawName& n : kFrictionLawNames) names += (names.empty() ? "" : separator) + std::string(n.name);
  return names;
}

double raw_friction_coefficient(const FrictionLaw& law, double s) {
  switch (law.kind) {
    case FrictionLawKind::paper:
      return law.mu_c * s * (2.0 * law.s_c - s) / (law.s_c * law.s_c);
    case FrictionLawKind::linearized:
      return law.mu0 + law.k * (s - law.s0);
    case FrictionLawKind::coulomb:
      return law.mu;
    case FrictionLawKind::table: {
      const auto& p = law.points;
      if (s <= p.front().first) return p.front().second;
      if (s >= p.back().first) return p.back().second;
      std::size_t i = 1;
      while (p[i].first < s) ++i;
      const double w = (s - p[i - 1].first) / (p[i].first - p[i - 1].first);
      return p[i - 1].second + w * (p[i].second - p[i - 1].second);
    }
  }
  return 0.0;
}

double friction_slope(const FrictionLaw& law, double s) {
  if (raw_friction_coefficient(law, s) < 0.0) return 0.0;
  switch (law.kind) {
    case FrictionLawKind::paper:
      return 2.0 * law.mu_c * (law.s_c - s) / (law.s_c * law.s_c);
    case FrictionLawKind::linearized:
      return law.k;
    case FrictionLawKind::coulomb:
      return 0.0;
    case FrictionLawKind::table: {
      const auto& p = law.points;
      if (s < p.front().first || s >= p.back().first) return 0.0;
      std::size_t i = 1;
      while (p[i].first <= s) ++i;
      return (p[i].second - p[i - 1].second) / (p[i].first - p[i - 1].first);
    }
  }
  return 0.0;
}

namespace {
std::string bad(const std::string& field, double value, const std::string& range) {
  return range_message(field, value, range);
}
}  // namespace

std::string validate(const FrictionLaw& law) {
  for (const FrictionParameter& p : kFrictionParameters)
    if (p.law == law.kind && !p.range.admits(law.*p.member))
      return bad(std::string("friction.") + p.name, law.*p.member, p.range.text());
  switch (law.kind) {
    case FrictionLawKind::paper:
      return "";
    case FrictionLawKind::linearized:
      if (raw_friction_coefficient(law, 0.0) <= 0.0 && raw_friction_coefficient(law, 1.0) <= 0.0)
        return "friction (linearized): mu0 = " + std::to_string(law.mu0) + ", k = " + std::to_string(law.k) +
               ", s0 = " + std::to_string(law.s0) + " give mu(s) <= 0 on all of [0, 1]: no friction at all";
      return "";
    case FrictionLawKind::coulomb:
      return "";
    case FrictionLawKind::table: {
      const auto& p = law.points;
      if (p.size() < 2) return "friction.points has " + std::to_string(p.size()) + " points: must have at least 2";
      for (std::size_t i = 0; i < p.size(); ++i) {
        const std::string at = "friction.points[" + std::to_string(i) + "]";
        if (!(p[i].first >= 0.0 && p[i].first <= 1.0)) return bad(at + ".s", p[i].first, "in [0, 1]");
        if (!std::isfinite(p[i].second)) return bad(at + ".mu", p[i].second, "finite");
        if (i > 0 && !(p[i].first > p[i - 1].first))
          return bad(at + ".s", p[i].first, "greater than the previous s (" + std::to_string(p[i - 1].first) + ")");
      }
      return "";
    }
  }
  return "friction.law: unknown";
}

bool clamp_is_active(const FrictionLaw& law) {
  switch (law.kind) {
    case FrictionLawKind::paper: return law.s_c < 0.5;  // mu < 0 for s > 2 s_c
    case FrictionLawKind::linearized:
      return raw_friction_coefficient(law, 0.0) < 0.0 || raw_friction_coefficient(law, 1.0) < 0.0;
    case FrictionLawKind::coulomb: return false;
    case FrictionLawKind::table:
      return std::any_of(law.points.begin(), law.points.end(), [](const auto& q) { return q.second < 0.0; });
  }
  return false;
}

double max_friction_coefficient(const FrictionLaw& law) {
  switch (law.kind) {
    case FrictionLawKind::paper: return law.mu_c;  // at s = s_c <= 1
    case FrictionLawKind::linearized:
      return std::max({0.0, raw_friction_coefficient(law, 0.0), raw_friction_coefficient(law, 1.0)});
    case FrictionLawKind::coulomb: return law.mu;
    case FrictionLawKind::table: {
      double m = 0.0;
      for (const auto& q : law.points) m = std::max(m, q.second);
      return m;
    }
  }
  return 0.0;
}

}  // namespace top_sim
