#pragma once
// The frame of a driven immersed rigid body (immersed_rigid_body.hpp): its motion is given as the
// velocity v(t) of its centre and its angular velocity w(t), and its frame q = (phi, d_1 .. d_dim)
// follows them. Over a step the centre moves by the midpoint quadrature of v and the directors
// turn by the rotation of angle vector dt w(t + dt/2) (Rodrigues' formula), so the directors stay
// orthonormal to round-off and the frame is second-order accurate in dt.
#include "moreau/fem/immersed/immersed_solids.hpp"

namespace moreau {

/// The frame at t + dt from the frame q at t:
///   phi_n+1 = phi_n + dt v(t + dt/2),   d_i,n+1 = exp(dt [w(t + dt/2)]x) d_i,n.
VectorX advance_prescribed_frame(const PrescribedRigidMotion& motion, const VectorX& q, Real t, Real dt, int dim);

/// The frame's velocity at t: dphi/dt = v(t), dd_i/dt = w(t) x d_i.
VectorX prescribed_frame_velocity(const PrescribedRigidMotion& motion, const VectorX& q, Real t, int dim);

}  // namespace moreau
