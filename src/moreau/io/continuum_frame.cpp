#include "moreau/io/continuum_frame.hpp"

#include "moreau/continuum/continuum_stress.hpp"

namespace moreau {

// The particles an emitter has not released (the object's last, model/particle_emitter.hpp) are
// left out.
ObjectFrame continuum_frame(const Model& model, const ObjectInfo& object, const State& state) {
  const Index b = object.particle_begin;
  Index n = object.particle_count();
  while (n > 0 && !state.live(b + n - 1)) --n;
  const ContinuumModel& continuum = model.continuum;
  const ContinuumState& deformation = state.continuum;
  const Index first = continuum.index_of(b);
  std::vector<Vec3> x(state.position.begin() + b, state.position.begin() + b + n);
  std::vector<Vec3> v(state.velocity.begin() + b, state.velocity.begin() + b + n), u(n);
  std::vector<Real> J(n), plastic(n), mises(n), pressure(n);
  for (Index k = 0; k < n; ++k) {
    const Index i = first + k;
    u[k] = x[k] - model.particle_rest_position[b + k];
    const Mat3& F = deformation.deformation[i];
    J[k] = F.determinant();
    plastic[k] = deformation.plastic_strain[i];
    const Vec3 s =
        principal_cauchy_stress(continuum.materials[continuum.material[i]], deformation.plastic_volume[i], F);
    mises[k] = von_mises_stress(s);
    pressure[k] = -s.sum() / 3;
  }
  return {.points = std::move(x),
          .point_vectors = {{"velocity", std::move(v)}, {"displacement", std::move(u)}},
          .point_scalars = {{"radius", std::vector<Real>(n, continuum.spacing / 2)},
                            {"J", std::move(J)},
                            {"plastic_strain", std::move(plastic)},
                            {"von_mises_stress", std::move(mises)},
                            {"pressure", std::move(pressure)}}};
}

}  // namespace moreau
