#pragma once
// Compliant attachments (pins) of particles to fixed points in the world.
//   C = x - p                        (m, three components with one compliance)
//   grad_x C = I
//   compliance alpha (m/N): the inverse stiffness of a zero-length spring to the pin point.
// Rigid pins (alpha = 0) are not constraints at all: the builder gives the particle zero inverse
// mass, which is exact and costs nothing in the solve.
#include <string_view>
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/constraint_rows.hpp"

namespace moreau {

struct AttachmentConstraints {
  static constexpr std::string_view kName = "attachment", kErrorName = "attachment";
  using Multiplier = Vec3;
  using Rows = RowBlock<1, 3>;

  std::vector<Index> particle;     // each particle appears at most once
  std::vector<Vec3> target;        // m
  std::vector<Real> compliance;    // m/N
  std::vector<Real> damping_time;  // s
  std::vector<Index> object;
  ColorBatches batches;  // one colour: each particle is attached at most once

  size_t size() const { return particle.size(); }
  void add(Index p, const Vec3& at, Real alpha, Real tau, Index obj) {
    particle.push_back(p);
    target.push_back(at);
    compliance.push_back(alpha);
    damping_time.push_back(tau);
    object.push_back(obj);
  }
  void color(const std::vector<Real>& particle_inv_mass);
  /// C = x - p, gradient I, compliance alpha I.
  Rows rows(Index k, const Vec3* x) const;
  /// sum 0.5 |x - p|^2 / alpha over compliant pins, J.
  Real energy(const Vec3* x, Index object) const;
  /// max |x - p|, m.
  Real max_error(const Vec3* x, Index object) const;
};

}  // namespace moreau
