// The Python module blockdem._core: the C++ engine for the blockdem package (python/blockdem/).
#include <pybind11/pybind11.h>

#include "bindings.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "blockdem engine bindings (use the blockdem package, which wraps them)";
  blockdem::python::bind_scenario(m);
  blockdem::python::bind_simulation(m);
  blockdem::python::bind_studies(m);
}
