#pragma once
// Whether a particle-borne solid with `fluid_friction` is heavy enough for its explicit viscous
// reaction (fluid_viscosity.hpp, apply_rough_solid_reactions). The fluid's viscosity is implicit,
// but the solid takes the opposite of the samples' traction afterwards, as an impulse: stable
// while the solid's surface outweighs the liquid its surface drags within one viscosity step h.
// Viscous momentum diffuses sqrt(nu h) into the liquid in that time, so per unit of wetted area
// the dragged liquid weighs about rho0 sqrt(nu h). A free sheet of 0.3 kg/m^2 beside 10 Pa s
// liquid (2.9 kg/m^2 at h = 0.83 ms) was flung to 2 m/s before the liquid stopped it; one of
// 3 kg/m^2 slowed smoothly (docs/scene-format.md).
#include <string>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct Model;

/// The surface mass per area (kg/m^2) of each cloth, soft body or continuum with fluid friction:
/// a cloth's mass over its area; a soft body's boundary vertices' mass over its boundary area (the
/// layer the fluid's reaction first moves; a stiff, thick body resists with more); a continuum's
/// particle mass over r^2 (a particle per r^2 of surface).
struct GrippingSolid {
  std::string name;
  Real surface_density;   // kg/m^2
  Real dragged_density;   // kg/m^2, rho0 sqrt(nu h) of the scene's heaviest, most viscous fluid
};

/// The gripping solids lighter than the liquid they drag within one viscosity step of h seconds
/// (the substep under xpbd and xpbi, the step under nmd). A solid whose particles are all pinned
/// cannot be flung and is left out.
std::vector<GrippingSolid> light_gripping_solids(const Model& model, Real h);

}  // namespace moreau
