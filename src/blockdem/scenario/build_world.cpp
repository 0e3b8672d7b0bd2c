// The world a scenario describes: its blocks, joint laws and rules, joints prestressed by the
// in-situ stress, with deep initial overlaps (unless allowed) and an absurd time step refused as
// input errors.
#include <Eigen/Core>
#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "blockdem/collision/boon2012.hpp"
#include "blockdem/collision/uniform_grid.hpp"
#include "blockdem/numerics/units.hpp"
#include "blockdem/scenario/scenario.hpp"

namespace blockdem {

void check_time_step(const Scenario& sc, const World& world) {
  const double dt = world.next_time_step();
  if (dt < 1e-9) {
    std::ostringstream s;
    s << "the time step would be " << dt
      << " s: a second of model time would take more than 1e9 steps. Check the units of the "
         "densities (kg/m^3), block sizes (m) and joint stiffnesses (Pa/m), or set time_step";
    throw ScenarioError(sc.file, "settings.time_step", s.str());
  }
}

namespace {

// The values of every list of `lists`.
std::size_t value_count(const std::vector<std::vector<int>>& lists) {
  std::size_t n = 0;
  for (const auto& l : lists) n += l.size();
  return n;
}

// The faces' laws and joint sets into the world, which holds them in one array each: taken
// lists (one per block, ~110 bytes a block for both in a rock mass) are freed then.
template <class Lists>
void set_face_lists(World& w, Lists& face_laws, Lists& face_sets) {
  for (std::size_t i = 0; i < face_laws.size(); ++i) {
    if (!face_laws[i].empty()) w.set_face_laws(static_cast<int>(i), face_laws[i]);
  }
  for (std::size_t i = 0; i < face_sets.size(); ++i) {
    if (!face_sets[i].empty()) w.set_face_sets(static_cast<int>(i), face_sets[i]);
  }
  if constexpr (!std::is_const_v<Lists>) {
    Lists().swap(face_laws);
    Lists().swap(face_sets);
  }
}

// build_world with the blocks and their faces' laws and joint sets given apart: copied from the
// scenario's (const), or taken (the scenario's are then freed).
template <class Blocks, class Lists>
World build_world_from(const Scenario& sc, Blocks& scenario_blocks, Lists& face_laws,
                       Lists& face_sets) {
  World w(sc.settings);
  for (const auto& law : sc.joint_laws) w.add_joint_law(law);
  for (const auto& r : sc.joint_rules) w.add_joint_rule(r);
  w.reserve_blocks(scenario_blocks.size(), value_count(face_laws), value_count(face_sets));
  for (auto& b : scenario_blocks) {
    if constexpr (std::is_const_v<Blocks>) {
      w.add_block(b);
    } else {
      w.add_block(std::move(b));
    }
  }
  // The world holds the blocks now: their moved-from array (~0.6 KB per block) is freed before
  // the initial-overlap check, whose narrow phase keeps the first step's contact states.
  if constexpr (!std::is_const_v<Blocks>) Blocks().swap(scenario_blocks);
  set_face_lists(w, face_laws, face_sets);
  // Deep initial overlaps are input errors, not something to blow apart. Candidate pairs come
  // from the broad phase (O(N log N)), sorted by (i, j); the narrow phase runs on every thread
  // and the error names the first offending pair in that order, whatever the thread count.
  const auto& blocks = w.blocks();
  std::vector<Eigen::Vector3d> lo(blocks.size()), hi(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    blocks[i].world_box(lo[i], hi[i]);
  }
  // The stress an initial overlap may carry: 100 times the weight of a column of rock as high as
  // the model, at the largest density and gravity of the run (at least 1 g). Closing a deeper
  // overlap would fling the blocks apart (and past a law's own bound its stress is infinite).
  double g_max = std::max(sc.settings.gravity.norm(), kOneG);
  for (const auto& st : sc.stages) {
    if (st.gravity) g_max = std::max(g_max, st.gravity->norm());
  }
  double rho_max = 0.0, z_lo = std::numeric_limits<double>::infinity(), z_hi = -z_lo;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    rho_max = std::max(rho_max, blocks[i].density);
    z_lo = std::min(z_lo, lo[i].z());
    z_hi = std::max(z_hi, hi[i].z());
  }
  const double stress_limit = 100.0 * rho_max * g_max * std::max(z_hi - z_lo, 0.0);
  auto initial_stress = [&](int i, int j, double overlap) {
    const int law = w.law_for(i, j);
    return law < 0 ? 0.0 : normal_stress(w.joint_laws()[law].normal, overlap);
  };
  std::vector<std::pair<int, int>> pairs;
  UniformGrid broad_phase;
  if (!sc.in_situ) {
    broad_phase.find_pairs(
        lo, hi, [](int, int) { return true; }, pairs, w.thread_count());
  } else {
    // Joints that carry the in-situ stress from the start (before the pass below primes the
    // first step's narrow phase, which leaves their pairs to it). Their candidates: the pairs
    // of boxes grown by a nanometre per metre (blocks that share an axis-aligned face may have
    // boxes that miss each other by round-off).
    std::vector<Eigen::Vector3d> lo_grown(lo), hi_grown(hi);
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      const double pad =
          1e-9 * (1.0 + blocks[i].shape.bounding_radius() + lo[i].cwiseAbs().maxCoeff());
      lo_grown[i].array() -= pad;
      hi_grown[i].array() += pad;
    }
    std::vector<std::pair<int, int>> near;
    broad_phase.find_pairs(
        lo_grown, hi_grown, [](int, int) { return true; }, near, w.thread_count());
    std::vector<Eigen::Vector3d>().swap(lo_grown);
    std::vector<Eigen::Vector3d>().swap(hi_grown);
    // The pairs of the boxes as they are, which the grown boxes' pairs hold, in the same (i, j)
    // order: those whose boxes overlap on every axis, touching counts (the broad phase's own
    // test, so the list is the one it would find), without a second broad phase.
    pairs.reserve(near.size());
    for (const auto& [i, j] : near) {
      const Eigen::Vector3d& ilo = lo[static_cast<std::size_t>(i)];
      const Eigen::Vector3d& ihi = hi[static_cast<std::size_t>(i)];
      const Eigen::Vector3d& jlo = lo[static_cast<std::size_t>(j)];
      const Eigen::Vector3d& jhi = hi[static_cast<std::size_t>(j)];
      if (!(jlo.x() > ihi.x() || ilo.x() > jhi.x() || jlo.y() > ihi.y() || ilo.y() > jhi.y() ||
            jlo.z() > ihi.z() || ilo.z() > jhi.z()))
        pairs.push_back({i, j});
    }
    try {
      w.prestress_joints(*sc.in_situ, near);
    } catch (const std::invalid_argument& e) {
      throw ScenarioError(sc.file, "in_situ", e.what());
    }
  }
  const std::int64_t n = static_cast<std::int64_t>(pairs.size());
  std::int64_t first = n;
  const auto check = [&](std::int64_t k, const ContactGeometry& g) {
    const auto [pi, pj] = pairs[static_cast<std::size_t>(k)];
    const Block& a = blocks[static_cast<std::size_t>(pi)];
    const Block& b = blocks[static_cast<std::size_t>(pj)];
    const double size = std::min(a.shape.bounding_radius(), b.shape.bounding_radius());
    if (sc.allow_initial_overlap) return;  // prestressed contacts on purpose
    if (g.touching && (g.overlap > sc.settings.max_overlap_fraction * size ||
                       !(initial_stress(pi, pj, g.overlap) <= stress_limit))) {
#pragma omp critical(blockdem_initial_overlap)
      first = std::min(first, k);
    }
  };
  const auto& distribution = sc.settings.distribution;
  if (distribution && distribution->size() > 1) {
    // Spread over processes, the first step finds only each process's own pairs and solves
    // them cold (the same geometry a primed slot gives), so nothing is primed: each process
    // checks a contiguous share of the pairs, and the first offending pair is the minimum over
    // the processes (exact), the same on every process. No process holds every pair's result.
    if (!sc.allow_initial_overlap) {
      const std::int64_t size = distribution->size(), rank = distribution->rank();
      const std::int64_t begin = n * rank / size, end = n * (rank + 1) / size;
      const int threads = w.thread_count();
#pragma omp parallel for num_threads(threads) schedule(dynamic, 64) if (threads > 1)
      for (std::int64_t k = begin; k < end; ++k) {
        const auto [i, j] = pairs[static_cast<std::size_t>(k)];
        const Block& a = blocks[static_cast<std::size_t>(i)];
        const Block& b = blocks[static_cast<std::size_t>(j)];
        const double extent = 2.0 * (a.shape.bounding_radius() + b.shape.bounding_radius());
        check(k, boon2012_contact(a.world_planes, b.world_planes, extent, sc.settings.boon2012));
      }
      first = static_cast<std::int64_t>(distribution->min({static_cast<double>(first)})[0]);
    }
  } else {
    // The world keeps these results for its first step, which would solve the same pairs again.
    w.prime_narrow_phase(pairs, check);
  }
  if (first < n) {
    const auto [i, j] = pairs[static_cast<std::size_t>(first)];
    const Block& a = blocks[static_cast<std::size_t>(i)];
    const Block& b = blocks[static_cast<std::size_t>(j)];
    const double extent = 2.0 * (a.shape.bounding_radius() + b.shape.bounding_radius());
    const ContactGeometry g =
        boon2012_contact(a.world_planes, b.world_planes, extent, sc.settings.boon2012);
    std::ostringstream s;
    const double stress = initial_stress(i, j, g.overlap);
    s << "blocks \"" << a.name << "\" and \"" << b.name << "\" overlap by " << g.overlap
      << " m at the start";
    if (!(stress <= stress_limit)) {
      s << ": closing it would press the joint at " << stress << " Pa, more than 100 times the "
        << "weight of a rock column as high as the model (" << stress_limit << " Pa)";
    } else {
      s << ", more than " << sc.settings.max_overlap_fraction << " of the smaller block's radius";
    }
    s << ": check their positions and sizes";
    throw ScenarioError(sc.file, "blocks[" + std::to_string(j + 1) + "]", s.str());
  }
  return w;
}

}  // namespace

World build_world(const Scenario& sc) {
  return build_world_from(sc, sc.blocks, sc.face_laws, sc.face_sets);
}

World build_world_taking_blocks(Scenario& sc) {
  std::vector<Block> blocks = std::move(sc.blocks);
  sc.blocks.clear();
  return build_world_from(sc, blocks, sc.face_laws, sc.face_sets);
}

}  // namespace blockdem
