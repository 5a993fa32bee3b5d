#pragma once
// Fixtures for the tests of rigid bodies immersed in the FEM fluid: a closed box of fluid and one
// rigid body in it, free or driven.
#include <optional>
#include <utility>

#include "flow_test_helpers.hpp"
#include "immersed_test_meshes.hpp"
#include "moreau/fem/immersed/immersed_rigid_body.hpp"

namespace moreau::test {

/// The closed box [0, 1] x [0, 1.5] of 24 x 36 fluid cells (rho 1, mu 0.01 Pa s), no-slip walls,
/// gravity (0, -9.81) or none.
inline NavierStokesModel closed_box_fluid(bool gravity) {
  NavierStokesModel m;
  m.mesh = make_rectangle_mesh(Vec2(0, 0), Vec2(1, 1.5), {24, 36}, ElementType::quad4);
  m.density = 1;
  m.viscosity = 0.01;
  if (gravity) m.body_force = Vec3(0, -9.81, 0);
  for (const char* side : {"left", "right", "bottom", "top"}) prescribe_velocity(m, side, [](const Vec3&) { return Vec3::Zero(); });
  fix_pressure(m, 0);
  setup_navier_stokes(m);
  return m;
}

/// Circular Couette flow's gap: the annulus 0.5 <= r <= 1 m of 16 x 128 fluid cells (rho 1,
/// mu 1 Pa s), its inner wall turning at `inner_rate` (rad/s), its outer wall fixed.
inline NavierStokesModel couette_gap_fluid(Real inner_rate) {
  NavierStokesModel m;
  m.mesh = annulus_mesh(0.5, 1.0, 16, 128);
  m.density = 1;
  m.viscosity = 1;
  prescribe_velocity(m, "inner", [&](const Vec3& p) { return Vec3(-inner_rate * p.y(), inner_rate * p.x(), 0); });
  prescribe_velocity(m, "outer", [](const Vec3&) { return Vec3::Zero(); });
  fix_pressure(m, 0);
  setup_navier_stokes(m);
  return m;
}

/// One rigid body named "body" with mesh `mesh` in `fluid`: driven by `motion` if given (its
/// density then only sets its nodes' volumes: give the fluid's, as scenes do), else free with
/// density rho_s; its coupling stiffness the default for steps of dt.
inline ImmersedSolids one_rigid_body(FemMesh mesh, Real density, const NavierStokesModel& fluid, Real dt,
                                     std::optional<PrescribedRigidMotion> motion = std::nullopt) {
  ImmersedSolids solids;
  solids.model.dim = fluid.dim();
  FemSolid solid;
  solid.name = "body";
  solid.mesh = std::move(mesh);
  solid.material.density = density;
  add_fem_solid(solids.model, std::move(solid));
  finalize_fem_model(solids.model);
  solids.viscosity.push_back(fluid.viscosity);
  solids.rigid_bodies.push_back(
      make_immersed_rigid_body(solids.model, 0, fluid.density, default_rigid_coupling_stiffness(fluid, dt)));
  solids.rigid_bodies[0].motion = std::move(motion);
  return solids;
}

}  // namespace moreau::test
