#pragma once
// What the XPBD formulation keeps to itself between the stages of one step: buffers that are
// rewritten every substep or step and that nothing outside the solver reads. The State holds what
// a step changes and what a user, a probe or the next step reads (positions, velocities, the
// contact sets and the multipliers of the last substep); a checkpoint of the State is complete
// without this workspace.
#include <vector>

#include "moreau/collision/particle_contacts.hpp"
#include "moreau/constraints/substep_start.hpp"
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/math/types.hpp"
#include "moreau/rigid/rigid_motion.hpp"

namespace moreau {

struct Model;

struct XpbdWorkspace {
  std::vector<Vec3> substep_start;      // m, particle positions at the start of the current substep
  std::vector<Vec3> velocity_before;    // m/s, particle velocities after prediction (restitution)
  std::vector<Vec3> substep_turn;       // rad, per particle: the substep's rotation vector (grains turn)
  std::vector<Vec3> shape_match_lambda;   // per cluster entry: the substep's multiplier (kg m), shape_matching.hpp
  RigidSubstepStart bodies;             // body poses at the substep start, velocities after prediction
  std::vector<Real> joint_drive_start;  // per joint: hinge angle (rad) or slide (m) at the substep start
  ContactScratch contact_scratch;       // reused buffers of particle-pair detection
  FluidScratch fluid;                   // the particle fluid's substep and iteration buffers
  // 1/kg, per particle: the inverse masses of this step's projections (moving_inverse_mass), kept
  // only while an emitter holds particles in its nozzle; otherwise the model's are used.
  std::vector<Real> moving_inv_mass;

  /// Sizes the buffers for `model` (nothing is reallocated when they already fit).
  void fit(const Model& model);

  /// The configuration the friction rows measure their slip from.
  SubstepStart substep_start_view() const {
    return {substep_start.data(), bodies.position.data(), bodies.orientation.data()};
  }
};

}  // namespace moreau
