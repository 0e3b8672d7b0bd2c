// Rock support in the step: bolts installed along their lines, and their loads added to the
// blocks after the contacts' in a fixed order (bolt by bolt), so that every thread count gives
// the same bits.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "blockdem/world/world.hpp"

namespace blockdem {

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

void World::apply_bolts() {
  // Serial and in bolt order: a bolt's loads on a block are summed in the same order for any
  // number of threads. The bolts' stiffnesses join the contacts' in the automatic time step.
  for (Bolt& bolt : bolts_) apply_bolt(bolt, blocks_, stiffness_, rotational_stiffness_);
  double dt_min = contact_dt_ > 0.0 ? contact_dt_ / settings_.safety_factor
                                    : std::numeric_limits<double>::infinity();
  for (const Bolt& bolt : bolts_) {
    if (!bolt.active()) continue;
    for (const BoltSpan& s : bolt.spans) {
      const auto i = static_cast<std::size_t>(s.block);
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
