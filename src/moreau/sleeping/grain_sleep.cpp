#include "moreau/sleeping/grain_sleep.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "moreau/model/state.hpp"

namespace moreau {

void GrainSleepState::resize(const std::vector<Vec3>& positions) {
  const Index particles = static_cast<Index>(positions.size());
  still_from = positions;
  still_time.assign(particles, 0);
  island.assign(particles, -1);
  asleep_count = 0;
  list_awake();
}

void GrainSleepState::list_awake() {
  awake.clear();
  for (Index p = 0; p < static_cast<Index>(island.size()); ++p)
    if (island[p] < 0) awake.push_back(p);
}

namespace {

// A grain that can sleep: a live particle of a granular object (not one its emitter holds back).
bool is_grain(const Model& model, const State& state, Index p) {
  return model.objects[model.particle_object[p]].kind == ObjectKind::granular && state.live(p);
}

// Union-find over particles; the root of a set is its smallest particle, whatever the order of
// the joins.
Index find_root(std::vector<Index>& parent, Index p) {
  while (parent[p] != p) {
    parent[p] = parent[parent[p]];  // path halving
    p = parent[p];
  }
  return p;
}

void join(std::vector<Index>& parent, Index a, Index b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  if (a < b) parent[b] = a;
  if (b < a) parent[a] = b;
}

// Wakes every grain of the listed islands (any order, repeats allowed): their still time starts
// again where they are.
void wake_islands(State& state, std::vector<Index>& islands) {
  GrainSleepState& sleep = state.sleep;
  std::sort(islands.begin(), islands.end());
  islands.erase(std::unique(islands.begin(), islands.end()), islands.end());
  for (Index p = 0; p < static_cast<Index>(sleep.island.size()); ++p) {
    if (!sleep.asleep(p) || !std::binary_search(islands.begin(), islands.end(), sleep.island[p])) continue;
    sleep.island[p] = -1;
    sleep.still_time[p] = 0;
    sleep.still_from[p] = state.position[p];
    --sleep.asleep_count;
  }
  sleep.list_awake();
}

}  // namespace

bool body_wakes_grains(const Model& model, const State& state, Index b) {
  return model.rigid.is_dynamic(b) || !state.rigid.velocity[b].isZero() || !state.rigid.angular_velocity[b].isZero();
}

bool wake_reached_islands(State& state) {
  GrainSleepState& sleep = state.sleep;
  if (sleep.asleep_count == 0) return false;
  // Detection never pairs two sleeping grains, nor a sleeping grain with a fixed collider or body:
  // every candidate of a sleeping grain reaches its island from outside.
  std::vector<Index> reached;
  for (const auto& [i, j] : state.particle_contacts.pair) {
    if (sleep.asleep(i)) reached.push_back(sleep.island[i]);
    if (sleep.asleep(j)) reached.push_back(sleep.island[j]);
  }
  for (Index p : state.collider_contacts.particle)
    if (sleep.asleep(p)) reached.push_back(sleep.island[p]);
  for (const auto& [b, p] : state.particle_body_contacts.pair)
    if (sleep.asleep(p)) reached.push_back(sleep.island[p]);
  if (reached.empty()) return false;
  wake_islands(state, reached);
  return true;
}

void wake_moved_grains(const Model& model, State& state) {
  GrainSleepState& sleep = state.sleep;
  if (sleep.asleep_count == 0) return;
  std::vector<Index> moved;
  for (Index p = 0; p < model.particle_count(); ++p)
    if (sleep.asleep(p) && (state.position[p] != sleep.still_from[p] || !state.velocity[p].isZero() ||
                            !state.angular_velocity[p].isZero()))
      moved.push_back(sleep.island[p]);
  if (!moved.empty()) wake_islands(state, moved);
}

void update_grain_sleep(const Model& model, State& state) {
  const SleepSettings& settings = model.settings.sleep;
  if (!settings.enabled) return;
  GrainSleepState& sleep = state.sleep;
  const Index n = model.particle_count();
  const Real dt = model.settings.dt, drift2 = std::pow(settings.speed * settings.time, 2);
  bool ready = false;  // some awake grain has been still for the sleep time
  for (Index p = 0; p < n; ++p) {
    if (sleep.asleep(p) || !is_grain(model, state, p)) continue;
    if ((state.position[p] - sleep.still_from[p]).squaredNorm() <= drift2) {
      sleep.still_time[p] += dt;
      ready |= sleep.still_time[p] >= settings.time;
    } else {
      sleep.still_from[p] = state.position[p];
      sleep.still_time[p] = 0;
    }
  }
  if (!ready) return;

  // Islands: awake grains joined by the step's candidates. A grain keeps its island awake while it
  // has not been still long enough, or has a candidate that does not sleep.
  std::vector<Index>& parent = sleep.parent;
  parent.resize(n);
  std::iota(parent.begin(), parent.end(), Index{0});
  std::vector<char>& keeps_awake = sleep.keeps_awake;
  keeps_awake.assign(n, 0);
  for (const auto& [i, j] : state.particle_contacts.pair) {
    const bool grain_i = is_grain(model, state, i), grain_j = is_grain(model, state, j);
    if (grain_i && grain_j) {
      join(parent, i, j);
    } else {
      keeps_awake[i] |= grain_i;
      keeps_awake[j] |= grain_j;
    }
  }
  const ShapeMatchClusters& clusters = model.shape_matching;  // a clump's spheres sleep and wake together
  for (Index k = 0; k < clusters.size(); ++k)
    if (model.objects[clusters.object[k]].kind == ObjectKind::granular)
      for (Index e = clusters.offsets[k] + 1; e < clusters.offsets[k + 1]; ++e)
        join(parent, clusters.particle[clusters.offsets[k]], clusters.particle[e]);
  for (size_t q = 0; q < state.collider_contacts.size(); ++q)
    if (model.colliders[state.collider_contacts.collider[q]].changes())
      keeps_awake[state.collider_contacts.particle[q]] = 1;
  for (const auto& [b, p] : state.particle_body_contacts.pair)
    if (body_wakes_grains(model, state, b)) keeps_awake[p] = 1;
  for (const Joint& joint : model.joints)  // a grain held by a joint moves with it
    for (const JointEnd& end : joint.ends)
      if (end.kind == BodyEndKind::particle) keeps_awake[end.index] = 1;

  std::vector<char>& island_awake = sleep.island_awake;  // by root
  island_awake.assign(n, 0);
  for (Index p = 0; p < n; ++p) {
    if (sleep.asleep(p) || !is_grain(model, state, p)) continue;
    if (keeps_awake[p] || sleep.still_time[p] < settings.time) island_awake[find_root(parent, p)] = 1;
  }
  const Index asleep_before = sleep.asleep_count;
  for (Index p = 0; p < n; ++p) {
    if (sleep.asleep(p) || !is_grain(model, state, p)) continue;
    const Index root = find_root(parent, p);
    if (island_awake[root]) continue;
    sleep.island[p] = root;
    sleep.still_from[p] = state.position[p];
    state.velocity[p].setZero();
    state.angular_velocity[p].setZero();
    ++sleep.asleep_count;
  }
  if (sleep.asleep_count != asleep_before) sleep.list_awake();
}

}  // namespace moreau
