#include "moreau/fluids/fluid_velocity.hpp"

#include "moreau/fluids/fluid_viscosity.hpp"
#include "moreau/fluids/interface_viscosity.hpp"
#include "moreau/fluids/neighbor_loop.hpp"
#include "moreau/fluids/pair_chunks.hpp"
#include "moreau/math/target_clones.hpp"
#include "moreau/model/model.hpp"

namespace moreau {

Vec3 fluid_vorticity(const Model& model, const FluidState& fluid, Index i) {
  const FluidModel& fm = model.fluid;
  const CubicSplineKernel& kernel = fm.kernel;
  const Vec3 vi = fluid.velocity[i];
  Vec3 omega = Vec3::Zero();
  for_each_fluid_neighbor(fluid, kernel, i,
                          [&](Index j, const Vec3& r, Real g) { omega += (vi - fluid.velocity[j]).cross(g * r); });
  return fm.particle_volume * omega;
}

MOREAU_TARGET_CLONES
void apply_fluid_velocity_corrections(const Model& model, FluidState& fluid, FluidScratch& scratch, Real dt) {
  const FluidModel& fm = model.fluid;
  bool any_xsph = false, any_vorticity = false;
  const bool any_viscosity = fluid_has_viscosity(model);
  for (const FluidPhase& p : fm.phases) {
    any_xsph |= p.xsph > 0;
    any_vorticity |= p.vorticity > 0;
  }
  // The implicit viscosity is applied by the formulation (apply_implicit_fluid_viscosity); the
  // explicit one is a pair term of the loop below.
  const bool explicit_viscosity = any_viscosity && fm.viscosity_solver == ViscositySolver::explicit_update;
  if (!explicit_viscosity && !any_xsph && !any_vorticity) return;

  const CubicSplineKernel kernel = fm.kernel;
  const Real V = fm.particle_volume, pad = 2 * kernel.h;
  const Real eta2 = 0.01 * kernel.h2;
  const Index n = fluid.count;
  const Vec3* x = fluid.position.data();
  const Vec3* v = fluid.velocity.data();
  std::vector<Vec3>& omega = scratch.correction;        // free between steps: the vorticity here
  std::vector<Real>& omega_norm = scratch.reorder_real;  // and its magnitude
  if (any_vorticity) {
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i) {
      omega[i] = fluid_vorticity(model, fluid, i);
      omega_norm[i] = omega[i].norm();
    }
  }

  // Every particle has the same viscosity (one for every phase, none melts): nu_ij needs no lookups.
  bool one_viscosity = true;
  for (const FluidPhase& phase : fm.phases)
    one_viscosity &= phase.viscosity == fm.phases[0].viscosity && !phase.melting_point;
  std::vector<Vec3>& v_new = scratch.reorder_vec;
  const Real* w = fluid.inv_mass.data();
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const FluidPhase& pi = fm.phases[fluid.phase[i]];
    const Vec3 xi = x[i], vi = v[i];
    const Real w_i = w[i];
    if (w_i == 0) {  // a solid particle or one held in a nozzle keeps its velocity
      v_new[i] = vi;
      continue;
    }
    const Real omega_i = any_vorticity ? omega_norm[i] : 0;
    // nu_ij is the pair's viscosity (interface_viscosity.hpp); XSPH uses particle i's coefficient.
    PairChunk chunk;
    alignas(64) Real vx[kPairChunk], vy[kPairChunk], vz[kPairChunk], nu[kPairChunk];
    alignas(64) Real visc_x[kPairChunk] = {}, visc_y[kPairChunk] = {}, visc_z[kPairChunk] = {};
    alignas(64) Real smooth_x[kPairChunk] = {}, smooth_y[kPairChunk] = {}, smooth_z[kPairChunk] = {};
    alignas(64) Real eta_x[kPairChunk] = {}, eta_y[kPairChunk] = {}, eta_z[kPairChunk] = {};
    const Index* row = fluid.fluid_neighbors.row(i);
    const Index count = fluid.fluid_neighbors.count[i];
    for (Index begin = 0; begin < count; begin += kPairChunk) {
      chunk.load(xi, x, row, begin, count, pad, w, any_vorticity ? omega_norm.data() : nullptr);
      // Pad lanes hold the row's first neighbour (FixedStrideLists); their kernel values are zero.
      const Index* lanes = row + begin;
      const Real* vs = v->data();
      gather_into(vx, vs, lanes, 3, 0);
      gather_into(vy, vs, lanes, 3, 1);
      gather_into(vz, vs, lanes, 3, 2);
      if (!explicit_viscosity)
        store(nu, Lanes{});
      else if (one_viscosity)
        store(nu, Lanes{} + pi.viscosity);
      else
        for (int k = 0; k < kPairChunk; ++k) nu[k] = pair_viscosity(fm, fluid, i, lanes[k]);
      chunk.evaluate(kernel);
#pragma omp simd
      for (int k = 0; k < kPairChunk; ++k) {
        // Pad lanes have w = g = 0 and inverse mass 0 (mu = 2): every term vanishes.
        const Real dvx = vi.x() - vx[k], dvy = vi.y() - vy[k], dvz = vi.z() - vz[k];
        const Real mu = 2 * w_i / (w_i + chunk.a[k]);
        const Real r2 = chunk.rx[k] * chunk.rx[k] + chunk.ry[k] * chunk.ry[k] + chunk.rz[k] * chunk.rz[k];
        const Real visc = mu * nu[k] * (dvx * chunk.rx[k] + dvy * chunk.ry[k] + dvz * chunk.rz[k]) / (r2 + eta2) * chunk.g[k];
        visc_x[k] += visc * chunk.rx[k], visc_y[k] += visc * chunk.ry[k], visc_z[k] += visc * chunk.rz[k];
        const Real smooth = mu * chunk.w[k];
        smooth_x[k] -= smooth * dvx, smooth_y[k] -= smooth * dvy, smooth_z[k] -= smooth * dvz;
        const Real e = (chunk.b[k] - omega_i) * chunk.g[k];
        eta_x[k] += e * chunk.rx[k], eta_y[k] += e * chunk.ry[k], eta_z[k] += e * chunk.rz[k];
      }
    }
    const Vec3 viscous(sum_lanes(visc_x), sum_lanes(visc_y), sum_lanes(visc_z));
    const Vec3 smoothing(sum_lanes(smooth_x), sum_lanes(smooth_y), sum_lanes(smooth_z));
    Vec3 vi_new = vi + (dt * 10 * V) * viscous + (pi.xsph * V) * smoothing;
    if (pi.vorticity > 0) {
      const Vec3 eta(sum_lanes(eta_x), sum_lanes(eta_y), sum_lanes(eta_z));
      const Real eta_norm = eta.norm();
      if (eta_norm > 0) vi_new += dt * pi.vorticity * (eta / eta_norm).cross(omega[i]);
    }
    v_new[i] = vi_new;
  }
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) fluid.velocity[i] = v_new[i];
}

}  // namespace moreau
