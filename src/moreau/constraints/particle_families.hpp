#pragma once
// The constraint families between particles, listed once. Storage (Model::constraints),
// multipliers (State::constraint_lambda), colouring, the XPBD projection order and its stage
// timings, energy and constraint-error diagnostics, probes, run.json counts and the scene summary
// all iterate this list. Adding a family is its file pair in constraints/ and one entry here
// (docs/architecture.md, "Adding a constraint family").
#include <array>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "moreau/constraints/attachment.hpp"
#include "moreau/constraints/constraint_family.hpp"
#include "moreau/constraints/dihedral_bending.hpp"
#include "moreau/constraints/distance.hpp"
#include "moreau/constraints/green_strain_tet.hpp"
#include "moreau/constraints/isometric_bending.hpp"
#include "moreau/constraints/neo_hookean_tet.hpp"
#include "moreau/constraints/tet_volume.hpp"
#include "moreau/constraints/triangle_strain.hpp"

namespace moreau {

/// Every family, in the order an XPBD iteration projects them.
using ParticleFamilies = std::tuple<DistanceConstraints, DihedralBendingConstraints, IsometricBendingConstraints,
                                    TriangleStrainConstraints, NeoHookeanTetConstraints, GreenStrainTetConstraints,
                                    TetVolumeConstraints, AttachmentConstraints>;

inline constexpr int kParticleFamilyCount = static_cast<int>(std::tuple_size_v<ParticleFamilies>);

namespace detail {
template <class Tuple>
struct MultipliersOf;
template <class... F>
struct MultipliersOf<std::tuple<F...>> {
  static_assert((ParticleConstraintFamily<F> && ...), "a listed family does not provide the family interface");
  using type = std::tuple<std::vector<typename F::Multiplier>...>;
};
}  // namespace detail

/// One multiplier vector per family, in list order.
using ParticleFamilyMultipliers = detail::MultipliersOf<ParticleFamilies>::type;

/// The position of `Family` in ParticleFamilies.
template <class Family>
constexpr int family_index() {
  return []<size_t... I>(std::index_sequence<I...>) {
    int index = -1;
    ((std::is_same_v<Family, std::tuple_element_t<I, ParticleFamilies>> ? index = static_cast<int>(I) : 0), ...);
    return index;
  }(std::make_index_sequence<kParticleFamilyCount>{});
}

/// The multipliers of `Family` in a ParticleFamilyMultipliers.
template <class Family>
auto& multipliers_of(ParticleFamilyMultipliers& lambda) {
  return std::get<family_index<Family>()>(lambda);
}
template <class Family>
const auto& multipliers_of(const ParticleFamilyMultipliers& lambda) {
  return std::get<family_index<Family>()>(lambda);
}

/// Calls f(family, index) for every family in list order.
template <class Families, class F>
void for_each_family(Families& families, F&& f) {
  [&]<size_t... I>(std::index_sequence<I...>) {
    (f(std::get<I>(families), static_cast<int>(I)), ...);
  }(std::make_index_sequence<kParticleFamilyCount>{});
}

/// Calls f(family, multipliers, index) for every family in list order.
template <class F>
void for_each_family(const ParticleFamilies& families, ParticleFamilyMultipliers& lambda, F&& f) {
  [&]<size_t... I>(std::index_sequence<I...>) {
    (f(std::get<I>(families), std::get<I>(lambda), static_cast<int>(I)), ...);
  }(std::make_index_sequence<kParticleFamilyCount>{});
}

/// The families' names (kName), in list order.
inline constexpr std::array<std::string_view, kParticleFamilyCount> particle_family_names() {
  return []<size_t... I>(std::index_sequence<I...>) {
    return std::array<std::string_view, kParticleFamilyCount>{std::tuple_element_t<I, ParticleFamilies>::kName...};
  }(std::make_index_sequence<kParticleFamilyCount>{});
}

/// The values the constraint_error probe accepts for `family`: "all", then each distinct kErrorName.
std::vector<std::string_view> constraint_error_names();

}  // namespace moreau
