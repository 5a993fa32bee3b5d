#pragma once
// What a constraint family between particles provides. A family is a struct of arrays (one entry
// per constraint, colour-sorted once after the scene is built) with:
//   kName        its name in stage timings, run.json counts and the scene summary,
//   kErrorName   the `family` value under which the constraint_error probe reports it,
//   Multiplier   the type of one constraint's multipliers (Real, Vec2 or Vec3: one per row),
//   Rows         its RowBlock<P, R> (constraint_rows.hpp),
//   size(), object[k] (owning object), batches (colour batches), color(particle_inv_mass),
//   rows(k, x)           the rows of constraint k at positions x,
//   energy(x, object)    stored elastic energy of the object's constraints (-1: all), J,
//   max_error(x, object) the largest violation in the family's own measure (documented per family).
// Solvers reach families only through this interface; the list of families is
// particle_families.hpp.
#include <concepts>
#include <string_view>
#include <type_traits>
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/constraint_rows.hpp"

namespace moreau {

template <class F>
concept ParticleConstraintFamily = requires(const F& family, F& mutable_family, const Vec3* x, Index k,
                                            const std::vector<Real>& inv_mass) {
  { F::kName } -> std::convertible_to<std::string_view>;
  { F::kErrorName } -> std::convertible_to<std::string_view>;
  typename F::Multiplier;
  typename F::Rows;
  requires sizeof(typename F::Multiplier) == F::Rows::kRows * sizeof(Real);
  { family.size() } -> std::convertible_to<size_t>;
  { family.object[k] } -> std::convertible_to<Index>;
  { family.batches } -> std::convertible_to<ColorBatches>;
  { family.rows(k, x) } -> std::same_as<typename F::Rows>;
  { family.energy(x, k) } -> std::same_as<Real>;
  { family.max_error(x, k) } -> std::same_as<Real>;
  mutable_family.color(inv_mass);
};

/// A zero multiplier block (Eigen vectors are not zeroed by default construction).
template <class Multiplier>
Multiplier zero_multiplier() {
  if constexpr (std::is_arithmetic_v<Multiplier>)
    return Multiplier{0};
  else
    return Multiplier::Zero();
}

/// The multipliers of one constraint as an R-vector (Real, Vec2 and Vec3 are R contiguous doubles).
template <class F>
auto multiplier_rows(typename F::Multiplier& lambda) {
  return Eigen::Map<typename F::Rows::Vector>(reinterpret_cast<Real*>(&lambda));
}

}  // namespace moreau
