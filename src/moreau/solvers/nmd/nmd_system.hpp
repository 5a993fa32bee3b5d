#pragma once
// The regularised, stabilised velocity-level system of one NMD solve (SPOOK: Lacoursiere 2007,
// "Ghosts and Machines", ch. 4; Servin, Lacoursiere, Melin 2006):
//
//   [ M  -G^T ] [ v+ ]   [ M v + h f        ]      a = 4 / (h (1 + 4d)),  b = 1 / (1 + 4d),
//   [ G   S   ] [ l  ] = [ -a g + b G v     ]      S = 4 eps / (h^2 (1 + 4d)),
//
// l = h lambda the impulse of the rows (the force is l / h), eps their compliance, d = tau / h
// their relaxation time in steps and g their value C. Eliminating v+ gives the Schur form
//   (G M^-1 G^T + S) l = q - G v*,   v* = v + h M^-1 f,   v+ = v* + M^-1 G^T l,
// which every method here solves with the complementarity of bounded rows: l_i = lo_i implies
// w_i >= 0, l_i = hi_i implies w_i <= 0, and w_i = 0 in between (w = G v+ + S l - q).
//
// Rows come in blocks: one constraint of a family, one joint block, one contact point. Rows of a
// block share up to four ends (velocity_space.hpp) and a compliance block. A row is one of
//   position  a holonomic row: q = -a C + b dC/dt (the SPOOK stabilisation above),
//   velocity  a motor: dC/dt + (eps / h) l = target (Lacoursiere's velocity constraint),
//   friction  a dissipative row: dC/dt = 0, bounded by the contact's normal impulse.
// A damper block (a joint's damping) is velocity rows of target 0 whose compliance is their own
// mobility over the rate c: eps = G W G^T / c, so S = G W G^T / (c h), and alone the block
// leaves dC/dt / (1 + c h) of its rate each step: the force -c (G W G^T)^-1 dC/dt+ is c times
// the ends' effective mass times their relative velocity, an implicit damper of decay rate c.
// Contact normal rows take the gap C >= 0 of speculative contacts exactly (q = -C / h: the gap
// may close within the step, no further) and add restitution, q >= -e dC/dt before the step for
// impacts faster than the threshold. A contact's friction rows are bounded by mu_s times the
// normal impulse while the contact slips slower than settings.sliding_speed at the step's start,
// by mu_k once it slides (static and kinetic Coulomb friction). An adhesive contact's normal row
// has a negative lower bound (nmd_assembly.cpp) and no speculative target. `known` is the part of dC/dt from ends outside the velocity
// vector (a moving collider).
#include <array>
#include <limits>
#include <vector>

#include "moreau/math/uninitialized_allocator.hpp"
#include "moreau/solvers/nmd/nmd_settings.hpp"
#include "moreau/solvers/nmd/velocity_space.hpp"

namespace moreau {

enum class RowLevel : std::uint8_t { position, velocity, friction };

/// How a block's rows are projected: an equality block is solved whole (its R x R matrix
/// inverted once); a bounded block row by row with fixed bounds; a contact block is a normal row
/// (rows 0) and two friction rows bounded by mu times its impulse, and where a side turns as a
/// grain three turning rows (turning_contact_rows.hpp) bounded by mu_r R* times it. A grain pair
/// is the contact block of two grains that both turn, its six rows kept in closed form
/// (GrainPairRows) instead of entry by entry: a pile's solve is mostly these, and reading 15
/// numbers a contact instead of 144 Jacobian and W J^T entries is what makes its sweeps fast.
enum class NmdBlockKind : std::uint8_t { equality, bounded, contact, grain_pair };

/// The rows of a contact between grains i and j that both turn (turning_contact_rows.hpp), over
/// the ends (v_i, v_j, w_i, w_j). With the arms' lever u = r_i' w_i + r_j' w_j their rates are
///   row 0      n . (v_i - v_j)                  (a_s x n = 0)
///   rows 1, 2  t1 . (v_i - v_j) - t2 . u,  t2 . (v_i - v_j) + t1 . u
///                                               (-r (n x t1) = -r t2, -r (n x t2) = r t1 on both sides)
///   rows 3-5   (t1, t2, n) . (w_i - w_j),
/// and an impulse l on the rows changes them by W G^T l:
///   v_i += m_i^-1 P,  v_j -= m_j^-1 P,           P = l_0 n + l_1 t1 + l_2 t2
///   w_i += I_i^-1 (r_i' T + L),  w_j += I_j^-1 (r_j' T - L),   T = -l_1 t2 + l_2 t1,  L = l_3 t1 + l_4 t2 + l_5 n.
/// G W G^T is diagonal but for the friction-turning coupling (r_i' I_i^-1 - r_j' I_j^-1), zero
/// between equal grains: D_0 = m_i^-1 + m_j^-1, D_1 = D_2 = D_0 + r_i'^2 I_i^-1 + r_j'^2 I_j^-1,
/// D_3 = D_4 = D_5 = I_i^-1 + I_j^-1.
struct GrainPairRows {
  Vec3 n = Vec3::Zero(), t1 = Vec3::Zero(), t2 = Vec3::Zero();
  Real arm[2] = {0, 0};          // m: r_i', r_j'
  Real inv_mass[2] = {0, 0};     // 1/kg (set by NmdSystem::fill from the velocity space)
  Real inv_inertia[2] = {0, 0};  // 1/(kg m^2), likewise
};

/// One block as an assembler hands it over: R rows over any number of ends (a joint has two, a
/// fluid particle's density row one per neighbour).
struct NmdBlockInput {
  static constexpr int kMaxRows = 6;
  using Vector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, kMaxRows, 1>;
  using Matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRows, kMaxRows>;

