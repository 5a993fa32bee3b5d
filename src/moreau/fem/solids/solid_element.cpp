#include "moreau/fem/solids/solid_element.hpp"

#include <cmath>
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

namespace {

using StrainMatrix = Eigen::Matrix<Real, 6, Eigen::Dynamic, 0, 6, kMaxElementDofs>;

// B with dE_voigt = B du at deformation gradient F (see the header).
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

// Adds scale (B^T CC B_right + geometric(S)) to the tangent: the geometric part (G_a . S G_b) on
// the diagonal of each node pair's block.
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
  out.energy = kInverted;
}

}  // namespace

void solid_element(const HyperelasticMaterial& material, const CellQuadrature& q, int dim, const Real* u,
                   bool with_tangent, ElementOutput& out) {
  start_output(q.nodes * dim, with_tangent, out);
  StrainMatrix B;
  for (int p = 0; p < q.points; ++p) {
    const Vec3* G = q.gradient + static_cast<size_t>(p) * q.nodes;
    const Real w = q.weight[p];
    const Mat3 H = displacement_gradient(G, q.nodes, dim, u);
    const Mat3 F = Mat3::Identity() + H;
    // det C = J^2 cannot see an inverted point (J < 0); W is defined for J > 0 only.
    if (!(F.determinant() > 0)) return mark_inverted(out);
    const HyperelasticResponse r = material.respond(green_lagrange_strain(H), with_tangent);
    if (!r.valid) return mark_inverted(out);
    out.energy += w * r.energy;
    strain_displacement(F, G, q.nodes, dim, B);
    out.force.noalias() += w * B.transpose() * r.stress;
    if (with_tangent) add_tangent(B, B, r.tangent, r.stress, G, q.nodes, dim, w, out.tangent);
  }
}

void solid_element_step(const HyperelasticMaterial& material, const CellQuadrature& q, int dim, const Real* u_n,
                        const Real* u_next, StepRule rule, bool with_tangent, ElementOutput& out) {
  start_output(q.nodes * dim, with_tangent, out);
  StrainMatrix B, B_next;
  for (int p = 0; p < q.points; ++p) {
    const Vec3* G = q.gradient + static_cast<size_t>(p) * q.nodes;
    const Real w = q.weight[p];
    const Mat3 H0 = displacement_gradient(G, q.nodes, dim, u_n);
    const Mat3 H1 = displacement_gradient(G, q.nodes, dim, u_next);
    const Mat3 Fm = Mat3::Identity() + 0.5 * (H0 + H1);
    if (!((Mat3::Identity() + H1).determinant() > 0) || !(Fm.determinant() > 0)) return mark_inverted(out);
    const Mat3 E0 = green_lagrange_strain(H0), E1 = green_lagrange_strain(H1);
    const HyperelasticResponse r1 = material.respond(E1, false);
    if (!r1.valid) return mark_inverted(out);
    const Real W1 = r1.energy;
    out.energy += w * W1;
    HyperelasticResponse r;
    Vec6 S_algo;
    // The correction's derivative: with kappa = (W1 - W0 - S_a : dE) / |dE|^2 and
    // g = S(E1) - S_a - CC_a dE / 2 - 2 kappa dE, d(kappa dE)/dE1 = dE (x) g / |dE|^2 + kappa II
    // (II maps an engineering-shear strain to the tensor's components).
    Mat6 correction_tangent = Mat6::Zero();
    if (rule == StepRule::midpoint) {
      r = material.respond(green_lagrange_strain(0.5 * (H0 + H1)), with_tangent);
      S_algo = r.stress;
    } else {
      r = material.respond(0.5 * (E0 + E1), with_tangent);
      S_algo = r.stress;
      const Mat3 dE = E1 - E0;
      const Real dE2 = dE.squaredNorm();
      if (dE2 > 1e-16) {
        const Vec6 dE_v = to_voigt(dE);
        const Real SdE = from_voigt(r.stress).cwiseProduct(dE).sum();
        const Real kappa = (W1 - material.energy(E0) - SdE) / dE2;
        S_algo += kappa * dE_v;
        if (with_tangent) {
          Vec6 dE_engineering = dE_v;
          dE_engineering.tail<3>() *= 2;
          const Vec6 g = r1.stress - r.stress - 0.5 * r.tangent * dE_engineering - 2 * kappa * dE_v;
          correction_tangent = dE_v * g.transpose() / dE2;
          correction_tangent.diagonal() += kappa * (Vec6() << 1, 1, 1, 0.5, 0.5, 0.5).finished();
        }
      }
    }
    if (!r.valid) return mark_inverted(out);
    strain_displacement(Fm, G, q.nodes, dim, B);
    out.force.noalias() += w * B.transpose() * S_algo;
    if (!with_tangent) continue;
    if (rule == StepRule::midpoint) {
      add_tangent(B, B, r.tangent, S_algo, G, q.nodes, dim, 0.5 * w, out.tangent);
    } else {
      // d E_avg / d u_next = B(F_next) / 2, and the correction depends on E1 = E(F_next) itself:
      // the tangent is not symmetric.
      strain_displacement(Mat3::Identity() + H1, G, q.nodes, dim, B_next);
      const Mat6 CC = r.tangent + 2 * correction_tangent;
      add_tangent(B, B_next, CC, S_algo, G, q.nodes, dim, 0.5 * w, out.tangent);
    }
  }
}

}  // namespace moreau
