// The step: one pipeline of passes for every way of running. A one-process world runs each pass
// over all its blocks and pairs; a distributed world (settings().distribution) runs the same
// passes over the blocks exact on this process and the pairs it owns, with its exchanges and
// exact reductions between them (the world's Decomposition, world/decomposition_step.cpp). Either
// way each block and contact ends the step with the same bits.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "blockdem/dynamics/integrator.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

void World::step() {
  if (!checkpoint_.valid) {
    synchronize();
    save_checkpoint();
  }
  StepScratch s;
  s.dt = next_time_step();
  s.threads = thread_count();
  s.distributed = settings_.distribution != nullptr;
  // 0. A distributed step: its partition, and the blocks exact on this process.
  if (s.distributed) decomposition_.begin_step(*this, s);
  // 1. World planes, boxes and the loads that do not come from contacts (parallel per block).
  refresh_blocks(s);
  // 2-5. Contacts: broad phase, per-pair work in parallel, loads scattered in a fixed order.
  // A law or the narrow phase that refuses a value here (a stress that overflowed, a moment
  // below zero) met a state the divergence checks had not caught yet, or a defect: not bad
  // input, which was checked before the first step. The run is reset as after a blow-up (a
  // distributed step agrees on a failure with the other processes first: evaluate_step_pairs).
  if (s.distributed) {
    contact_passes(s);
  } else {
    try {
      contact_passes(s);
    } catch (const std::invalid_argument& e) {
      fail_step(e.what());
    }
  }
  // 5b. Bolts: their loads after the contacts', bolt by bolt (one process only).
  if (!bolts_.empty()) apply_bolts(s);
  // 6. Servos, then integration with each block's terms of the energy budget (parallel per
  // block).
  apply_servos(s.dt, s.distributed ? &decomposition_.own() : nullptr);
  integrate_blocks(s);
  time_ += s.dt;
  ++step_count_;
  last_dt_ = s.dt;
  // 7. The checks: a diverged block, a too-deep overlap (reset to the checkpoint and throw).
  check_step(s);
  // 8. The divergence checkpoint, then (distributed) a rebalance of the processes' work.
  if (step_count_ % 200 == 0) keep_divergence_checkpoint();
  if (s.distributed) decomposition_.end_step(*this, s);
}

void World::refresh_blocks(StepScratch& s) {
  if (!s.distributed) {
    update_geometry(s.threads);
    return;
  }
  // The exact blocks only, listed in index order: the step's broad phase and its per-block
  // loops cover them alone, not the whole world.
  const std::size_t n = blocks_.size();
  const auto n_held = static_cast<std::int64_t>(s.held.size());
  box_min_.resize(n);
  box_max_.resize(n);
  s.held_min.resize(s.held.size());
  s.held_max.resize(s.held.size());
  s.moves.assign(n, 0);  // per exact block: is_dynamic(), read per pair
#pragma omp parallel for num_threads(s.threads) schedule(static) if (s.threads > 1 && n_held > 1024)
  for (std::int64_t k = 0; k < n_held; ++k) {
    const auto i = static_cast<std::size_t>(s.held[static_cast<std::size_t>(k)]);
    refresh_block(i);
    s.held_min[static_cast<std::size_t>(k)] = box_min_[i];
    s.held_max[static_cast<std::size_t>(k)] = box_max_[i];
    s.moves[i] = blocks_[i].is_dynamic() ? 1 : 0;
  }
}

void World::contact_passes(StepScratch& s) {
  find_step_pairs(s);
  evaluate_step_pairs(s);
  scatter_step_loads(s);
}

void World::evaluate_step_pairs(StepScratch& s) {
  if (!s.distributed) {
    evaluate_pairs(s.dt, true, s.threads);
    drop_primed();
    return;
  }
  // This process's pairs (in parallel over its threads; each writes only its own slot). The
  // new contact states wait in pending_ (in slot order per run) for one settle_contacts, after
  // the slots received from the other processes have joined them.
  decomposition_.select_own_pairs(*this, s);
  const auto t0 = std::chrono::steady_clock::now();
  const std::exception_ptr error = evaluate_slots(s.dt, true, s.threads, &s.is_mine);
  s.pair_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  decomposition_.exchange_evaluated_slots(*this, s, error);
}

