#pragma once
// Compliant attachments (pins) of particles to fixed points in the world.
//   C = x - p                        (m, three components with one compliance)
//   grad_x C = I
//   compliance alpha (m/N): the inverse stiffness of a zero-length spring to the pin point.
// Rigid pins (alpha = 0) are not constraints at all: the builder gives the particle zero inverse
// mass, which is exact and costs nothing in the solve.
#include <vector>

#include "moreau/constraints/xpbd_update.hpp"

namespace moreau {

struct AttachmentConstraints {
  std::vector<Index> particle;     // each particle appears at most once
  std::vector<Vec3> target;        // m
  std::vector<Real> compliance;    // m/N
  std::vector<Real> damping_time;  // s
  std::vector<Index> object;

  size_t size() const { return particle.size(); }
  void add(Index p, const Vec3& at, Real alpha, Real tau, Index obj) {
    particle.push_back(p);
    target.push_back(at);
    compliance.push_back(alpha);
    damping_time.push_back(tau);
    object.push_back(obj);
  }
};

/// One sweep; attachments touch distinct particles, so all of them form one parallel batch.
void project_attachments(const AttachmentConstraints& c, Vec3* lambda, const SubstepContext& s);
Real attachment_energy(const AttachmentConstraints& c, const Vec3* x, Index object);
Real attachment_max_error(const AttachmentConstraints& c, const Vec3* x, Index object);

}  // namespace moreau
