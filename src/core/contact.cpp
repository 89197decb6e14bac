// Contact kinematics and faults (physics.md sections 3 and 4).
#include "top_sim/contact.hpp"
#include "top_sim/contact_shapes.hpp"
#include "top_sim/format.hpp"

#include <cmath>
#include <sstream>

namespace top_sim {

const char* to_string(ContactFault fault) {
  switch (fault) {
    case ContactFault::none: return "none";
    case ContactFault::painleve: return "painleve";
    case ContactFault::numerical: return "numerical";
  }
  return "?";
}

std::string describe(ContactFault fault, double value, double t) {
  std::ostringstream os;
  os << "t = " << format_number(t) << " s: ";
  switch (fault) {
    case ContactFault::none: os << "no contact fault"; break;
    case ContactFault::painleve:
      os << "Painleve: the rigid contact has no unique normal force (m n.K d = " << value
         << " <= 0); reduce the friction";
      break;
    case ContactFault::numerical:
      os << "numerical failure: the integrator produced a non-finite state or could not find a step; "
            "use a smaller dt or another method";
      break;
  }
  return os.str();
}

}  // namespace top_sim

namespace top_sim {

const char* to_string(EndState state) {
  switch (state) {
    case EndState::lying_flat: return "lying_flat";
    case EndState::at_rest: return "at_rest";
    case EndState::fallen: return "fallen";
    case EndState::none: break;
  }
  return "none";
}

std::string describe(EndState state, double margin, double t) {
  std::ostringstream os;
  os << "t = " << format_number(t) << " s: ";
  if (state == EndState::lying_flat)
    os << "end state lying_flat: the rim lies flat (the tilt's sine is " << format_number(margin + kFlatEndSine)
       << ", below " << format_number(kFlatEndSine) << ")";
  else if (state == EndState::at_rest)
    os << "end state at_rest: the body rests on two shapes (its speeds and accelerations are below the rest "
          "thresholds, margin " << format_number(margin) << ")";
  else if (state == EndState::fallen)
    os << "end state fallen: the figure axis passed max_tilt from the plane normal with no shape to catch the body "
          "(n . f_hat - cos(max_tilt) = " << format_number(margin) << ")";
  else
    os << "no end state";
  return os.str();
}

}  // namespace top_sim
