#pragma once
// The viscosity where two liquids of different viscosity meet.
//
// Across a phase interface the viscosity jumps while the shear stress is continuous, so the
// velocity gradient jumps with it: the layers on either side are sheared in series, and the
// viscosity of the pair is the harmonic mean of the two, 2 mu_i mu_j / (mu_i + mu_j), as in
// multi-phase SPH (Hu & Adams 2006, "A multi-phase SPH method for macroscopic and mesoscopic
// flows", J. Comput. Phys. 213). A drop of honey smaller than a kernel then shears the water about
// it with about twice water's viscosity, as a small rigid drop would; the arithmetic mean gave the
// water next to it half the honey's. Within one phase nothing changes: the viscosity varies only
// with the temperature there, smoothly, and the pairs keep the mean of the two.
#include <cmath>

#include "moreau/fluids/fluid_model.hpp"
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

/// mu_k = rho0 nu_k, Pa s: particle k's dynamic viscosity (its phase's, or its state's).
inline Real dynamic_viscosity(const FluidModel& fm, const FluidState& fluid, Index k) {
  return fluid.viscosity[k] * fm.phases[fluid.phase[k]].rest_density;
}

/// nu_ij, m^2/s, of a pair of the explicit Laplacian and of the implicit viscosity's stabilising
/// term, where particle i's change is mu nu_ij (...) with mu = 2 m_j / (m_i + m_j). Within a phase
/// the mean of the two kinematic viscosities. Between phases the harmonic mean of the dynamic
/// ones, mu_ij, written as nu_ij = mu_ij / rho_ij with rho_ij the harmonic mean of the rest
/// densities, so that m_i mu nu_ij = V mu_ij: the pair's momentum exchange has the viscosity mu_ij.
inline Real pair_viscosity(const FluidModel& fm, const FluidState& fluid, Index i, Index j) {
  const Index phase_i = fluid.phase[i], phase_j = fluid.phase[j];
  if (phase_i == phase_j) return 0.5 * (fluid.viscosity[i] + fluid.viscosity[j]);
  const Real rho_i = fm.phases[phase_i].rest_density, rho_j = fm.phases[phase_j].rest_density;
  const Real mu_i = dynamic_viscosity(fm, fluid, i), mu_j = dynamic_viscosity(fm, fluid, j);
  if (mu_i <= 0 || mu_j <= 0) return 0;
  // mu_ij / rho_ij = (2 mu_i mu_j / (mu_i + mu_j)) (rho_i + rho_j) / (2 rho_i rho_j)
  return mu_i * mu_j * (rho_i + rho_j) / ((mu_i + mu_j) * rho_i * rho_j);
}

/// mu_k, Pa s, of particle k's stress in the implicit viscosity (fluid_viscosity.hpp): its own
/// dynamic viscosity, except where its kernel holds particles of another phase. There the stress
/// 2 mu_k sym(G_k) takes a velocity gradient averaged over both sides, so a particle's own
/// viscosity would spread over its whole kernel (one particle of honey in water would stiffen the
/// water a kernel around it); instead mu_k is the kernel-weighted harmonic mean of the viscosities
/// in the kernel, the series average,
///   1 / mu_k = sum_j W_kj / mu_j / sum_j W_kj       (j over the fluid particles in the kernel, k included),
/// whose integral across a flat interface is that of 1 / mu: the layers' shear in series. The cost
/// is in shear along the interface, where each liquid keeps its own stress: there the viscous
/// liquid's particles within a kernel of the other shear as the thinner mix does. Next to an
/// inviscid liquid (mu = 0) the mean is 0: the interface slips freely, and a kernel-deep skin of
/// the viscous liquid carries no viscous stress of its own.
inline Real stress_viscosity(const FluidModel& fm, const FluidState& fluid, Index k) {
  const Real mu_k = dynamic_viscosity(fm, fluid, k);
  const CubicSplineKernel& kernel = fm.kernel;
  const Vec3 xk = fluid.position[k];
  const Index* row = fluid.fluid_neighbors.row(k);
  bool mixed = false;
  Real weight = kernel.value(0), fluidity = 0;  // sum_j W_kj, sum_j W_kj / mu_j without k's own term
  for (Index n = 0; n < fluid.fluid_neighbors.count[k]; ++n) {
    const Index j = row[n];
    const Real d2 = (xk - fluid.position[j]).squaredNorm();
    if (d2 >= kernel.h2) continue;  // the lists also hold pairs in the Verlet skin beyond h
    mixed = mixed || fluid.phase[j] != fluid.phase[k];
    const Real w = kernel.value(std::sqrt(d2)), mu_j = dynamic_viscosity(fm, fluid, j);
    weight += w;
    fluidity = mu_j > 0 ? fluidity + w / mu_j : kInfinity;
  }
  if (!mixed) return mu_k;
  // An inviscid liquid in the kernel: the series has no resistance.
  if (mu_k <= 0 || fluidity == kInfinity) return 0;
  return weight / (fluidity + kernel.value(0) / mu_k);
}

}  // namespace moreau
