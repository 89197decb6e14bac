// Mechanical energy and the energy balance E + W_diss (physics.md section 4).
#pragma once

#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// E = kinetic (translation, shell, rotor) + potential m g z_cm (world height).
double mechanical_energy(const Model& model, const StateVector& y);

// Origin-free energy scale for the relative residual: kinetic energy plus m g (R + |f|).
double energy_scale(const Model& model, const StateVector& y);

// Conserved-quantity bookkeeping: re-based at every command (commands inject energy).
struct EnergyBalance {
  double reference = 0.0;  // E + W_diss at the last re-base
  double scale = 1.0;

  void rebase(const Model& model, const StateVector& y);
  // |E + W_diss - reference| / scale, from the energy E = mechanical_energy(model, y) its caller has evaluated
  double residual(double energy, const StateVector& y) const;
};

}  // namespace top_sim
