#include "moreau/fluids/fluid_velocity.hpp"

#include "moreau/model/model.hpp"

namespace moreau {

Vec3 fluid_vorticity(const Model& model, const FluidState& fluid, Index i) {
  const FluidModel& fm = model.fluid;
  const CubicSplineKernel& kernel = fm.kernel;
  const Vec3 xi = fluid.position[i], vi = fluid.velocity[i];
  Vec3 omega = Vec3::Zero();
  const Index* row = fluid.fluid_neighbors.row(i);
  for (Index k = 0; k < fluid.fluid_neighbors.count[i]; ++k) {
    const Index j = row[k];
    const Vec3 r = xi - fluid.position[j];
    const Real d2 = r.squaredNorm();
    if (d2 >= kernel.h2) continue;
    omega += (vi - fluid.velocity[j]).cross(kernel.gradient_factor(std::sqrt(d2)) * r);
  }
  return fm.particle_volume * omega;
}

void apply_fluid_velocity_corrections(const Model& model, FluidState& fluid, Real dt) {
  const FluidModel& fm = model.fluid;
  bool any_viscosity = false, any_xsph = false, any_vorticity = false;
  for (const FluidPhase& p : fm.phases) {
    any_viscosity |= p.viscosity > 0;
    any_xsph |= p.xsph > 0;
    any_vorticity |= p.vorticity > 0;
  }
  if (!any_viscosity && !any_xsph && !any_vorticity) return;

  const CubicSplineKernel kernel = fm.kernel;
  const Real V = fm.particle_volume;
  const Real eta2 = 0.01 * kernel.h2;
  const Index n = fluid.count;
  const Vec3* x = fluid.position.data();
  const Vec3* v = fluid.velocity.data();
  std::vector<Vec3>& omega = fluid.correction;  // free between steps: holds the vorticity here
  if (any_vorticity) {
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i) omega[i] = fluid_vorticity(model, fluid, i);
  }

  std::vector<Vec3>& v_new = fluid.scratch_vec;
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const FluidPhase& pi = fm.phases[fluid.phase[i]];
    const Vec3 xi = x[i], vi = v[i];
    const Real w_i = fluid.inv_mass[i];
    const Real omega_i = any_vorticity ? omega[i].norm() : 0;
    Vec3 viscous = Vec3::Zero(), smoothing = Vec3::Zero(), eta = Vec3::Zero();
    const Index* row = fluid.fluid_neighbors.row(i);
    const Index count = fluid.fluid_neighbors.count[i];
    for (Index k = 0; k < count; ++k) {
      const Index j = row[k];
      const Vec3 r = xi - x[j];
      const Real r2 = r.squaredNorm();
      if (r2 >= kernel.h2) continue;
      Real wij, g;
      kernel.evaluate(r2, wij, g);
      const Vec3 vij = vi - v[j];
      const Real mu = 2 * w_i / (w_i + fluid.inv_mass[j]);
      const Real nu = 0.5 * (pi.viscosity + fm.phases[fluid.phase[j]].viscosity);
      viscous += (mu * nu * vij.dot(r) / (r2 + eta2) * g) * r;
      smoothing -= (mu * wij) * vij;
      if (any_vorticity) eta += ((omega[j].norm() - omega_i) * g) * r;
    }
    Vec3 vi_new = vi + (dt * 10 * V) * viscous + (pi.xsph * V) * smoothing;
    const Real eta_norm = eta.norm();
    if (pi.vorticity > 0 && eta_norm > 0) vi_new += dt * pi.vorticity * (eta / eta_norm).cross(omega[i]);
    v_new[i] = vi_new;
  }
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) fluid.velocity[i] = v_new[i];
}

}  // namespace moreau
