#include "moreau/fluids/solid_coupling.hpp"

#include <algorithm>
#include <cmath>

#include "moreau/collision/collider.hpp"
#include "moreau/fluids/pair_chunks.hpp"
#include "moreau/fluids/solid_gather.hpp"
#include "moreau/model/state.hpp"
#include "moreau/rigid/body_handle.hpp"

namespace moreau {

namespace {

// dx_p = w_p sum_s b_ps R_s for every particle of a coupled solid. Every thread.
void move_solid_particles(const Model& model, const FluidScratch& scratch, Vec3* x) {
  gather_to_solid_particles(model, scratch.solid_reaction.data(),
                            [&](Index p, Real w, const Vec3& reaction) { x[p] += w * reaction; });
}

// Each dynamic sampled body takes the reactions of its samples (see the header). Every thread;
// orphaned omp for over the bodies, each summing its own samples in order.
void move_rigid_bodies(const Model& model, const FluidState& fluid, const FluidScratch& scratch,
                       RigidBodyState& rigid) {
  const FluidSolidSamples& s = model.fluid.solid;
  const Index bodies = static_cast<Index>(s.sampled_body.size());
#pragma omp for schedule(static)
  for (Index j = 0; j < bodies; ++j) {
    const Index b = s.sampled_body[j];
    if (!model.rigid.is_dynamic(b)) continue;
    Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
    for (Index k = s.body_begin[j]; k < s.body_begin[j + 1]; ++k) {
      force += scratch.solid_reaction[k];
      moment += (fluid.solid_position[k] - rigid.position[b]).cross(scratch.solid_reaction[k]);
    }
    const BodyHandle body = rigid_body_handle(model.rigid, rigid, b);
    body.apply_position_impulse(force, Vec3::Zero());
    body.apply_angular_impulse(moment);
  }
}

void move_solids(const Model& model, State& state, const FluidScratch& scratch) {
  move_solid_particles(model, scratch, state.position.data());
  if (!model.fluid.solid.sampled_body.empty()) move_rigid_bodies(model, state.fluid, scratch, state.rigid);
}

}  // namespace

void place_solid_samples(const Model& model, State& state) {
  const FluidSolidSamples& s = model.fluid.solid;
  FluidState& fluid = state.fluid;
  const Vec3* x = state.position.data();
  const RigidBodyState& rigid = state.rigid;
  const Index n = s.size();
#pragma omp for schedule(static)
  for (Index k = 0; k < n; ++k) {
    const Index body = s.body[k];
    if (body >= 0) {
      fluid.solid_position[k] = rigid.position[body] + rigid.orientation[body] * s.body_point[k];
      continue;
    }
    const auto& p = s.particle[k];
    const auto& b = s.weight[k];
    fluid.solid_position[k] = b[0] * x[p[0]] + b[1] * x[p[1]] + b[2] * x[p[2]] + b[3] * x[p[3]];
  }
}

void split_solid_masses(const Model& model, const FluidState& fluid, FluidScratch& scratch) {
  const FluidSolidSamples& s = model.fluid.solid;
  const Index particles = static_cast<Index>(s.coupled_particle.size()), samples = s.size();
  // c_k = max(1, sum_s b_sk n_s), n_s the fluid particles within h of sample s.
#pragma omp for schedule(static)
  for (Index q = 0; q < particles; ++q) {
    Real pairs = 0;
    for (Index e = s.coupled_begin[q]; e < s.coupled_begin[q + 1]; ++e)
      pairs += s.coupled_weight[e] * fluid.solid_fluids.count[s.coupled_sample[e]];
    scratch.solid_share[s.coupled_particle[q]] = 1 / std::max<Real>(1, pairs);
  }
  // Rigid samples: w_s = w_bs / c_b, c_b = max(1, sum_s n_s) over the body's samples.
  const Index bodies = static_cast<Index>(s.sampled_body.size());
#pragma omp for schedule(static)
  for (Index j = 0; j < bodies; ++j) {
    Real pairs = 0;
    for (Index k = s.body_begin[j]; k < s.body_begin[j + 1]; ++k) pairs += fluid.solid_fluids.count[k];
    const Real share = 1 / std::max<Real>(1, pairs);
    for (Index k = s.body_begin[j]; k < s.body_begin[j + 1]; ++k) scratch.solid_inv_mass[k] = s.body_weight[k] * share;
  }
  // Cloth and soft-body samples: w_s = sum_k b_k^2 w_k / c_k.
#pragma omp for schedule(static)
  for (Index k = 0; k < samples; ++k) {
    if (s.body[k] >= 0) continue;
    Real w = 0;
    for (int slot = 0; slot < 4; ++slot) {
      const Index p = s.particle[k][slot];
      const Real b = s.weight[k][slot];
      if (b != 0) w += b * b * model.particle_inv_mass[p] * scratch.solid_share[p];
    }
    scratch.solid_inv_mass[k] = w;
  }
}

void apply_solid_reactions(const Model& model, State& state, FluidScratch& scratch) {
  FluidState& fluid = state.fluid;
  const FluidSolidSamples& s = model.fluid.solid;
  const CubicSplineKernel kernel = model.fluid.kernel;
  const Real pad = 2 * kernel.h;
  const Index n = s.size();
  const Vec3* xf = fluid.position.data();
  const Real* lambda = scratch.lambda.data();
  // R_s = -V_s sum_i lambda_i grad W(x_i - x_s), with grad W(r) = g(|r|) r.
#pragma omp for schedule(static)
  for (Index k = 0; k < n; ++k) {
    const Index* row = fluid.solid_fluids.row(k);
    const Index count = fluid.solid_fluids.count[k];
    const Vec3 xs = fluid.solid_position[k];
    PairChunk chunk;
    alignas(64) Real rx[kPairChunk] = {}, ry[kPairChunk] = {}, rz[kPairChunk] = {};
    for (Index begin = 0; begin < count; begin += kPairChunk) {
      chunk.load(xs, xf, row, begin, count, pad, lambda);
      chunk.evaluate(kernel);
      #pragma omp simd
      for (int l = 0; l < kPairChunk; ++l) {
        // chunk.r = x_s - x_i = -(x_i - x_s)
        const Real c = chunk.a[l] * chunk.g[l];
        rx[l] += c * chunk.rx[l], ry[l] += c * chunk.ry[l], rz[l] += c * chunk.rz[l];
      }
    }
    scratch.solid_reaction[k] = s.volume[k] * Vec3(sum_lanes(rx), sum_lanes(ry), sum_lanes(rz));
  }
  move_solids(model, state, scratch);
}

void project_solid_contacts(const Model& model, State& state, FluidScratch& scratch, Real time) {
  FluidState& fluid = state.fluid;
  const FluidModel& fm = model.fluid;
  const FluidSolidSamples& s = fm.solid;
  const Real reach = fm.solid_contact_distance, reach2 = reach * reach;
  const Index n = fluid.count, samples = s.size();
  const Real* w = fluid.inv_mass.data();
  // The pair (i, s) in contact: p_is = (d_c - d) / (w_i + w_s) n_is / n_i, n_is = (x_i - x_s) / d.
  auto pair_share = [&](Index i, Index k, const Vec3& xi, Vec3& p) {
    const Vec3 r = xi - fluid.solid_position[k];
    const Real d2 = r.squaredNorm();
    if (d2 >= reach2) return false;
    const Real d = std::sqrt(d2);
    // A particle exactly on a sample (d ~ 0) has no direction of its own: push it "up" (against
    // gravity, or +y without gravity).
    const Vec3 up = model.settings.gravity.norm() > 0 ? Vec3(-model.settings.gravity.normalized()) : Vec3::UnitY();
    const Vec3 normal = d > 1e-9 * reach ? Vec3(r / d) : up;
    const Real weight = w[i] + scratch.solid_inv_mass[k];
    p = weight > 0 ? Vec3((reach - d) / weight * normal) : Vec3::Zero();  // 0: a solid fluid particle on a fixed solid
    return true;
  };
  // Fluid side: dx_i = w_i sum_s p_is (the contact count n_i kept for the solid side).
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Index* row = fluid.solid_neighbors.row(i);
    const Index count = fluid.solid_neighbors.count[i];
    const Vec3 xi = fluid.position[i];
    Vec3 sum = Vec3::Zero(), p;
    Index contacts = 0;
    for (Index e = 0; e < count; ++e)
      if (pair_share(i, row[e], xi, p)) sum += p, ++contacts;
    scratch.solid_contacts[i] = contacts;
    scratch.correction[i] = contacts > 0 ? Vec3(w[i] / contacts * sum) : Vec3::Zero();
  }
  // Solid side: R_s = -sum_i p_is.
#pragma omp for schedule(static)
  for (Index k = 0; k < samples; ++k) {
    const Index* row = fluid.solid_fluids.row(k);
    const Index count = fluid.solid_fluids.count[k];
    Vec3 sum = Vec3::Zero(), p;
    for (Index e = 0; e < count; ++e) {
      const Index i = row[e];
      if (pair_share(i, k, fluid.position[i], p)) sum -= p / scratch.solid_contacts[i];
    }
    scratch.solid_reaction[k] = sum;
  }
  move_solids(model, state, scratch);
  const Real r = fm.particle_radius;
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    if (scratch.solid_contacts[i] == 0 || fluid.inv_mass[i] == 0) continue;  // kinematic: on its course
    Vec3 xi = fluid.position[i] + scratch.correction[i];
    for (const Collider& c : model.colliders) xi = keep_clear_of_collider(c, c.position_at(time), xi, r);
    fluid.position[i] = xi;
  }
}

}  // namespace moreau
