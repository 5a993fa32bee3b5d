#include "moreau/fluids/interfacial_tension.hpp"

#include <cmath>

#include "moreau/fluids/neighbor_loop.hpp"
#include "moreau/model/model.hpp"

namespace moreau {

namespace {

// |g| h below which a particle has no normal (Morris 2000: 0.01 / h); its neighbours' curvature
// skips it, since a few far neighbours of the other liquid give no reliable direction.
constexpr Real kNormalThreshold = 0.01;

}  // namespace

void apply_fluid_interfacial_tension(const Model& model, FluidState& fluid, FluidScratch& scratch, Real dt) {
  const FluidModel& fm = model.fluid;
  if (fm.interfaces.empty()) return;
  const CubicSplineKernel& kernel = fm.kernel;
  const Real V = fm.particle_volume, smallest_gradient = kNormalThreshold / kernel.h;
  const Index n = fluid.count;
  std::vector<Vec3>& gradient = scratch.correction;  // free between steps (after the surface tension)
  std::vector<Vec3>& normal = scratch.reorder_vec;  // free after the surface tension's velocity pass
  std::vector<Real>& curvature = scratch.reorder_real;

  for (const FluidInterface& face : fm.interfaces) {
    // +1 on side A, -1 on side B, 0 for particles of neither liquid.
    auto side = [&](Index i) -> int { return fluid.phase[i] == face.phase_a ? 1 : fluid.phase[i] == face.phase_b ? -1 : 0; };
    // Calls pair(j, r, g, s_j) for the neighbours j of i within h of either liquid (neighbor_loop.hpp).
    auto for_each_interface_pair = [&](Index i, auto&& pair) {
      for_each_fluid_neighbor(fluid, kernel, i, [&](Index j, const Vec3& r, Real g) {
        if (const int s_j = side(j)) pair(j, r, g, s_j);
      });
    };

    // g_i = -V sum_{j other} grad W_ij: the gradient of i's own colour.
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i) {
      const int s = side(i);
      Vec3 sum = Vec3::Zero();
      if (s != 0)
        for_each_interface_pair(i, [&](Index, const Vec3& r, Real g, int s_j) {
          if (s_j != s) sum += g * r;
        });
      gradient[i] = -V * sum;
    }

    // n_i = g_i / |g_i|, or zero where |g_i| is below the threshold.
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i) {
      const Real size = gradient[i].norm();
      normal[i] = size > smallest_gradient ? Vec3(gradient[i] / size) : Vec3::Zero();
    }

    // kappa_i = -3 sum_j (n_j - n_i) . grad W_ij / sum_j |x_ij| |grad W_ij| over neighbours with a normal.
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i) {
      curvature[i] = 0;
      const int s = side(i);
      if (s == 0 || normal[i].isZero(0)) continue;
      Real divergence = 0, weight = 0;
      for_each_interface_pair(i, [&](Index j, const Vec3& r, Real g, int s_j) {  // grad W_ij = g r, g < 0
        if (normal[j].isZero(0)) return;
        const Vec3 normal_j = s_j == s ? normal[j] : Vec3(-normal[j]);  // in i's colour
        divergence += (normal_j - normal[i]).dot(g * r);
        weight += -g * r.squaredNorm();                               // |x_ij| |grad W_ij|
      });
      if (weight > 0) curvature[i] = -3 * divergence / weight;
    }

    // v_i += dt sigma kappa_i g_i / rho0_i (not for solid or held particles).
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i) {
      if (curvature[i] == 0 || fluid.inv_mass[i] == 0) continue;
      const Real rho0 = fm.phases[fluid.phase[i]].rest_density;
      fluid.velocity[i] += dt * face.tension * curvature[i] / rho0 * gradient[i];
    }
  }
}

}  // namespace moreau
