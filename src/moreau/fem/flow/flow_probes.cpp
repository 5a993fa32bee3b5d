#include <fmt/format.h>

#include <fstream>

#include "moreau/errors.hpp"
#include "moreau/fem/flow/flow_problem.hpp"
#include "moreau/fem/flow/flow_source_assembly.hpp"
#include "moreau/fem/immersed/immersed_coupling.hpp"

namespace moreau {

std::vector<std::string> flow_probe_columns(const FlowProbe& p, int dim) {
  static const char* axes[] = {".x", ".y", ".z"};
  std::vector<std::string> columns;
  switch (p.type) {
    case FlowProbeType::point:
      for (int k = 0; k < dim; ++k) columns.push_back(p.name + ".velocity" + axes[k]);
      columns.push_back(p.name + ".pressure");
      break;
    case FlowProbeType::boundary_force:
      for (int k = 0; k < dim; ++k) columns.push_back(p.name + ".force" + axes[k]);
      if (p.coefficient_scale > 0)
        for (int k = 0; k < dim; ++k) columns.push_back(p.name + ".coefficient" + axes[k]);
      break;
    case FlowProbeType::pressure_difference:
    case FlowProbeType::kinetic_energy:
    case FlowProbeType::newton_iterations: columns.push_back(p.name); break;
    case FlowProbeType::solid_point:
      for (int k = 0; k < dim; ++k) columns.push_back(p.name + "." + p.quantity + axes[k]);
      break;
    case FlowProbeType::rigid_body:
      if ((p.quantity == "angular_velocity" || p.quantity == "torque") && dim == 2) columns.push_back(p.name + ".z");
      else
        for (int k = 0; k < dim; ++k) columns.push_back(p.name + axes[k]);
      break;
    case FlowProbeType::solid_force:
      for (int k = 0; k < dim; ++k) columns.push_back(p.name + axes[k]);
      if (p.coefficient_scale > 0)
        for (int k = 0; k < dim; ++k) columns.push_back(p.name + ".coefficient" + axes[k]);
      break;
    case FlowProbeType::energy:
      for (const char* part : {".fluid_kinetic", ".solid_excess_kinetic", ".solid_elastic", ".total"})
        columns.push_back(p.name + part);
      break;
    case FlowProbeType::line: break;
  }
  return columns;
}

Vec3 boundary_force(const NavierStokesModel& m, const VectorX& residual, const std::vector<Index>& nodes) {
  Vec3 f = Vec3::Zero();
  for (Index n : nodes)
    for (int k = 0; k < m.dim(); ++k) f[k] -= residual[m.dof(n, k)];
  return f;
}

Real mean_pressure(const NavierStokesModel& m, const VectorX& x) {
  const int nodes = m.mesh.nodes_per_cell();
  Real integral = 0, measure = 0;
  for (Index e = 0; e < m.mesh.cell_count(); ++e)
    for (int q = 0; q < m.points; ++q) {
      const size_t qp = static_cast<size_t>(e) * m.points + q;
      Real p = 0;
      for (int a = 0; a < nodes; ++a) p += m.shape[qp * nodes + a] * x[m.dof(m.mesh.cell(e)[a], m.dim())];
      integral += m.weight[qp] * p;
      measure += m.weight[qp];
    }
  return integral / measure;
}

Real flow_kinetic_energy(const NavierStokesModel& m, const VectorX& x) {
  const int nodes = m.mesh.nodes_per_cell();
  Real energy = 0;
  for (Index e = 0; e < m.mesh.cell_count(); ++e)
    for (int q = 0; q < m.points; ++q) {
      const size_t qp = static_cast<size_t>(e) * m.points + q;
      Vec3 u = Vec3::Zero();
      for (int a = 0; a < nodes; ++a)
        for (int k = 0; k < m.dim(); ++k) u[k] += m.shape[qp * nodes + a] * x[m.dof(m.mesh.cell(e)[a], k)];
      energy += 0.5 * m.density * m.weight[qp] * u.squaredNorm();
    }
  return energy;
}

std::vector<Vec3> nodal_vorticity(const NavierStokesModel& m, const VectorX& x) {
  const int nodes = m.mesh.nodes_per_cell();
  std::vector<Vec3> curl(m.mesh.node_count(), Vec3::Zero());
  std::vector<Real> weight(m.mesh.node_count(), 0.0);
  for (Index e = 0; e < m.mesh.cell_count(); ++e) {
    const Index* c = m.mesh.cell(e);
    Mat3 G = Mat3::Zero();  // cell mean of du_i/dx_j
    Real measure = 0;
    for (int q = 0; q < m.points; ++q) {
      const size_t qp = static_cast<size_t>(e) * m.points + q;
      for (int a = 0; a < nodes; ++a)
        for (int i = 0; i < m.dim(); ++i) G.row(i) += m.weight[qp] * x[m.dof(c[a], i)] * m.gradient[qp * nodes + a].transpose();
      measure += m.weight[qp];
    }
    const Vec3 w(G(2, 1) - G(1, 2), G(0, 2) - G(2, 0), G(1, 0) - G(0, 1));  // already weighted by the measure
    for (int a = 0; a < nodes; ++a) {
      curl[c[a]] += w;
      weight[c[a]] += measure;
    }
  }
  for (size_t n = 0; n < curl.size(); ++n)
    if (weight[n] > 0) curl[n] /= weight[n];
  return curl;
}

void evaluate_flow_probe(const FlowProbe& p, const FlowProblem& problem, const VectorX& x, const FlowTimeStep& step,
                         int newton_iterations, const ImmersedSolidState* solids, std::vector<Real>& values) {
  const NavierStokesModel& m = problem.model;
  switch (p.type) {
    case FlowProbeType::point: {
      Vec3 u;
      Real pressure;
      interpolate_flow(m, p.located[0], x, u, pressure);
      for (int k = 0; k < m.dim(); ++k) values.push_back(u[k]);
      values.push_back(pressure);
      break;
    }
    case FlowProbeType::pressure_difference: {
      Vec3 u;
      Real pa, pb;
      interpolate_flow(m, p.located[0], x, u, pa);
      interpolate_flow(m, p.located[1], x, u, pb);
      values.push_back(pa - pb);
      break;
    }
    case FlowProbeType::boundary_force: {
      // With immersed solids, the reactions hold them too where their forces fall on the
      // boundary's nodes (and their force density enters the stabilization, as in the solve).
      VectorX R;
      if (solids && solids->fluid_source.size() == m.dof_count()) flow_residual_with_source(m, x, step, solids->fluid_source, R);
      else assemble_flow(m, x, step, R, nullptr);
      const Vec3 f = boundary_force(m, R, p.nodes);
      for (int k = 0; k < m.dim(); ++k) values.push_back(f[k]);
      if (p.coefficient_scale > 0)
        for (int k = 0; k < m.dim(); ++k) values.push_back(p.coefficient_scale * f[k]);
      break;
    }
    case FlowProbeType::kinetic_energy: values.push_back(flow_kinetic_energy(m, x)); break;
    case FlowProbeType::newton_iterations: values.push_back(newton_iterations); break;
    case FlowProbeType::solid_point: {
      const FemModel& solid = problem.immersed->model;
      const Vec3 X = solid.reference_position(p.solid_node);
      for (int k = 0; k < m.dim(); ++k) {
        const Index d = solid.dof(p.solid_node, k);
        values.push_back(p.quantity == "velocity"       ? solids->velocity[d]
                         : p.quantity == "displacement" ? solids->displacement[d]
                                                        : X[k] + solids->displacement[d]);
      }
      break;
    }
    case FlowProbeType::rigid_body: {
      const int dim = m.dim();
      const VectorX& q = solids->frame[p.body];
      const VectorX& dq = solids->frame_velocity[p.body];
      if (p.quantity == "angular_velocity" || p.quantity == "torque") {
        const Vec3 w = p.quantity == "torque" ? solids->fluid_torque[problem.immersed->rigid_bodies[p.body].solid]
                                              : rigid_frame_angular_velocity(q, dq, dim);
        if (dim == 2) values.push_back(w.z());
        else
          for (int k = 0; k < 3; ++k) values.push_back(w[k]);
      } else {
        const VectorX& v = p.quantity == "velocity" ? dq : q;  // phi: the centre of mass
        for (int k = 0; k < dim; ++k) values.push_back(v[k]);
      }
      break;
    }
    case FlowProbeType::solid_force: {
      const Vec3& f = solids->fluid_force[p.solid];
      for (int k = 0; k < m.dim(); ++k) values.push_back(f[k]);
      if (p.coefficient_scale > 0)
        for (int k = 0; k < m.dim(); ++k) values.push_back(p.coefficient_scale * f[k]);
      break;
    }
    case FlowProbeType::energy: {
      // Fluid kinetic energy over the whole domain (the solid's included at the fluid's density),
      // what the solid's density adds, and the solid's stored elastic energy.
      const Real fluid = flow_kinetic_energy(m, x);
      const Real excess = solids ? immersed_excess_kinetic_energy(*problem.immersed, m, *solids) : 0;
      const Real elastic = solids ? immersed_elastic_energy(*problem.immersed, *solids) : 0;
      for (Real e : {fluid, excess, elastic, fluid + excess + elastic}) values.push_back(e);
      break;
    }
    case FlowProbeType::line: break;
  }
}

void write_line_probe(const FlowProbe& p, const FlowProblem& problem, const VectorX& x, const std::string& path) {
  const NavierStokesModel& m = problem.model;
  std::ofstream out(path);
  static const char* axes[] = {"x", "y", "z"};
  for (int k = 0; k < m.dim(); ++k) out << axes[k] << ',';
  for (int k = 0; k < m.dim(); ++k) out << "velocity." << axes[k] << ',';
  out << "pressure\n";
  for (size_t s = 0; s < p.located.size(); ++s) {
    const Vec3& at = p.sample_points[s];
    Vec3 u;
    Real pressure;
    interpolate_flow(m, p.located[s], x, u, pressure);
    for (int k = 0; k < m.dim(); ++k) out << fmt::format("{:.9g},", at[k]);
    for (int k = 0; k < m.dim(); ++k) out << fmt::format("{:.17g},", u[k]);
    out << fmt::format("{:.17g}\n", pressure);
  }
}

}  // namespace moreau
