// Dry-friction laws mu(s) of physics.md section 4.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace top_sim {

enum class FrictionLawKind { paper, linearized, coulomb, table };

// Each law's name: the scene's friction.law, TopCommand.friction_law, dynamic_reconfigure's friction_law.
struct FrictionLawName {
  FrictionLawKind kind;
  const char* name;
};
inline constexpr FrictionLawName kFrictionLawNames[] = {{FrictionLawKind::paper, "paper"},
                                                        {FrictionLawKind::linearized, "linearized"},
                                                        {FrictionLawKind::coulomb, "coulomb"},
                                                        {FrictionLawKind::table, "table"}};

// The admissible values of a scalar parameter: finite, between the bounds (each open or closed; infinite = none).
struct ParameterRange {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  double lower = -kInf, upper = kInf;
  bool lower_open = true, upper_open = true;

  static constexpr ParameterRange any() { return {}; }
  static constexpr ParameterRange above(double a) { return {a, kInf, true, true}; }
  static constexpr ParameterRange at_least(double a) { return {a, kInf, false, true}; }
  static constexpr ParameterRange between(double a, bool a_open, double b, bool b_open) { return {a, b, a_open, b_open}; }

  bool admits(double v) const;
  std::string text() const;  // for messages: "> 0", ">= 0", "in (0, 1]", "a finite number"
};

// Every scalar parameter of every friction law, once: X(law, name, range). `name` is at the same time the
// FrictionLaw member, the scene key under `friction:`, and the field of the TopCommand message and of the
// dynamic_reconfigure config, so adapters copy fields with this list; the core iterates kFrictionParameters below.
// Adding a law or a parameter: a FrictionLaw member, a row here, its formulas in friction.cpp and stationary.cpp.
#define TOP_SIM_FRICTION_PARAMETERS(X)                                                        \
  X(paper, mu_c, ::top_sim::ParameterRange::above(0.0))                      /* > 0 */       \
  X(paper, s_c, ::top_sim::ParameterRange::between(0.0, true, 1.0, false))   /* (0, 1] */    \
  X(linearized, mu0, ::top_sim::ParameterRange::any())                       /* finite */    \
  X(linearized, k, ::top_sim::ParameterRange::any())                         /* finite */    \
  X(linearized, s0, ::top_sim::ParameterRange::between(0.0, false, 1.0, false)) /* [0, 1] */ \
  X(coulomb, mu, ::top_sim::ParameterRange::at_least(0.0))                   /* >= 0 */

// The table law's one parameter that is not a number: its (s, mu) points.
inline constexpr const char* kFrictionPointsKey = "points";
inline constexpr FrictionLawKind kFrictionPointsLaw = FrictionLawKind::table;

// A friction law: the kind selects which parameters are read.
struct FrictionLaw {
  FrictionLawKind kind = FrictionLawKind::paper;
  double mu_c = 0.25;  // paper: maximum friction coefficient
  double s_c = 0.6;    // paper: slip at the maximum
  double mu0 = 0.1;    // linearized: mu at s0
  double k = 1.0;      // linearized: d mu / d s
  double s0 = 0.3;     // linearized: expansion point
  double mu = 0.3;     // coulomb: constant coefficient
  std::vector<std::pair<double, double>> points;  // table: (s_i, mu_i), s strictly increasing in [0, 1]
};

struct FrictionParameter {
  const char* name;
  FrictionLawKind law;  // the law that reads it
  double FrictionLaw::*member;
  ParameterRange range;
};
#define TOP_SIM_FRICTION_PARAMETER_ROW(law, name, range) \
  FrictionParameter{#name, FrictionLawKind::law, &FrictionLaw::name, range},
inline constexpr FrictionParameter kFrictionParameters[] = {TOP_SIM_FRICTION_PARAMETERS(TOP_SIM_FRICTION_PARAMETER_ROW)};
#undef TOP_SIM_FRICTION_PARAMETER_ROW

// The parameter called `name`, or nullptr.
const FrictionParameter* find_friction_parameter(const std::string& name);

// The keys law `kind` reads, in table order: "mu_c, s_c" (paper), "points" (table).
std::string friction_parameter_names(FrictionLawKind kind);

const char* to_string(FrictionLawKind kind);
bool parse_friction_law_kind(const std::string& name, FrictionLawKind& out);
// All law names joined by `separator`: "paper, linearized, coulomb, table".
std::string friction_law_names(const char* separator);

// mu(s) of the law before the clamp; may be negative.
double raw_friction_coefficient(const FrictionLaw& law, double s);

// mu(s) clamped at 0: friction never propels (physics.md section 4).
inline double friction_coefficient(const FrictionLaw& law, double s) {
  const double mu = raw_friction_coefficient(law, s);
  return mu > 0.0 ? mu : 0.0;
}

// d mu / d s of the clamped law (one-sided from the right at kinks).
double friction_slope(const FrictionLaw& law, double s);

// Empty when the parameters are admissible, else "field = value: allowed range".
std::string validate(const FrictionLaw& law);

// A change of friction law as a command carries it: the law (absent: the law in force's) and the parameters it
// names (and a table's points). The core applies it to the law in force at the step boundary (apply_command).
struct FrictionChange {
  std::optional<FrictionLawKind> kind;
  std::vector<std::pair<const FrictionParameter*, double>> given;
  std::optional<std::vector<std::pair<double, double>>> points;
};

// The one rule of every change (TopCommand, Python's apply, dynamic_reconfigure, scene events): the parameters a
// change does not name keep their values in the law in force (a table keeps its points unless new ones are given).
FrictionLaw changed_law(const FrictionLaw& in_force, const FrictionChange& change);

// Empty when every parameter the change names belongs to the law it leads to, else "friction.name: ...".
std::string validate(const FrictionChange& change, const FrictionLaw& in_force);

// True when the law gives mu(s) < 0 somewhere on [0, 1] (so the clamp is active there).
bool clamp_is_active(const FrictionLaw& law);

// Largest mu(s) on [0, 1]: tan(alpha_c) for laws whose maximum bounds the sleeping states.
double max_friction_coefficient(const FrictionLaw& law);

}  // namespace top_sim
