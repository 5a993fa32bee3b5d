#pragma once
// A 2D immersed-solid fixture shared by the coupling tests and the PETSc tests: a stretched
// elastic block released in a closed box of fluid.
#include "flow_test_helpers.hpp"
#include "moreau/fem/flow/flow_problem.hpp"
#include "moreau/fem/immersed/immersed_coupling.hpp"

namespace moreau::test {

// A rectangular solid of quad4 cells with a Neo-Hookean material (shear modulus G, Poisson's ratio
// 0.3) and its own viscosity.
inline ImmersedSolids rectangle_solid(const Vec2& lo, const Vec2& hi, std::array<int, 2> cells, Real shear_modulus,
                               Real density, Real viscosity) {
  ImmersedSolids solids;
  solids.model.dim = 2;
  FemSolid solid;
  solid.name = "block";
  solid.mesh = make_rectangle_mesh(lo, hi, cells, ElementType::quad4);
  solid.material.lame = lame_from_youngs(2 * shear_modulus * 1.3, 0.3);
  solid.material.density = density;
  add_fem_solid(solids.model, std::move(solid));
  finalize_fem_model(solids.model);
  solids.viscosity.push_back(viscosity);
  return solids;
}

// A closed unit box of fluid at rest with a block stretched by an isochoric s x 1/s at its centre
// (shear modulus G), released at t = 0.
struct ReleasedBlock {
  NavierStokesModel fluid;
  ImmersedSolids solids;
  ImmersedSolidState state;
};

inline ReleasedBlock released_block(Real solid_viscosity) {
  ReleasedBlock b;
  NavierStokesModel& m = b.fluid;
  m.mesh = make_rectangle_mesh(Vec2(0, 0), Vec2(1, 1), {24, 24}, ElementType::quad4);
  m.density = 1;
  m.viscosity = 0.01;
  for (const char* side : {"left", "right", "bottom", "top"}) prescribe_velocity(m, side, [](const Vec3&) { return Vec3::Zero(); });
  fix_pressure(m, 0);
  setup_navier_stokes(m);
  b.solids = rectangle_solid(Vec2(0.3, 0.4), Vec2(0.7, 0.6), {16, 8}, 10, 1, solid_viscosity);
  b.state = initial_immersed_state(b.solids);
  const Real s = 1.15;
  const FemMesh& mesh = b.solids.model.solids[0].mesh;
  for (Index n = 0; n < mesh.node_count(); ++n) {
    b.state.displacement[2 * n] = (s - 1) * (mesh.nodes[n].x() - 0.5);
    b.state.displacement[2 * n + 1] = (1 / s - 1) * (mesh.nodes[n].y() - 0.5);
  }
  return b;
}

inline Real total_energy(const ReleasedBlock& b, const VectorX& x) {
  return flow_kinetic_energy(b.fluid, x) + immersed_excess_kinetic_energy(b.solids, b.fluid, b.state) +
         immersed_elastic_energy(b.solids, b.state);
}

}  // namespace moreau::test