void World::scatter_step_loads(StepScratch& s) {
  if (!s.distributed) {
    // Every slot and block: the counts, the energy terms and the time-step minimum with them.
    scatter_loads();
    return;
  }
  // Every slot of an own block is exact here, so its sums are the serial ones. scatter_loads
  // counts, of this process's pairs only, the contacts' energy terms, the active contacts and
  // broken bonds, and finds the first too-deep overlap among them (the blocks' copies of their
  // shapes' radii, refreshed with their planes this step); it sums the loads of the own and
  // resting blocks only. The time-step minimum counts the own blocks only.
  s.broken_before = broken_bonds_;
  scatter_loads(&s.is_mine);
  s.active = static_cast<std::int64_t>(active_count_);
  s.broke = broken_bonds_ - s.broken_before;
  if (overlap_violation_ >= 0) {
    const PairSlot& slot = slots_[static_cast<std::size_t>(overlap_violation_)];
    s.overlap_key = static_cast<double>(slot.a) * static_cast<double>(blocks_.size()) + slot.b;
  }
  for (const int h : decomposition_.own_list()) {
    const auto i = static_cast<std::size_t>(h);
    if (stiffness_[i] <= 0.0 || s.moves[i] == 0) continue;
    const Block& bl = blocks_[i];
    s.dt_min = std::min(s.dt_min, std::sqrt(bl.inertial_mass() / stiffness_[i]));
    s.dt_min =
        std::min(s.dt_min, std::sqrt(bl.inertial_moments().minCoeff() / rotational_stiffness_[i]));
  }
}

void World::integrate_blocks(StepScratch& s) {
  // The blocks this process integrates: all of them, or (distributed) its own. The ledger keeps
  // the records of those only: another process keeps the others' (a refresh sets them here from
  // their owners).
  const std::vector<int>* own = s.distributed ? &decomposition_.own_list() : nullptr;
  if (own != nullptr) {
    energy_.before_integration(blocks_, *own);
  } else {
    energy_.before_integration(blocks_);
  }
  energy_.prepare(blocks_.size());
  // With each block, its terms of the energy budget at the level whose forces this step used:
  // exact sums, the same bits for any split over threads and processes (the contacts' terms
  // were summed by scatter_loads).
  EnergyStepSums sums = std::move(contact_energy_);
  contact_energy_ = EnergyStepSums{};
  const std::int64_t n = static_cast<std::int64_t>(own != nullptr ? own->size() : blocks_.size());
  const Eigen::Vector3d gravity = settings_.gravity;
  const double damping = settings_.damping;
  const double dt = s.dt;
  const auto advance = [&](std::int64_t k, EnergyStepSums& into) {
    const auto i = own != nullptr ? static_cast<std::size_t>((*own)[static_cast<std::size_t>(k)])
                                  : static_cast<std::size_t>(k);
    integrate_block(blocks_[i], dt, damping);
    into.add_block(energy_.block_terms(i, blocks_[i], gravity, damping, dt));
  };
  if (s.threads <= 1 || n <= 256) {
    // One thread: the terms go straight into the step's sums (exact: the same bits as the
    // parallel split's, without a part per thread and its normalising +=).
    for (std::int64_t k = 0; k < n; ++k) advance(k, sums);
  } else {
#pragma omp parallel num_threads(s.threads)
    {
      EnergyStepSums part;
#pragma omp for schedule(static) nowait
      for (std::int64_t k = 0; k < n; ++k) advance(k, part);
#pragma omp critical(blockdem_energy_sums)
      sums += part;
    }
  }
  energy_.add_step(s.distributed ? decomposition_.reduce_energy(*this, s, sums) : sums);
}

void World::check_step(StepScratch& s) {
  if (!s.distributed) {
    check_divergence();
    return;
  }
  // Ghosts for the next step, then the global checks as exact reductions; a failed check makes
  // the whole world on every process and runs the one-process check (which restores the last
  // checkpoint and throws, alike everywhere).
  if (decomposition_.reduce_step_checks(*this, s)) {
    synchronize();
    check_divergence();
  }
}

void World::keep_divergence_checkpoint() {
  // A distributed step keeps it in parts when the caller defers the refresh (gathered by the next
  // synchronize(), before anything reads it); otherwise from the whole world.
  if (settings_.distribution && decomposition_.deferred_replica()) {
    decomposition_.save_checkpoint_part(*this);
    return;
  }
  synchronize();
  save_checkpoint();
}

}  // namespace blockdem
