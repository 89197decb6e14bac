// Dry-friction laws mu(s) of physics.md section 4.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace top_sim {

enum class FrictionLawKind { paper, linearized, coulomb, table };

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

const char* to_string(FrictionLawKind kind);
bool parse_friction_law_kind(const std::string& name, FrictionLawKind& out);

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

// True when the law gives mu(s) < 0 somewhere on [0, 1] (so the clamp is active there).
bool clamp_is_active(const FrictionLaw& law);

// Largest mu(s) on [0, 1]: tan(alpha_c) for laws whose maximum bounds the sleeping states.
double max_friction_coefficient(const FrictionLaw& law);

}  // namespace top_sim
