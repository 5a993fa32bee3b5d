#pragma once
// Building FEM models in tests without a scene file.
#include <random>

#include "moreau/fem/solids/fem_assembly.hpp"
#include "moreau/fem/solids/fem_model.hpp"

namespace moreau::test {

inline HyperelasticMaterial fem_material(HyperelasticModel model, Real E, Real nu, Real density = 1000) {
  HyperelasticMaterial m;
  m.model = model;
  m.lame = lame_from_youngs(E, nu);
  m.density = density;
  return m;
}

inline FemSolid fem_solid(const std::string& name, FemMesh mesh, const HyperelasticMaterial& material) {
  FemSolid s;
  s.name = name;
  s.mesh = std::move(mesh);
  s.material = material;
  return s;
}

/// Moves every node not on the mesh's exterior by up to `amount` times `spacing` in each
/// coordinate (in the mesh's plane in 2D), reproducibly.
inline void distort_interior(FemMesh& mesh, Real amount, Real spacing, unsigned seed = 7) {
  std::vector<char> exterior(mesh.node_count(), 0);
  for (Index n : exterior_facets(mesh)) exterior[n] = 1;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> jitter(-amount * spacing, amount * spacing);
  for (Index n = 0; n < mesh.node_count(); ++n) {
    if (exterior[n]) continue;
    for (int k = 0; k < mesh.dim; ++k) mesh.nodes[n][k] += jitter(rng);
  }
}

/// Every component of the given (global) nodes prescribed by value(X) (a function of the node's
/// reference position, constant in time).
template <class F>
void prescribe_nodes(FemModel& model, const std::vector<Index>& nodes, F value) {
  for (Index n : nodes) {
    const Vec3 X = model.reference_position(n);
    const Vec3 u = value(X);
    for (int k = 0; k < model.dim; ++k) model.prescribed.push_back({model.dof(n, k), [v = u[k]](Real) { return v; }});
  }
}

/// Global node indices of a solid's named boundary.
inline std::vector<Index> boundary_global_nodes(const FemModel& model, Index solid, const std::string& name) {
  std::vector<Index> nodes = model.solids[solid].mesh.boundary_nodes(name);
  for (Index& n : nodes) n += model.solids[solid].node_begin;
  return nodes;
}

/// A traction t * traction (Pa, on reference areas; t the load factor) on a solid's named boundary.
inline void add_traction(FemModel& model, Index solid, const std::string& name, const Vec3& traction) {
  NodalLoad load;
  load.name = name;
  facet_node_integrals(model.solids[solid], name, load.nodes, load.weights);
  for (Index& n : load.nodes) n += model.solids[solid].node_begin;
  load.value = [traction](Real t) { return Vec3(t * traction); };
  model.loads.push_back(std::move(load));
}

/// The largest entry of J - dR/dx, the derivative taken by central differences of step h: how
/// far a Jacobian is from the derivative of its residual.
template <class Residual>
Real jacobian_error(const Eigen::MatrixXd& J, const VectorX& x, Real h, Residual residual) {
  Real worst = 0;
  for (Index j = 0; j < x.size(); ++j) {
    VectorX xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    worst = std::max(worst, (J.col(j) - (residual(xp) - residual(xm)) / (2 * h)).cwiseAbs().maxCoeff());
  }
  return worst;
}

/// Solves a two-unknown residual(a, b) = 0 by Newton with a finite-difference Jacobian (the
/// exact stretches of homogeneous deformations in tests).
template <class Residual>
Vec2 solve_two(Residual residual, Vec2 x) {
  for (int it = 0; it < 50; ++it) {
    const Real h = 1e-7;
    Eigen::Matrix2d J;
    J.col(0) = (residual(x.x() + h, x.y()) - residual(x.x() - h, x.y())) / (2 * h);
    J.col(1) = (residual(x.x(), x.y() + h) - residual(x.x(), x.y() - h)) / (2 * h);
    x -= J.partialPivLu().solve(residual(x.x(), x.y()));
  }
  return x;
}

}  // namespace moreau::test
