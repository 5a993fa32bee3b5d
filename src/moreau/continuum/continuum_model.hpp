#pragma once
// The inelastic continua of the XPBI formulation (`"solver": "xpbi"`, Yu et al. 2024): sand, snow,
// plasticine, metal, foam and mud, or an elastic solid, each a cloud of particles in the model's
// particle arrays (ObjectKind::continuum) that carries a deformation gradient. One continuum per
// scene: every continuum object shares the particle spacing r and the kernel support 2 r, and
// particles of different continuum objects are each other's neighbours (sand poured onto sand is
// one body).
#include <algorithm>
#include <vector>

#include "moreau/materials/hyperelastic.hpp"

namespace moreau {

/// How a particle's elastic deformation gradient flows when it leaves the yield surface
/// (return_maps.hpp).
enum class PlasticModel {
  none,            // an elastic StVK-Hencky solid
  drucker_prager,  // sand: friction angle, cohesion
  von_mises,       // metal, plasticine: uniaxial yield stress
  snow,            // Stomakhin et al. 2013: stretches clamped, hardening with compaction
  herschel_bulkley, // foam, cream, mud: shear yield stress, consistency, flow index (Bingham: 1)
  maxwell           // silly putty, slime, polymer melts: elastic when quick, viscous when slow
};

struct ContinuumMaterial {
  Real density = 0;                // kg/m^3 of the filled volume
  LameParameters lame;             // Pa
  PlasticModel plastic = PlasticModel::none;
  Real friction_angle = 0;         // rad (drucker_prager)
  Real cohesion = 0;               // Pa (drucker_prager): the isotropic tension the sand carries
  Real yield_stress = 0;           // Pa (von_mises): the uniaxial yield stress
  Real critical_compression = 0;   // theta_c (snow): the smallest stretch is 1 - theta_c
  Real critical_stretch = 0;       // theta_s (snow): the largest stretch is 1 + theta_s
  Real hardening = 0;              // xi (snow): mu, lambda scale with exp(xi (1 - J_p))
  Real shear_yield_stress = 0;     // Pa (herschel_bulkley): tau_y in simple shear
  Real consistency = 0;            // Pa s^n (herschel_bulkley): K in tau = tau_y + K gamma'^n
  Real flow_index = 1;             // n (herschel_bulkley): 1 is a Bingham fluid
  Real relaxation_time = 0;        // s (maxwell): lambda; the fluid's shear viscosity is mu lambda
};

struct ContinuumModel {
  Real spacing = 0;                 // m, r: the particles' lattice spacing
  std::vector<Index> particle;      // global particle index of each continuum particle
  std::vector<Real> rest_volume;    // m^3, V^0 per continuum particle
  std::vector<Index> material;      // index into `materials` per continuum particle
  std::vector<ContinuumMaterial> materials;

  bool empty() const { return particle.empty(); }
  Index size() const { return static_cast<Index>(particle.size()); }
  /// The kernel support, 2 r.
  Real support() const { return 2 * spacing; }
  /// The continuum index of global particle p (which must be a continuum particle).
  Index index_of(Index p) const {
    return static_cast<Index>(std::lower_bound(particle.begin(), particle.end(), p) - particle.begin());
  }
};

}  // namespace moreau
