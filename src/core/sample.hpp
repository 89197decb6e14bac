// A sample: what a reader sees of one state, each derived value once (physics.md section 10 for the regime).
#pragma once

#include "top_sim/contact_modes.hpp"
#include "top_sim/dynamics.hpp"
#include "energy.hpp"
#include "top_sim/regime.hpp"
#include "top_sim/snapshot.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

// What one sample derives from a state, each once: the dynamics in the contact mode, the sleeping state at the
// state's shell spin, and the regime indicators (zero for the adiabatic model) that the classification reads.
struct SampleAnalysis {
  Dynamics dynamics;
  StationaryState stationary;
  RegimeIndicators indicators;
  double energy = 0.0;  // mechanical energy E [J]
};

// `geometry`: the model's stationary_geometry(), solved once per model change.
SampleAnalysis analyse_sample(const Model& model, ContactMode mode, const StateVector& y,
                              const StationaryGeometry& geometry);
// The same, from y's dynamics (evaluate_dynamics in `mode`) and energy evaluated already.
SampleAnalysis analyse_sample(const Model& model, ContactMode mode, const StateVector& y,
                              const StationaryGeometry& geometry, const Dynamics& dynamics, double energy);
// What a regime point needs of a state: the dynamics, the indicators and the energy, with no stationary solve
// (the indicators read only the model's answer, exists and slip_unstable, which no spin changes).
SampleAnalysis regime_point_analysis(const Model& model, ContactMode mode, const StateVector& y,
                                     const StationaryState& model_stationary);
// The part of an analysis of a finite state that is not finite (products of large speeds overflow), or nullptr.
const char* overflowed_part(const SampleAnalysis& a);

// Snapshot of a state of a model from its analysis and its regime (classified by the caller, with hysteresis).
// `geometry` is stationary_geometry(model), the Simulator's.
Snapshot make_snapshot(const Model& model, const StationaryGeometry& geometry, const StateVector& y, double t,
                       const EnergyBalance& balance, const SampleAnalysis& analysis, Regime regime, ContactMode mode);

}  // namespace top_sim
