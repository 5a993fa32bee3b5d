#include "moreau/fem/scene/fem_output.hpp"

#include <fmt/format.h>

#include "moreau/io/frame_writer.hpp"

namespace moreau {

void cell_stresses(const FemModel& model, const FemSolid& s, const VectorX& u, std::vector<Real>& cauchy,
                   std::vector<Real>& von_mises) {
  const int dim = model.dim, nodes = s.mesh.nodes_per_cell();
  cauchy.assign(static_cast<size_t>(s.mesh.cell_count()) * 6, 0.0);
  von_mises.assign(s.mesh.cell_count(), 0.0);
  Real local[kMaxElementDofs];
  const bool mean_dilatation = s.volume == VolumeTreatment::mean_dilatation;
  const HyperelasticMaterial rest = s.material.without_volumetric_energy();
  for (Index e = 0; e < s.mesh.cell_count(); ++e) {
    const Index* c = s.mesh.cell(e);
    for (int a = 0; a < nodes; ++a)
      for (int k = 0; k < dim; ++k) local[a * dim + k] = u[model.dof(s.node_begin + c[a], k)];
    const CellQuadrature q = s.cell_quadrature(e);
    Mat3 sigma = Mat3::Zero();
    Real volume = 0, theta_minus_one = 0;
    for (int p = 0; p < q.points; ++p) {
      const Mat3 H = displacement_gradient(q.gradient + static_cast<size_t>(p) * nodes, nodes, dim, local);
      const Mat3 F = Mat3::Identity() + H;
      const Real J = F.determinant();
      const Mat3 S = (mean_dilatation ? rest : s.material).stress(green_lagrange_strain(H));
      sigma += q.weight[p] * (F * S * F.transpose() / J);
      volume += q.weight[p];
      theta_minus_one += q.weight[p] * det_identity_plus_minus_one(H);
    }
    sigma /= volume;
    // Mean dilatation: the volumetric stress is the cell's pressure U'(theta), the same at every
    // point (F (p J C^-1) F^T / J = p I).
    if (mean_dilatation) sigma.diagonal().array() += s.material.volumetric_energy(theta_minus_one / volume).pressure;
    const Mat3 dev = sigma - sigma.trace() / 3 * Mat3::Identity();
    const Real v[6] = {sigma(0, 0), sigma(1, 1), sigma(2, 2), sigma(0, 1), sigma(1, 2), sigma(0, 2)};
    std::copy(v, v + 6, cauchy.begin() + 6 * e);
    von_mises[e] = std::sqrt(1.5 * dev.squaredNorm());
  }
}

VtkCell vtk_cell(ElementType type) {
  switch (type) {
    case ElementType::line2: return VtkCell::line;
    case ElementType::tri3: return VtkCell::triangle;
    case ElementType::quad4: return VtkCell::quad;
    case ElementType::tet4: return VtkCell::tetra;
    case ElementType::hex8: return VtkCell::hexahedron;
  }
  return VtkCell::triangle;
}

std::string write_solid_frame(const FemModel& model, const FemSolid& s, const VectorX& u, const VectorX& v,
                              const std::string& out_dir, int frame) {
  const Index n = s.mesh.node_count();
  std::vector<Vec3> x(n), displacement(n, Vec3::Zero()), velocity(n, Vec3::Zero());
  for (Index a = 0; a < n; ++a) {
    for (int k = 0; k < model.dim; ++k) {
      displacement[a][k] = u[model.dof(s.node_begin + a, k)];
      velocity[a][k] = v[model.dof(s.node_begin + a, k)];
    }
    x[a] = s.mesh.nodes[a] + displacement[a];
  }
  std::vector<Real> cauchy, von_mises;
  cell_stresses(model, s, u, cauchy, von_mises);
  const std::string file = fmt::format("frames/{}_{:06d}.vtu", safe_file_name(s.name), frame);
  write_vtu(out_dir + "/" + file, x, s.mesh.cells, s.mesh.nodes_per_cell(), vtk_cell(s.mesh.element),
            {{"displacement", displacement}, {"velocity", velocity}},
            {{"cauchy_stress", 6, cauchy}, {"von_mises", 1, von_mises}});
  return file;
}

void FemFrameWriter::write(const FemRunState& run) {
  const FemDynamicState& state = run.solids;
  std::vector<PvdEntry> entries;
  for (size_t i = 0; i < model_.solids.size(); ++i) {
    const std::string file = write_solid_frame(model_, model_.solids[i], state.u, state.v, out_dir_, frames_);
    entries.push_back({state.time, static_cast<int>(i), file});
  }
  for (size_t b = 0; b < problem_.rigid_bodies.size(); ++b) {
    const FemRigidBody& body = problem_.rigid_bodies[b];
    const DirectorState& d = run.bodies[b];
    const Index n = body.mesh.node_count();
    std::vector<Vec3> x(n), u(n), v(n);
    for (Index a = 0; a < n; ++a) {
      const Vec3 X = body.mesh.nodes[a] - body.body.centre;
      x[a] = d.phi;
      v[a] = d.v_phi;
      for (int i = 0; i < 3; ++i) {
        const Real c = X.dot(body.body.axes.col(i));
        x[a] += c * d.d[i];
        v[a] += c * d.v_d[i];
      }
      u[a] = x[a] - body.mesh.nodes[a];
    }
    const std::string file = fmt::format("frames/{}_{:06d}.vtu", safe_file_name(body.name), frames_);
    write_vtu(out_dir_ + "/" + file, x, body.mesh.cells, body.mesh.nodes_per_cell(), vtk_cell(body.mesh.element),
              {{"displacement", u}, {"velocity", v}});
    entries.push_back({state.time, static_cast<int>(model_.solids.size() + b), file});
  }
  pvd_.add_frame(entries);
  ++frames_;
}

}  // namespace moreau