  NmdBlockKind kind = NmdBlockKind::equality;
  std::vector<VelocityEnd> end;
  std::vector<Real> jacobian;         // R x 6 ends, row-major: row r, end e at [6 (r ends + e), + 6)
  Vector C, known, target, lower, upper;  // lower/upper in force units (N, N m); target for velocity rows
  Matrix compliance;                  // eps, R x R
  std::array<RowLevel, kMaxRows> level{};
  Real damping_time = 0;              // s
  Real damper_rate = 0;               // 1/s: a damper block (see NmdSystem::add), 0 otherwise
  Real static_friction = 0, dynamic_friction = 0, restitution = 0;  // contact blocks
  Real cohesion = 0;                  // N, contact blocks: a bond's strength, added to the normal force in the friction bound
  Real rolling = 0;                   // m, contact blocks with turning rows: mu_r R*, their bound per unit normal force
  GrainPairRows grain_pair;           // grain pairs: n, t1, t2 and the arms (the ends are v_i, v_j, w_i, w_j; no Jacobian)
  Real* memory = nullptr;             // l h of the rows (kg m for positional rows): warm start in, result out
  int memory_rows = 0;

  /// Sizes an input of `rows` rows over `ends` ends (without Jacobian entries unless `entries`:
  /// a grain pair keeps none) and clears everything else: zero Jacobian, C, known and target;
  /// no compliance, damping, friction, restitution or memory; an equality block of unbounded
  /// position rows. The buffers keep their capacity from block to block.
  void resize(int rows, int end_count, bool entries = true);
  /// Grows the input to `rows` rows over `end_count` ends, keeping what is set: the new rows are
  /// unbounded position rows of zero C, the new ends and entries zero.
  void extend(int rows, int end_count);
  int rows() const { return static_cast<int>(C.size()); }
  int ends() const { return static_cast<int>(end.size()); }
  /// The six Jacobian entries of row r at end e (linear, then angular; particles use three).
  Real* at(int r, int e) { return jacobian.data() + 6 * (static_cast<std::size_t>(r) * end.size() + e); }
  const Real* at(int r, int e) const { return jacobian.data() + 6 * (static_cast<std::size_t>(r) * end.size() + e); }
};

struct NmdBlock {
  NmdBlockKind kind = NmdBlockKind::equality;
  int rows = 0, ends = 0;
  Index first_row = 0;
  Index first_end = 0;                // into NmdSystem::block_ends
  Index matrix = -1;                  // equality blocks: offset of the R x R inverse of G W G^T + S; contact
                                      // blocks of six rows: of the 3 x 3 inverse of their turning rows' G W G^T
  Real friction = 0;                  // contact blocks: mu of this solve (static or kinetic)
  Real cohesion = 0;                  // contact blocks: F h of a bond (the friction bound is mu (l_n + F h))
  Real rolling = 0;                   // contact blocks of six rows: mu_r R* (m), the turning rows' bound per unit of l_n + F h
  Index grain_pair = -1;              // grain pairs: their rows in NmdSystem::grain_pairs
  Real* memory = nullptr;
  int memory_rows = 0;
};

/// Where a block's data go in the system's arrays (room made by NmdSystem::grow).
struct NmdSlot {
  Index block = 0, first_row = 0, first_end = 0, first_entry = 0;
  Index matrix = -1;  // equality blocks: the offset of their R x R matrices (a turning block's 3 x 3)
  Index grain_pair = -1;  // grain pairs: their place in NmdSystem::grain_pairs
};

struct NmdSystem {
  std::vector<NmdBlock> blocks;
  std::vector<VelocityEnd> block_ends;  // every block's ends, from NmdBlock::first_end
  // Per row: its ends' Jacobian entries and W J^T (end.size per end: 3 for a particle, 6 for a
  // body, none for the world; from jacobian_offset), the
  // right-hand side q, the bounds in impulse units, S_ii and l.
  std::vector<Index> jacobian_offset, row_block;
  std::vector<Real, UninitializedAllocator<Real>> jacobian, weighted;  // grown, then filled block by block
  std::vector<Real> rhs, lower, upper, sigma, impulse;
  // Per row: a contact's friction rows keep G_t W G_n^T, how much their rate changes per unit of
  // the normal row's impulse (0 on every other row).
  std::vector<Real> normal_coupling;
  // Per row: 1 / (G_i W G_i^T + S_ii), 0 where that is not positive, so a sweep multiplies; a
  // contact's friction rows both keep 1 / the larger of their two diagonals.
  std::vector<Real> inverse_diagonal;
  std::vector<Real> sigma_block;      // equality blocks: S, R x R (row-major), at NmdBlock::matrix
  std::vector<Real> inverse;          // equality blocks: (G W G^T + S)^-1, R x R; turning rows' (G W G^T)^-1, 3 x 3
  std::vector<GrainPairRows> grain_pairs;  // grain pairs' rows, from NmdBlock::grain_pair

