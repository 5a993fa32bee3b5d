#pragma once
// A suction cup's sealed cavity (after Bernardin et al. 2022, "Constraint-based simulation of
// passive suction cups", ACM TOG 41(1)): the air between the cup's cavity faces and the surface
// its rim is pressed on, as one volume row whose force is the pressure difference.
//
// Volume. The surface is taken as the plane through the point o with unit normal n (pointing
// towards the cup) where it meets the rim. With d(x) = n . (x - o) the height above it, the field
// d n has divergence 1, and the cavity is bounded by the cavity faces S (whose outward normal,
// out of the cup's material, points into the cavity) and the plane patch, where d = 0. So
//   V = -sum_t dbar_t (n . a_t),   a_t = (x2 - x1) x (x3 - x1) / 2,  dbar_t = (d1 + d2 + d3)/3,
// exact for flat triangles, and the sealed area (the footprint) is A = -sum_t n . a_t. Its gradient:
//   dV/dx_1 = -[ n (n . a_t)/3 + dbar_t (x2 - x3) x n / 2 ]   (and cyclic),
// and a surface moving at velocity u changes V at the rate -A (n . u). A surface on a rigid body
// (centre c) that turns by dtheta changes every height by dtheta . (n x (x - c)) and tilts n by
// dtheta x n (so n . a_t by dtheta . (n x a_t)); the body's row Jacobian is
//   dV/dx_body = -A n,   dV/dtheta_body = -sum_t [ (n . a_t) n x (xbar_t - c) + dbar_t n x a_t ].
//
// Air. Inside, air at pressure p fills V; outside is the atmosphere p0. The lip is a check
// valve: while the cavity would be above p0 air escapes, so the air holds the amount that fills
// V_air at p0, V_air = min(V_air, V). Isothermal (p V = p0 V_air), the suction is
//   dp = p0 - p = p0 (1 - V_air / V) >= 0,
// the derivative of the stored energy U(V) = p0 V - p0 V_air ln V. As a row with C = V, it has the
// tangent compliance alpha = 1/U''(V) = V^2 / (p0 V_air) and the value C = alpha dp, so that its
// force -C/alpha = -dp pulls the cavity shut, with the stiffness of the air; it never pushes
// (its force is bounded to [-inf, 0]). The seal breaks (dp = 0, the air back at p0) when a rim
// vertex lifts off the surface by more than the seal gap.
#include <array>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

/// A soft body's cavity: faces (global particle indices, oriented out of the material) and the
/// rim, the vertices on the cavity's edge, which must touch the surface to seal it.
struct SuctionCup {
  Index object = -1;
  std::vector<std::array<Index, 3>> cavity;
  std::vector<Index> cavity_vertices;  // each vertex of `cavity` once, ascending
  std::vector<Index> rim;
  Real atmospheric_pressure = 101325;  // Pa
  Real seal_gap = 1e-3;                // m: how far beyond its contact gap a rim vertex may lift
};

/// Where a cup stands this step.
struct SuctionCupState {
  bool sealed = false;
  Index collider = -1, body = -1;  // the surface sealed on: a collider's or a rigid body's
  Real air_volume = 0;            // V_air, m^3: the air inside, as its volume at p0
  Real volume = 0, area = 0;      // V (m^3) and A (m^2) at the last assembly
  Real pressure_difference = 0;   // dp, Pa: the row's force in the last solve (0 unsealed)
  Real memory = 0;                // the row's impulse times h (warm start)
};

struct CavityVolume {
  Real volume = 0, area = 0;
  std::vector<Vec3> gradient;  // dV/dx per cavity vertex (SuctionCup::cavity_vertices order)
  Vec3 surface_turn = Vec3::Zero();  // dV/dtheta of the surface turning about `center`
};

/// V, A and dV/dx of `cup` over the plane (o, n) at positions x, and dV/dtheta of the plane
/// turning about `center`.
CavityVolume cavity_volume(const SuctionCup& cup, const Vec3* x, const Vec3& o, const Vec3& n,
                           const Vec3& center = Vec3::Zero());

/// The suction dp = p0 (1 - V_air / V) (0 when V <= V_air).
inline Real suction_pressure(Real p0, Real air_volume, Real volume) {
  return volume > air_volume ? p0 * (1 - air_volume / volume) : 0;
}

/// The row's tangent compliance V^2 / (p0 V_air), m^3/Pa.
inline Real suction_compliance(Real p0, Real air_volume, Real volume) { return volume * volume / (p0 * air_volume); }

}  // namespace moreau
