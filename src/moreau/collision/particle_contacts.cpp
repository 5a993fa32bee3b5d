#include "moreau/collision/particle_contacts.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "moreau/model/state.hpp"

namespace moreau {

void ColliderContacts::clear() {
  particle.clear();
  collider.clear();
  group_offsets.clear();
  lambda_normal.clear();
  lambda_friction.clear();
  lambda_rolling.clear();
  normal.clear();
  static_friction.clear();
  dynamic_friction.clear();
  restitution.clear();
  adhesion.clear();
  rolling_resistance.clear();
  spring.clear();
}

void ParticleContacts::clear() {
  pair.clear();
  batches.clear();
  lambda_normal.clear();
  lambda_friction.clear();
  lambda_rolling.clear();
  normal.clear();
  static_friction.clear();
  dynamic_friction.clear();
  restitution.clear();
  cohesion.clear();
  cohesion_distance.clear();
  rolling_resistance.clear();
  spring.clear();
}

namespace {
// Friction and restitution of a pair: the mean of the two (Mueller 2020, sec. 3.5). Cohesion too:
// a cohesive grain on a dry one holds with half its bond.
Real combine(Real a, Real b) { return 0.5 * (a + b); }

// The strength of the bond between two objects' particles: only grains bond (a dry granular
// object has cohesion 0 and cohesion_distance 0).
Real bond_strength(const ObjectInfo& a, const ObjectInfo& b) {
  return a.kind == ObjectKind::granular && b.kind == ObjectKind::granular ? combine(a.cohesion, b.cohesion) : 0;
}

// Rolling resistance of a pair: the mean of two grains'; a grain's own against a particle that
// does not turn (whose mu_r is 0).
Real rolling_resistance(const ObjectInfo& a, const ObjectInfo& b) {
  return a.kind == ObjectKind::granular && b.kind == ObjectKind::granular
             ? combine(a.rolling_resistance, b.rolling_resistance)
             : std::max(a.rolling_resistance, b.rolling_resistance);
}

// The viscoelastic spring of a pair: the mean of two grains'; a grain's own against a particle
// of another kind (which has none).
ContactSpring pair_spring(const ObjectInfo& a, const ObjectInfo& b) {
  if (a.kind == ObjectKind::granular && b.kind == ObjectKind::granular) return mean_spring(a.contact_spring, b.contact_spring);
  return a.kind == ObjectKind::granular ? a.contact_spring : b.contact_spring;
}

// The gap within which two objects' particles pull on each other: 0 unless their bond has
// strength; at most the largest cohesion_distance of a cohesive object.
Real bond_distance(const ObjectInfo& a, const ObjectInfo& b) {
  return bond_strength(a, b) > 0 ? combine(a.cohesion_distance, b.cohesion_distance) : 0;
}

// Reorders the pairs (found cell by cell, in the grid's Morton order) tile by tile, the tiles by
// colour (constraints/tile_batches.hpp). A tile is the cells whose Morton keys agree but for the
// lowest two bits of each axis (cell coordinates taken from the grid's corner), so its cells are
// contiguous in the sort; the lowest three bits of the remaining key are the parities of the
// tile's coordinates, its colour.
void sort_pairs_into_tiles(const CellGrid& grid, ContactScratch& scratch, ParticleContacts& c) {
  constexpr int kTileKeyShift = 3 * std::countr_zero(static_cast<unsigned>(kTileCells));
  auto& tiles = scratch.color_tile_pairs;  // per colour, the pair ranges of its tiles
  for (auto& color : tiles) color.clear();
  const Index cells = grid.cell_count();
  for (Index first = 0; first < cells;) {
    const std::uint64_t tile_key = grid.cell_key(first) >> kTileKeyShift;
    Index last = first + 1;
    while (last < cells && grid.cell_key(last) >> kTileKeyShift == tile_key) ++last;
    const std::array<Index, 2> pairs{scratch.cell_pair_begin[first], scratch.cell_pair_begin[last]};
    if (pairs[1] > pairs[0]) tiles[tile_key % kTileColors].push_back(pairs);
    first = last;
  }
  TileBatches& batches = c.batches;
  batches.clear();
  scratch.tiled_pairs.clear();
  for (const auto& color : tiles) {
    for (const auto& [first_pair, end_pair] : color) {
      scratch.tiled_pairs.insert(scratch.tiled_pairs.end(), c.pair.begin() + first_pair, c.pair.begin() + end_pair);
      batches.tile_offsets.push_back(static_cast<Index>(scratch.tiled_pairs.size()));
    }
    batches.color_tiles.push_back(static_cast<Index>(batches.tile_offsets.size()) - 1);
  }
  c.pair.swap(scratch.tiled_pairs);
}

// The coefficients of a pair of two objects' particles.
struct PairMaterial {
  Real static_friction, dynamic_friction, restitution, cohesion, cohesion_distance, rolling_resistance;
  ContactSpring spring;
};

PairMaterial pair_material(const ObjectInfo& a, const ObjectInfo& b) {
  return {combine(a.static_friction, b.static_friction),
          combine(a.dynamic_friction, b.dynamic_friction),
          combine(a.restitution, b.restitution),
          bond_strength(a, b),
          bond_distance(a, b),
          rolling_resistance(a, b),
          pair_spring(a, b)};
}

// The coefficients of every pair from its two objects, and zero multipliers. Pairs of the same two
// objects follow one another in long runs (a pile is one object), so each run's are found once.
void set_pair_materials(const Model& model, ParticleContacts& c) {
  const size_t m = c.pair.size();
  c.lambda_normal.assign(m, 0);
  c.lambda_friction.assign(m, Vec3::Zero());
  c.lambda_rolling.assign(m, Vec3::Zero());
  c.normal.assign(m, Vec3::Zero());
  c.static_friction.resize(m);
  c.dynamic_friction.resize(m);
  c.restitution.resize(m);
  c.cohesion.resize(m);
  c.cohesion_distance.resize(m);
  c.rolling_resistance.resize(m);
  c.spring.resize(m);
  Index last_a = -1, last_b = -1;
  PairMaterial material{};
  for (size_t q = 0; q < m; ++q) {
    const Index oa = model.particle_object[c.pair[q][0]], ob = model.particle_object[c.pair[q][1]];
    if (oa != last_a || ob != last_b) {
      material = pair_material(model.objects[oa], model.objects[ob]);
      last_a = oa;
      last_b = ob;
    }
    c.static_friction[q] = material.static_friction;
    c.dynamic_friction[q] = material.dynamic_friction;
    c.restitution[q] = material.restitution;
    c.cohesion[q] = material.cohesion;
    c.cohesion_distance[q] = material.cohesion_distance;
    c.rolling_resistance[q] = material.rolling_resistance;
    c.spring[q] = material.spring;
  }
}
}  // namespace

void detect_collider_contacts(const Model& model, State& state) {
  ColliderContacts& c = state.collider_contacts;
  c.clear();
  if (model.colliders.empty()) return;
  const Real dt = model.settings.dt, k = model.settings.contact_margin_factor;
  // A solid collider's surface lies within its bounding sphere: a particle farther from its centre
  // than that sphere plus its reach needs no distance query (a silo's walls and floor pieces
  // against thousands of grains). Planes and containers have no such bound (-1).
  const Index colliders = static_cast<Index>(model.colliders.size());
  std::vector<Real> bound(colliders, -1);
  for (Index ci = 0; ci < colliders; ++ci) {
    const Collider& col = model.colliders[ci];
    if (!col.inside && col.shape.type != ShapeType::plane) bound[ci] = col.shape.bounding_radius();
  }
  for (Index p = 0; p < model.particle_count(); ++p) {
    if (model.particle_inv_mass[p] <= 0 || !state.live(p)) continue;
    const ObjectInfo& obj = model.objects[model.particle_object[p]];
    const Index group_start = static_cast<Index>(c.particle.size());
    const bool asleep = state.sleep.asleep(p);
    for (Index ci = 0; ci < colliders; ++ci) {
      const Collider& col = model.colliders[ci];
      if (!col.present_at(state.time)) continue;  // removed (`until`)
      if (asleep && !col.changes()) continue;     // a sleeping grain rests on a fixed collider
      // Reach: what the particle can travel in the step, by its velocity and by gravity.
      const Real reach = model.particle_collider_gap[p] +
                         k * dt * ((state.velocity[p] - col.velocity).norm() + dt * model.settings.gravity.norm());
      const Vec3 center = col.position_at(state.time);
      if (bound[ci] >= 0 && (state.position[p] - center).squaredNorm() > (bound[ci] + reach) * (bound[ci] + reach)) continue;
      const Real d = collider_distance(col, center, state.position[p]).distance;
      if (d > reach) continue;
      c.particle.push_back(p);
      c.collider.push_back(ci);
      c.lambda_normal.push_back(0);
      c.lambda_friction.push_back(Vec3::Zero());
      c.lambda_rolling.push_back(Vec3::Zero());
      c.normal.push_back(Vec3::Zero());
      c.static_friction.push_back(combine(obj.static_friction, col.static_friction));
      c.dynamic_friction.push_back(combine(obj.dynamic_friction, col.dynamic_friction));
      c.restitution.push_back(combine(obj.restitution, col.restitution));
      c.adhesion.push_back(std::max(obj.adhesion, col.adhesion));
      c.rolling_resistance.push_back(obj.rolling_resistance);
      c.spring.push_back(obj.contact_spring);
    }
    if (static_cast<Index>(c.particle.size()) > group_start) c.group_offsets.push_back(group_start);
  }
  c.group_offsets.push_back(static_cast<Index>(c.particle.size()));
}

void detect_particle_contacts(const Model& model, State& state, ContactScratch& scratch, int threads) {
  ParticleContacts& c = state.particle_contacts;
  c.clear();
  const std::vector<Index>& contact_particle = state.live_contact_particles(model);
  if (!model.settings.particle_contacts || contact_particle.size() < 2) return;
  // Every contact particle a sleeping grain: no pair can have an awake side.
  if (state.sleep.asleep_count == static_cast<Index>(contact_particle.size())) return;

  // A pair is a candidate within reach r_i + r_j + g + min(k dt |v_i - v_j|, r_i + r_j), at most
  // 4 r_max + g_max (g the pair's bond distance, g_max <= r_max the largest). The grid's cells are
  // 2.5 r_max + g_max: every pair within that distance lies in the 27 cells around either
  // particle. With V the particles' mean velocity, |v_i - v_j| <= |v_i - V| + |v_j - V|, so a pair
  // of particles that each move less than u = 0.25 r_max / (k dt) apart from V reaches at most a
  // cell. The others are "fast" and search the cells (two each way at most) within 4 r_max + g_max
  // of them. A block falling as one is slow everywhere; a few rattlers in a pile do not coarsen
  // the grid for all.
  const Index n = static_cast<Index>(contact_particle.size());
  Real max_radius = 0;
  Vec3 mean_velocity = Vec3::Zero();
  scratch.contact_position.resize(n);
  for (Index a = 0; a < n; ++a) {
    const Index p = contact_particle[a];
    max_radius = std::max(max_radius, model.particle_radius[p]);
    mean_velocity += state.velocity[p];
    scratch.contact_position[a] = state.position[p];
  }
  mean_velocity /= static_cast<Real>(n);
  Real max_bond = 0;
  for (const ObjectInfo& object : model.objects)
    if (object.cohesion > 0) max_bond = std::max(max_bond, object.cohesion_distance);
  const Real dt = model.settings.dt, k = model.settings.contact_margin_factor;
  const Real slow_speed = 0.25 * max_radius / (k * dt);
  const Real fall = dt * model.settings.gravity.norm();  // what gravity adds to a speed over the step
  // The Morton-sorted grid of the fluids: the particles of a cell are contiguous in `order`, and
  // cells near in space are near in memory, so the pairs come out in a spatially coherent order.
  const CellGrid& grid = scratch.grid;
  scratch.grid.build(scratch.contact_position.data(), n, GridFrame{Vec3::Zero(), 2.5 * max_radius + max_bond});
  const std::vector<Index>& order = grid.order();
  const Index cells = grid.cell_count();
  // Positions, radii, velocities, particle ids, objects and flags in the sorted order, so the scan
  // below reads memory in sequence.
  scratch.sorted_position.resize(n);
  scratch.sorted_radius.resize(n);
  scratch.sorted_particle.resize(n);
  scratch.sorted_velocity.resize(n);
  scratch.sorted_object.resize(n);
  scratch.sorted_fast.resize(n);
  scratch.sorted_moves.resize(n);
  scratch.sorted_asleep.resize(n);
  for (Index s = 0; s < n; ++s) {
    const Index a = order[s], p = contact_particle[a];
    scratch.sorted_position[s] = scratch.contact_position[a];
    scratch.sorted_particle[s] = p;
    scratch.sorted_radius[s] = model.particle_radius[p];
    scratch.sorted_velocity[s] = state.velocity[p];
    scratch.sorted_object[s] = model.particle_object[p];
    scratch.sorted_fast[s] = (state.velocity[p] - mean_velocity).squaredNorm() > slow_speed * slow_speed;
    scratch.sorted_moves[s] = model.particle_inv_mass[p] > 0;
    scratch.sorted_asleep[s] = state.sleep.asleep(p);
  }

  // The reach of the bond between two objects' particles, looked up per candidate.
  const Index objects = static_cast<Index>(model.objects.size());
  scratch.bond_reach.resize(objects * objects);
  for (Index a = 0; a < objects; ++a)
    for (Index b = 0; b < objects; ++b) scratch.bond_reach[a * objects + b] = bond_distance(model.objects[a], model.objects[b]);

  threads = std::max(1, threads);
  scratch.thread_pairs.resize(threads);
  for (auto& list : scratch.thread_pairs) list.clear();  // OpenMP may run fewer threads than asked
  scratch.thread_first_cell.assign(threads, cells);       // cells: the thread got none
  scratch.cell_pair_begin.resize(cells + 1);
#pragma omp parallel num_threads(threads)
  {
    auto& pairs = scratch.thread_pairs[omp_get_thread_num()];
    // The candidate at sorted positions s and t: kept if within its reach.
    auto consider = [&](Index s, Index t) __attribute__((always_inline)) {
      const Real contact_distance = scratch.sorted_radius[s] + scratch.sorted_radius[t];
      const Real distance2 = (scratch.sorted_position[s] - scratch.sorted_position[t]).squaredNorm();
      const Real farthest = 2 * contact_distance + max_bond;
      if (distance2 >= farthest * farthest) return;  // beyond any reach
      if (!scratch.sorted_moves[s] && !scratch.sorted_moves[t]) return;
      if (scratch.sorted_asleep[s] && scratch.sorted_asleep[t]) return;  // two sleeping grains rest as they are
      const Index i = scratch.sorted_particle[s], j = scratch.sorted_particle[t];
      const Index oi = scratch.sorted_object[s], oj = scratch.sorted_object[t];
      if (oi == oj) {
        const ObjectInfo& object = model.objects[oi];
        if (!object.self_collision) return;
        // Neighbours that are closer than the contact distance at rest never collide (grains
        // have no neighbours: each touches every other but the spheres of its own clump).
        if (object.clump_size > 0) {
          if ((i - object.particle_begin) / object.clump_size == (j - object.particle_begin) / object.clump_size) return;
        } else if (object.kind != ObjectKind::granular &&
                   (model.particle_rest_position[i] - model.particle_rest_position[j]).norm() < contact_distance) {
          return;
        }
      } else if (model.objects[oi].kind == ObjectKind::continuum && model.objects[oj].kind == ObjectKind::continuum) {
        return;  // one continuum: its particles' constraints hold them apart (continuum_model.hpp)
      }
      const Real reach =
          contact_distance + scratch.bond_reach[oi * objects + oj] +
          std::min(k * dt * ((scratch.sorted_velocity[s] - scratch.sorted_velocity[t]).norm() + fall), contact_distance);
      if (distance2 < reach * reach) pairs.push_back({std::min(i, j), std::max(i, j)});
    };
    // Static schedule: each thread gets one contiguous run of cells, so joining the per-thread
    // lists in the order of their runs reproduces the serial order for any thread count.
    // Each pair is visited once: two slow particles from the earlier one in the sort (its own
    // cell's later particles and the 13 cells ahead of it), a pair with a fast particle from the
    // fast one, two fast particles from the earlier one. Every pair is found from a particle of
    // the cell it is counted in, and lies within 4 r_max + g_max of that particle (the tiles'
    // separation rests on it: constraints/tile_batches.hpp).
#pragma omp for schedule(static)
    for (Index c = 0; c < cells; ++c) {
      Index& first_cell = scratch.thread_first_cell[omp_get_thread_num()];
      first_cell = std::min(first_cell, c);
      const size_t found_before = pairs.size();
      CellRange ahead[13], wide[125];
      const int ahead_count = grid.ranges_ahead(grid.cell_coord(c), ahead);
      const Index end = grid.cell_begin(c + 1);
      for (Index s = grid.cell_begin(c); s < end; ++s) {
        if (!scratch.sorted_fast[s]) {
          for (Index t = s + 1; t < end; ++t)
            if (!scratch.sorted_fast[t]) consider(s, t);
          for (int r = 0; r < ahead_count; ++r)
            for (Index t = ahead[r].first; t < ahead[r].second; ++t)
              if (!scratch.sorted_fast[t]) consider(s, t);
        } else {
          // The cells within the farthest reach, 4 r_max + g_max, of the particle.
          const int wide_count = grid.ranges_near(scratch.sorted_position[s], 4 * max_radius + max_bond, wide);
          for (int r = 0; r < wide_count; ++r)
            for (Index t = wide[r].first; t < wide[r].second; ++t)
              if (t != s && (!scratch.sorted_fast[t] || t > s)) consider(s, t);
        }
      }
      scratch.cell_pair_begin[c + 1] = static_cast<Index>(pairs.size() - found_before);  // a count, summed below
    }
  }
  // The threads' lists joined in the order of their cells (a static schedule hands out contiguous
  // runs of cells, though OpenMP does not promise them in thread order): the pairs in cell order.
  scratch.thread_order.resize(threads);
  for (int t = 0; t < threads; ++t) scratch.thread_order[t] = t;
  std::sort(scratch.thread_order.begin(), scratch.thread_order.end(),
            [&](int a, int b) { return scratch.thread_first_cell[a] < scratch.thread_first_cell[b]; });
  for (int t : scratch.thread_order)
    c.pair.insert(c.pair.end(), scratch.thread_pairs[t].begin(), scratch.thread_pairs[t].end());
  if (c.pair.empty()) return;
  scratch.cell_pair_begin[0] = 0;
  for (Index cell = 0; cell < cells; ++cell) scratch.cell_pair_begin[cell + 1] += scratch.cell_pair_begin[cell];

  sort_pairs_into_tiles(grid, scratch, c);
  set_pair_materials(model, c);
}

}  // namespace moreau