  void clear();
  Index row_count() const { return static_cast<Index>(rhs.size()); }
  const VelocityEnd* ends_of(const NmdBlock& b) const { return block_ends.data() + b.first_end; }
  /// G_i v for row i of block b over its ends (a block with Jacobian entries: not a grain pair).
  Real rate(const NmdBlock& b, Index row, const std::vector<Real>& v) const {
    const Real* J = jacobian.data() + jacobian_offset[row];
    const VelocityEnd* end = ends_of(b);
    Real value = 0;
    for (int e = 0; e < b.ends; ++e) {
      value += end_rate(J, v.data() + end[e].dof, end[e].size);
      J += end[e].size;
    }
    return value;
  }
  /// One end's share of G_i v. The products are summed in pairs, not in one running sum: a
  /// Gauss-Seidel row waits on this sum, and pairs halve the chain of dependent additions.
  static Real end_rate(const Real* J, const Real* v, int size) {
    if (size == 6) return ((J[0] * v[0] + J[1] * v[1]) + (J[2] * v[2] + J[3] * v[3])) + (J[4] * v[4] + J[5] * v[5]);
    if (size == 3) return (J[0] * v[0] + J[1] * v[1]) + J[2] * v[2];
    Real value = 0;
    for (int c = 0; c < size; ++c) value += J[c] * v[c];
    return value;
  }
  /// Adds a block for a solve of step h with velocities `space.v` at the step's start (before
  /// forces): its right-hand side, regularisation, bounds and local matrix.
  void add(const NmdBlockInput& input, const VelocitySpace& space, Real h, const NmdSettings& settings);
  /// add() in two halves, so that blocks can be filled in parallel after room for them is made in
  /// order: grow() appends room for `block_count` blocks with `end_count` ends, `rows` rows,
  /// `entries` Jacobian entries (and as many of W J^T, left uninitialised) and `matrix_entries`
  /// entries of equality-block matrices in all; fill() writes one block into its slot there,
  /// touching nothing outside it.
  void grow(Index block_count, Index end_count, Index rows, Index entries, Index matrix_entries);
  void fill(const NmdSlot& slot, const NmdBlockInput& input, const VelocitySpace& space, Real h,
            const NmdSettings& settings);
};

}  // namespace moreau
