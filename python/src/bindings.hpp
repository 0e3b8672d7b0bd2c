// The pieces of the Python module blockdem._core, one function per source file, and the
// exceptions they share.
#pragma once

#include <pybind11/pybind11.h>

namespace blockdem::python {

/// Scenario (load, parse, inspect), run_scenario (a full run with outputs), the exceptions.
void bind_scenario(pybind11::module_& m);
/// Simulation: a world built from a scenario, stepped stage by stage with callbacks.
void bind_simulation(pybind11::module_& m);
struct Simulation;
/// The state of a simulation as NumPy arrays (blocks, contacts), added to its class.
void bind_state(pybind11::class_<Simulation>& cls);
/// Simulation.save and Simulation.load, added to its class.
void bind_save(pybind11::class_<Simulation>& cls);
/// The study commands: analytic voussoir, lab tests, calibration, the boon2015 reproduction.
void bind_studies(pybind11::module_& m);

}  // namespace blockdem::python
