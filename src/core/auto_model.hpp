// model.kind auto (physics.md section 7.1): when the full model may hand a sleeping top over to the reduced model
// of section 7, the state it hands over, and when the reduced model stays valid.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>

#include "top_sim/model.hpp"
#include "top_sim/stability.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// The linearisation of the full model at the sleeping state of one shell spin (section 10), split into the modes
// that decay (they move the contact point by a finite offset, then vanish) and those that persist (the free spin,
// the rotor's bearing: the reduced model carries them on).
struct Reduction {
  bool valid = false;
  std::string reason;                 // why the reduced model is not valid here, when !valid
  double spin = std::numeric_limits<double>::quiet_NaN();  // the shell spin analysed [rad/s]
  double relaxation_time = std::numeric_limits<double>::infinity();  // 1 / |Re| of the slowest decaying mode [s]
  ReducedCoordinates coords;
  Eigen::VectorXd z_star;             // the sleeping state's reduced coordinates
  Eigen::MatrixXd offset;             // 2 x n: the contact point's remaining offset per deviation dz [m]
  Eigen::MatrixXd persisting;         // n x n: the part of dz that does not decay
};

// A reduction stays in use while the shell spin is within this fraction of the analysed one.
constexpr double kReanalysedSpin = 1.0e-2;

// The reduction at the sleeping state of y's shell spin (and rotor spin), for the model's full kind. Valid when
// that state exists, is linearly stable and the bearing drags the spin slowly enough: the full model lags behind
// the sleeping state by |u*| |spin'| / |spin| T_relax in velocity for as long as the bearing drags (1 / its decay
// rate c (1/J + 1/I_f')), which must move the contact point by at most model.auto_tolerance.
// `geometry` is stationary_geometry(model) (the Simulator holds it; it does not depend on the model's kind).
Reduction analyse_reduction(const Model& model, const StationaryGeometry& geometry, const StateVector& y);

// Whether r was analysed at about y's spin (within kReanalysedSpin).
bool reduction_applies(const Reduction& r, const StateVector& y);

// The full model's predicted remaining offset of the contact point from y (the decaying modes) [m]: cheap, for the
// criterion at every cadence point; handover() repeats it and builds the state.
Eigen::Vector2d remaining_offset(const Reduction& r, const StateVector& y);

// The full model's state y handed over to the reduced model: the contact point moved by the predicted remaining
// offset of the decaying modes, the persisting ones kept, and u, f_hat, omega put on the sleeping state.
struct Handover {
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();  // the predicted remaining offset of the contact point [m]
  StateVector y{};
};
Handover handover(const Model& model, const StationaryGeometry& geometry, const Reduction& r, const StateVector& y);

}  // namespace top_sim
