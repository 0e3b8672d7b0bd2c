// A world built from a scenario, with the index of the next stage: what blockdem.Simulation wraps.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <thread>
#include <utility>

#include "blockdem/scenario/scenario.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem::python {

/// The scenarios that simulations were built from (Simulation::scenario): a setting changed on
/// one would not reach its world, so its setters refuse (an error, not a change ignored).
inline std::set<const Scenario*>& built_scenarios() {
  static std::set<const Scenario*> built;
  return built;
}

struct Simulation {
  explicit Simulation(std::shared_ptr<const Scenario> sc)
      : scenario(std::move(sc)), world(build_world(*scenario)) {
    check_time_step(*scenario, world);
    built_scenarios().insert(scenario.get());
  }
  ~Simulation() { built_scenarios().erase(scenario.get()); }
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;
  std::shared_ptr<const Scenario> scenario;
  World world;
  int next_stage = 0;  ///< the stage run_stage() runs when given none
  /// The thread stepping the world (run_stage, step), if any. The steps hold Python's lock, so
  /// another thread reaches the simulation only while a callback runs, between two steps.
  std::optional<std::thread::id> runner;
};

/// Marks a simulation as stepped by this thread for the guard's life; throws RuntimeError when
/// another thread is stepping it (the same thread may step again from a callback).
class Running {
 public:
  explicit Running(Simulation& s) : s_(s), outer_(!s.runner) {
    if (s.runner && *s.runner != std::this_thread::get_id())
      throw std::runtime_error(
          "this Simulation is being run by another thread: step one simulation from one thread "
          "(run independent simulations in processes)");
    s.runner = std::this_thread::get_id();
  }
  ~Running() {
    if (outer_) s_.runner.reset();
  }
  Running(const Running&) = delete;
  Running& operator=(const Running&) = delete;

 private:
  Simulation& s_;
  bool outer_;
};

/// The index of a block given by name or index; throws IndexError / KeyError.
int block_index(const World& world, const pybind11::handle& block);

}  // namespace blockdem::python
