#pragma once
// Solids immersed in a FEM fluid (a "fluid" beside "solid" and "rigid_body" objects in one
// "solver": "fem" scene). The fluid fills the whole domain and its mesh never moves; each solid is
// a Lagrangian mesh carried by the fluid's velocity and acting on the fluid as a momentum source
// (immersed_coupling.hpp has the equations). The solids reuse the FEM solids' model: meshes,
// hyperelastic materials, reference quadrature and consistent mass, and Dirichlet conditions
// (a clamped leaflet base) as prescribed displacements.
// A rigid body is one of those meshes moved rigidly by a director frame instead of by the fluid
// (immersed_rigid_body.hpp): its nodes are where it meets the fluid, and its material has no
// stiffness (its stress is zero: it cannot deform).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "moreau/fem/solids/fem_model.hpp"

namespace moreau {

/// A driven body's motion, functions of time t (s): its centre's velocity (m/s) and its angular
/// velocity (rad/s, world axes; 2D: only z).
struct PrescribedRigidMotion {
  std::function<Vec3(Real)> velocity, angular_velocity;
};

/// A rigid body's frame: q = (phi, d_1, ..., d_dim), its centre of mass and directors that start
/// along the world axes, so a node at X sits at x = phi + sum_i (X - centre)_i d_i.
struct ImmersedRigidBody {
  Index solid = -1;           // its mesh: model.solids[solid]
  Vec3 centre = Vec3::Zero(); // reference centre of mass, m
  Eigen::MatrixXd excess_mass;// the frame's mass matrix for the density rho_s - rho_f (kg, kg m, kg m^2)
  Eigen::MatrixXd fluid_mass; // the same for the fluid's density: the fluid the body holds inside it
  VectorX nodal_volume;       // per node of its mesh: the volume it stands for, m^3 (2D: m^2 per m)
  Real coupling_stiffness = 0;// k, Pa s/m^2: force per volume per unit slip between the fluid and the body
  std::optional<PrescribedRigidMotion> motion;  // set: a driven body, its motion given; empty: free
};

struct ImmersedSolids {
  FemModel model;                // the solids (material.density is the solid's density), never changed by a run
  std::vector<Real> viscosity;   // per solid, Pa s: the solid's own (Kelvin-Voigt) viscosity
  std::vector<ImmersedRigidBody> rigid_bodies;

  /// The rigid body that moves solid s, or null if the fluid carries it.
  const ImmersedRigidBody* rigid_body_of(size_t s) const {
    for (const ImmersedRigidBody& b : rigid_bodies)
      if (static_cast<size_t>(b.solid) == s) return &b;
    return nullptr;
  }
};

/// What a step advances: per solid dof, the displacement u_n (m) and the material velocity V_n
/// (m/s) of the last accepted step, at its time; per rigid body its frame q and velocity dq/dt;
/// per solid (index in model.solids) the force the fluid exerted on it over that step and, for a
/// rigid body, the torque about its centre (zero for a deformable solid); per fluid dof, the
/// solids' forces on the fluid over that step (their residual R_src: where it falls on a wall's
/// prescribed dofs, the wall takes it).
struct ImmersedSolidState {
  VectorX displacement, velocity;
  Real time = 0;  // s, the time of u_n (Dirichlet conditions are functions of it)
  std::vector<VectorX> frame, frame_velocity;
  std::vector<Vec3> fluid_force, fluid_torque;  // N and N m (2D: per m of depth)
  VectorX fluid_source;                         // N (2D: per m of depth); empty before the first step
};

/// The solids at rest in their reference configuration at t = 0.
ImmersedSolidState initial_immersed_state(const ImmersedSolids& solids);

}  // namespace moreau
