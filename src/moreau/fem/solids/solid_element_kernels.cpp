#include "moreau/fem/solids/solid_element_kernels.hpp"

#include <limits>

namespace moreau {

void strain_displacement(const Mat3& F, const Vec3* G, int nodes, int dim, StrainMatrix& B) {
  B.resize(6, nodes * dim);
  for (int a = 0; a < nodes; ++a) {
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
}

void add_tangent(const StrainMatrix& B, const StrainMatrix& B_right, const Mat6& CC, const Vec6& stress, const Vec3* G,
                 int nodes, int dim, Real scale, ElementMatrix& K) {
  const StrainMatrix DB = CC * B_right;
  K.noalias() += scale * B.transpose() * DB;
  const Mat3 S = from_voigt(stress);
  for (int a = 0; a < nodes; ++a) {
    const Vec3 SGa = S * G[a];
    for (int b = 0; b < nodes; ++b) {
      const Real s = scale * SGa.dot(G[b]);
      for (int k = 0; k < dim; ++k) K(a * dim + k, b * dim + k) += s;
    }
  }
}

void start_output(int n, bool with_tangent, ElementOutput& out) {
  out.energy = 0;
  out.valid = true;
  out.force.setZero(n);
  if (with_tangent) out.tangent.setZero(n, n);
}

void mark_inverted(ElementOutput& out) {
  out.valid = false;
  out.energy = std::numeric_limits<Real>::infinity();
}

PointDiscreteGradient discrete_gradient(const HyperelasticMaterial& material, const Mat3& E0, const Mat3& E1,
                                        bool with_tangent) {
  PointDiscreteGradient d;
  const HyperelasticResponse r1 = material.respond(E1, false);
  const HyperelasticResponse r = material.respond(0.5 * (E0 + E1), with_tangent);
  if (!r1.valid || !r.valid) {
    d.valid = false;
    return d;
  }
  d.energy = r1.energy;
  d.stress = r.stress;
  if (with_tangent) d.tangent = r.tangent;
  const Mat3 dE = E1 - E0;
  const Real dE2 = dE.squaredNorm();
  if (!(dE2 > 1e-16)) return d;
  const Vec6 dE_v = to_voigt(dE);
  const Real SdE = from_voigt(r.stress).cwiseProduct(dE).sum();
  const Real kappa = (r1.energy - material.energy(E0) - SdE) / dE2;
  d.stress += kappa * dE_v;
  if (!with_tangent) return d;
  // The correction's derivative: with g = S(E1) - S_a - CC_a dE / 2 - 2 kappa dE,
  // d(kappa dE)/dE1 = dE (x) g / |dE|^2 + kappa II (II maps an engineering-shear strain to the
  // tensor's components); the tangent holds twice it.
  Vec6 dE_engineering = dE_v;
  dE_engineering.tail<3>() *= 2;
  const Vec6 g = r1.stress - r.stress - 0.5 * r.tangent * dE_engineering - 2 * kappa * dE_v;
  Mat6 correction = dE_v * g.transpose() / dE2;
  correction.diagonal() += kappa * (Vec6() << 1, 1, 1, 0.5, 0.5, 0.5).finished();
  d.tangent = r.tangent + 2 * correction;
  return d;
}

}  // namespace moreau
