#pragma once
// Helpers for Navier-Stokes tests: exact solutions prescribed on boundaries, L2 errors.
#include <cmath>
#include <functional>
#include <optional>
#include <string>

#include "moreau/fem/flow/navier_stokes.hpp"

namespace moreau::test {

/// An exact flow: velocity and pressure as functions of the position and time.
struct ExactFlow {
  std::function<Vec3(const Vec3&, Real)> velocity;
  std::function<Real(const Vec3&, Real)> pressure;
};

/// Every velocity component of a boundary's nodes set by value(X); later calls override.
template <class F>
void prescribe_velocity(NavierStokesModel& m, const std::string& boundary, F value) {
  for (Index n : m.mesh.boundary_nodes(boundary)) {
    const Vec3 v = value(m.mesh.nodes[n]);
    for (int k = 0; k < m.mesh.dim; ++k) m.prescribed.push_back({m.dof(n, k), [c = v[k]](Real) { return c; }});
  }
}

/// The exact velocity (at time t) on every node of every boundary, each dof once.
inline void prescribe_exact_velocity(NavierStokesModel& m, const ExactFlow& exact) {
  std::vector<bool> done(m.mesh.node_count(), false);
  for (const FemBoundary& b : m.mesh.boundaries)
    for (Index n : m.mesh.boundary_nodes(b.name)) {
      if (done[n]) continue;
      done[n] = true;
      const Vec3 X = m.mesh.nodes[n];
      for (int k = 0; k < m.mesh.dim; ++k)
        m.prescribed.push_back({m.dof(n, k), [X, k, exact](Real t) { return exact.velocity(X, t)[k]; }});
    }
}

/// Velocity and pressure at a point; false if it is outside the mesh.
inline bool sample_flow(const NavierStokesModel& m, const VectorX& x, const Vec3& point, Vec3& velocity, Real& pressure) {
  const std::optional<MeshPoint> at = MeshLocator(m.mesh).locate(point);
  if (at) interpolate_flow(m, *at, x, velocity, pressure);
  return at.has_value();
}

inline void fix_pressure(NavierStokesModel& m, Index node) {
  m.prescribed.push_back({m.dof(node, m.mesh.dim), [](Real) { return 0.0; }});
}

/// The lid-driven unit cavity (quad4, n x n) or cube (hex8, n^3): rho = 1, mu = `viscosity`, the
/// lid (side "top", y = 1) moving in x at 1 m/s, every other side at rest, pressure 0 at node 0.
/// The lid's edge nodes belong to the walls (u = 0), as in Ghia et al. (1982); set up.
inline NavierStokesModel lid_driven_cavity(int dim, int n, Real viscosity = 0.01) {
  NavierStokesModel m;
  m.mesh = dim == 3 ? make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {n, n, n}, ElementType::hex8)
                    : make_rectangle_mesh(Vec2(0, 0), Vec2(1, 1), {n, n}, ElementType::quad4);
  m.viscosity = viscosity;
  std::vector<bool> on_wall(m.mesh.node_count(), false);
  for (const FemBoundary& b : m.mesh.boundaries)
    if (b.name != "top") {
      prescribe_velocity(m, b.name, [](const Vec3&) { return Vec3::Zero(); });
      for (Index node : m.mesh.boundary_nodes(b.name)) on_wall[node] = true;
    }
  for (Index node : m.mesh.boundary_nodes("top"))
    if (!on_wall[node])
      for (int k = 0; k < dim; ++k) m.prescribed.push_back({m.dof(node, k), [k](Real) { return k == 0 ? 1.0 : 0.0; }});
  fix_pressure(m, 0);
  setup_navier_stokes(m);
  return m;
}

/// The exact velocity at time t on every node (pressure 0).
inline VectorX exact_state(const NavierStokesModel& m, const ExactFlow& exact, Real t) {
  VectorX x = VectorX::Zero(m.dof_count());
  for (Index n = 0; n < m.mesh.node_count(); ++n)
    for (int k = 0; k < m.mesh.dim; ++k) x[m.dof(n, k)] = exact.velocity(m.mesh.nodes[n], t)[k];
  return x;
}

struct FlowErrors {
  Real velocity = 0, pressure = 0;  // L2 norms; the pressure's with both means removed
};

/// L2 errors against the exact flow at time t, by the model's 2 x 2 (x 2) Gauss points.
inline FlowErrors flow_errors(const NavierStokesModel& m, const VectorX& x, const ExactFlow& exact, Real t) {
  const int nodes = m.mesh.nodes_per_cell();
  Real mean_h = 0, mean_exact = 0, measure = 0, eu = 0, ep = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (Index e = 0; e < m.mesh.cell_count(); ++e)
      for (int q = 0; q < m.points; ++q) {
        const size_t qp = static_cast<size_t>(e) * m.points + q;
        Vec3 X = Vec3::Zero(), u = Vec3::Zero();
        Real p = 0;
        for (int a = 0; a < nodes; ++a) {
          const Index n = m.mesh.cell(e)[a];
          const Real N = m.shape[qp * nodes + a];
          X += N * m.mesh.nodes[n];
          for (int k = 0; k < m.dim(); ++k) u[k] += N * x[m.dof(n, k)];
          p += N * x[m.dof(n, m.dim())];
        }
        const Real w = m.weight[qp];
        if (pass == 0) {
          mean_h += w * p;
          mean_exact += w * exact.pressure(X, t);
          measure += w;
          continue;
        }
        eu += w * (u - exact.velocity(X, t)).squaredNorm();
        const Real dp = (p - mean_h / measure) - (exact.pressure(X, t) - mean_exact / measure);
        ep += w * dp * dp;
      }
  return {std::sqrt(eu), std::sqrt(ep)};
}

}  // namespace moreau::test
