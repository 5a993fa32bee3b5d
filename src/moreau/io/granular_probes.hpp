#pragma once
// Probes of piles and flows of particles: the angle of repose of a pile, and the mass flowing
// through a plane (a silo's orifice, a chute's cross-section).
#include <optional>
#include <utility>

#include "moreau/model/state.hpp"

namespace moreau {

/// Up: against gravity (+y without gravity). The piles' probes measure heights along it and
/// distances across it.
Vec3 up_direction(const Model& model);

/// The angle of repose of the pile of `object`'s particles, in degrees: the slope of its free
/// surface, fitted by least squares over the flank.
///
/// Up is -g. The pile's axis is the vertical line through `axis_point` (default: the particles'
/// centre of mass). The particles are binned by their horizontal distance rho from the axis, in
/// rings of width `bin` (m); a ring's surface height is the highest particle top (centre + r)
/// in it, measured from the lowest particle bottom (centre - r). The flank is the rings whose
/// height lies between 20 % and 80 % of the highest ring's, which leaves out the rounded top and
/// the single-grain toe; the angle is atan(-s) of the fitted slope s = dh/drho. NaN when fewer than
/// three rings lie on the flank.
/// Only the particles inside `region` (min, max corners) count when it is given, and only those
/// slower than `resting_speed` (m/s) when it is positive: a pile under the silo that feeds it,
/// without the stream falling onto it.
Real angle_of_repose(const Model& model, const State& state, Index object, const std::optional<Vec3>& axis_point,
                     Real bin, const std::optional<std::pair<Vec3, Vec3>>& region = std::nullopt,
                     Real resting_speed = 0);

/// How far a pile reaches, m: the distance within which the share `fraction` of `object`'s
/// particles lie, each counted by its outer edge (centre distance + r). Measured horizontally
/// (across g) from the vertical axis through `axis_point` (default: the particles' centre of
/// mass), or, with `direction` (a horizontal unit vector), along it from `axis_point`. A
/// fraction below 1 leaves out the few grains that bounce or roll away from a deposit.
/// NaN without particles.
Real runout(const Model& model, const State& state, Index object, const std::optional<Vec3>& axis_point,
            const std::optional<Vec3>& direction, Real fraction);

/// Mass flow through the plane through `point` with unit normal n, kg/s, positive along n:
/// sum of m_i (v_i . n) over the particles within delta of the plane, divided by 2 delta (the flux
/// of the mass density rho v across the plane, averaged over a slab of thickness 2 delta). delta is
/// the largest particle radius of the object (the fluid's particle radius for a fluid).
Real mass_flow_rate(const Model& model, const State& state, Index object, const Vec3& point, const Vec3& n);

/// Mass of `object`'s particles on the side of the plane that n points to, kg.
Real mass_beyond(const Model& model, const State& state, Index object, const Vec3& point, const Vec3& n);

}  // namespace moreau
