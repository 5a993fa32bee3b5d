#pragma once
// Deformable solids immersed in a FEM fluid (a "fluid" and "solid" objects in one "solver": "fem"
// scene). The fluid fills the whole domain and its mesh never moves; each solid is a Lagrangian
// mesh carried by the fluid's velocity and acting on the fluid as a momentum source
// (immersed_coupling.hpp has the equations). The solids reuse the FEM solids' model: meshes,
// hyperelastic materials, reference quadrature and consistent mass, and Dirichlet conditions
// (a clamped leaflet base) as prescribed displacements.
#include <string>
#include <vector>

#include "moreau/fem/solids/fem_model.hpp"

namespace moreau {

struct ImmersedSolids {
  FemModel model;                // the solids (material.density is the solid's density), never changed by a run
  std::vector<Real> viscosity;   // per solid, Pa s: the solid's own (Kelvin-Voigt) viscosity
};

/// What a step advances: per solid dof, the displacement u_n (m) and the material velocity V_n
/// (m/s) of the last accepted step, at its time.
struct ImmersedSolidState {
  VectorX displacement, velocity;
  Real time = 0;  // s, the time of u_n (Dirichlet conditions are functions of it)
};

}  // namespace moreau
