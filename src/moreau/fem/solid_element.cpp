#include "moreau/fem/solid_element.hpp"

#include <limits>

namespace moreau {

namespace {
constexpr Real kInverted = std::numeric_limits<Real>::infinity();
}  // namespace

Mat3 displacement_gradient(const Vec3* G, int nodes, int dim, const Real* u) {
  Mat3 H = Mat3::Zero();
  for (int a = 0; a < nodes; ++a)
    for (int k = 0; k < dim; ++k) H.row(k) += u[a * dim + k] * G[a].transpose();
  return H;
}

void solid_element(const HyperelasticMaterial& material, const CellQuadrature& q, int dim, const Real* u,
                   bool with_tangent, ElementOutput& out) {
  const int n = q.nodes * dim;
  out.energy = 0;
  out.valid = true;
  out.force.setZero(n);
  if (with_tangent) out.tangent.setZero(n, n);
  Eigen::Matrix<Real, 6, Eigen::Dynamic, 0, 6, kMaxElementDofs> B(6, n);
  Eigen::Matrix<Real, 6, Eigen::Dynamic, 0, 6, kMaxElementDofs> DB(6, n);
  for (int p = 0; p < q.points; ++p) {
    const Vec3* G = q.gradient + static_cast<size_t>(p) * q.nodes;
    const Real w = q.weight[p];
    const Mat3 H = displacement_gradient(G, q.nodes, dim, u);
    const Mat3 F = Mat3::Identity() + H;
    // det C = J^2 cannot see an inverted point (J < 0); W is defined for J > 0 only.
    if (!(F.determinant() > 0)) {
      out.valid = false;
      out.energy = kInverted;
      return;
    }
    const HyperelasticResponse r = material.respond(green_lagrange_strain(H), with_tangent);
    if (!r.valid) {
      out.valid = false;
      out.energy = r.energy;
      return;
    }
    out.energy += w * r.energy;
    for (int a = 0; a < q.nodes; ++a) {
      const Vec3& g = G[a];
      for (int k = 0; k < dim; ++k) {
        const int col = a * dim + k;
        B(0, col) = F(k, 0) * g[0];
        B(1, col) = F(k, 1) * g[1];
        B(2, col) = F(k, 2) * g[2];
        B(3, col) = F(k, 0) * g[1] + F(k, 1) * g[0];
        B(4, col) = F(k, 1) * g[2] + F(k, 2) * g[1];
        B(5, col) = F(k, 0) * g[2] + F(k, 2) * g[0];
      }
    }
    out.force.noalias() += w * B.transpose() * r.stress;
    if (!with_tangent) continue;
    DB.noalias() = r.tangent * B;
    out.tangent.noalias() += w * B.transpose() * DB;
    // Geometric part: (G_a . S G_b) on the diagonal of each node pair's block.
    const Mat3 S = from_voigt(r.stress);
    for (int a = 0; a < q.nodes; ++a) {
      const Vec3 SGa = S * G[a];
      for (int b = 0; b < q.nodes; ++b) {
        const Real s = w * SGa.dot(G[b]);
        for (int k = 0; k < dim; ++k) out.tangent(a * dim + k, b * dim + k) += s;
      }
    }
  }
}

}  // namespace moreau
