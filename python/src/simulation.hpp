// A world built from a scenario, with the index of the next stage: what blockdem.Simulation wraps.
#pragma once

#include <pybind11/pybind11.h>
#include <cstdint>

#include <memory>
#include <utility>

#include "blockdem/scenario/scenario.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem::python {

struct Simulation {
  explicit Simulation(std::shared_ptr<const Scenario> sc)
      : scenario(std::move(sc)), world(build_world(*scenario)) {
    check_time_step(*scenario, world);
  }
  std::shared_ptr<const Scenario> scenario;
  World world;
  int next_stage = 0;  ///< the stage run_stage() runs when given none
};

/// The index of a block given by name or index; throws IndexError / KeyError.
int block_index(const World& world, const pybind11::handle& block);

}  // namespace blockdem::python
