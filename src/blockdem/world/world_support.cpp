// Rock support in the step: bolts installed along their lines, and their loads added to the
// blocks after the contacts' in a fixed order (bolt by bolt), so that every thread count gives
// the same bits.
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "blockdem/world/world.hpp"

namespace blockdem {
namespace {
// The fewest bolts solved on several threads.
constexpr std::int64_t kParallelBolts = 16;
}  // namespace

int World::install_bolt(const BoltSpec& spec) {
  if (settings_.distribution != nullptr)
    throw std::invalid_argument("bolts run on one process: run without mpirun");
  spec.validate();
  // The blocks' planes at their present poses.
  std::vector<BoltSpan> spans = bolt_spans(spec, blocks_);
  const std::string problem = bolt_span_problem(spec, spans, blocks_);
  if (!problem.empty()) throw std::invalid_argument("bolt '" + spec.name + "': " + problem);
  bolts_.push_back(blockdem::install_bolt(spec, std::move(spans), blocks_));
  return static_cast<int>(bolts_.size()) - 1;
}

std::int64_t World::bolt_count(Bolt::State state) const {
  std::int64_t n = 0;
  for (const Bolt& b : bolts_) n += b.state == state ? 1 : 0;
  return n;
}

void World::apply_bolts(const StepScratch& s) {
  // Each bolt is solved from the blocks' poses alone, so the bolts are solved side by side; their
  // loads are then added bolt by bolt, in order, so that a block's loads are summed in the same
  // order for any number of threads. The bolts' stiffnesses join the contacts' in the automatic
  // time step.
  // A bolt's solve takes some microseconds; a handful of bolts is solved on one thread, where
  // waking the others would cost more than it saves.
  const auto n = static_cast<std::int64_t>(bolts_.size());
  bolt_loads_.resize(bolts_.size());
#pragma omp parallel for num_threads(s.threads) \
    schedule(dynamic, 4) if (s.threads > 1 && n >= kParallelBolts)
  for (std::int64_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    bolt_loads(bolts_[i], blocks_, bolt_loads_[i]);
  }
  for (const std::vector<BoltLoad>& loads : bolt_loads_)
    add_bolt_loads(loads, blocks_, stiffness_, rotational_stiffness_);
  double dt_min = contact_dt_ > 0.0 ? contact_dt_ / settings_.safety_factor
                                    : std::numeric_limits<double>::infinity();
  for (const Bolt& bolt : bolts_) {
    if (!bolt.active()) continue;
    for (const BoltSpan& span : bolt.spans) {
      const auto i = static_cast<std::size_t>(span.block);
      const Block& b = blocks_[i];
      if (!b.is_dynamic() || stiffness_[i] <= 0.0) continue;
      dt_min = std::min(dt_min, std::sqrt(b.inertial_mass() / stiffness_[i]));
      if (rotational_stiffness_[i] > 0.0)
        dt_min =
            std::min(dt_min, std::sqrt(b.inertial_moments().minCoeff() / rotational_stiffness_[i]));
    }
  }
  if (std::isfinite(dt_min)) contact_dt_ = settings_.safety_factor * dt_min;
}

void World::renumber_bolts(const std::vector<int>& new_index) {
  for (Bolt& bolt : bolts_) {
    bool lost = false;
    const auto renumber = [&](int& block) {
      block = new_index[static_cast<std::size_t>(block)];
      lost |= block < 0;
    };
    for (BoltSpan& s : bolt.spans) renumber(s.block);
    for (BoltTie& t : bolt.ties) renumber(t.block);
    for (BoltCrossing& c : bolt.crossings) {
      renumber(c.block_a);
      renumber(c.block_b);
    }
    // A bolt tied to an excavated block is gone with it.
    if (lost && bolt.active()) bolt.state = Bolt::State::removed;
  }
}

}  // namespace blockdem
