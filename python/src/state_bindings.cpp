// The state of a Simulation as NumPy arrays. Every array is a fresh copy: the world keeps its
// blocks as an array of structures (a block's position sits beside its shape and loads), and
// blocks move in memory when an excavation removes some, so a view could outlive its data.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <functional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "simulation.hpp"

namespace py = pybind11;

namespace blockdem::python {
namespace {

/// An (n, width) array of doubles filled row by row by `fill(i, row)`.
py::array_t<double> table(std::size_t n, std::size_t width,
                          const std::function<void(std::size_t, double*)>& fill) {
  py::array_t<double> a({n, width});
  auto* data = a.mutable_data();
  for (std::size_t i = 0; i < n; ++i) fill(i, data + i * width);
  return a;
}

py::array_t<double> block_vectors(const Simulation& s,
                                  const std::function<Eigen::Vector3d(const Block&)>& get) {
  const auto& blocks = s.world.blocks();
  return table(blocks.size(), 3, [&](std::size_t i, double* row) {
    const Eigen::Vector3d v = get(blocks[i]);
    row[0] = v.x();
    row[1] = v.y();
    row[2] = v.z();
  });
}

void put3(double* row, const Eigen::Vector3d& v) {
  row[0] = v.x();
  row[1] = v.y();
  row[2] = v.z();
}

}  // namespace

void bind_state(py::class_<Simulation>& sim) {
  sim.def_property_readonly(
         "block_names",
         [](const Simulation& s) {
           std::vector<std::string> names;
           for (const auto& b : s.world.blocks()) names.push_back(b.name);
           return names;
         },
         "block names, in index order (a list)")
      .def_property_readonly(
          "positions",
          [](const Simulation& s) {
            return block_vectors(s, [](const Block& b) { return b.position; });
          },
          "(n, 3) centroids (m), a copy")
      .def_property_readonly(
          "displacements",
          [](const Simulation& s) {
            return block_vectors(
                s, [](const Block& b) { return Eigen::Vector3d(b.position - b.initial_position); });
          },
          "(n, 3) centroid displacements since the world was built (m), a copy")
      .def_property_readonly(
          "orientations",
          [](const Simulation& s) {
            const auto& blocks = s.world.blocks();
            return table(blocks.size(), 4, [&](std::size_t i, double* row) {
              const Eigen::Quaterniond& q = blocks[i].orientation;
              row[0] = q.w();
              row[1] = q.x();
              row[2] = q.y();
              row[3] = q.z();
            });
          },
          "(n, 4) unit quaternions (w, x, y, z), body frame to world frame, a copy")
      .def_property_readonly(
          "rotations",
          [](const Simulation& s) {
            return block_vectors(s, [](const Block& b) { return b.rotation_since_start(); });
          },
          "(n, 3) rotation vectors since the world was built (rad, axis times angle), a copy")
      .def_property_readonly(
          "velocities",
          [](const Simulation& s) {
            return block_vectors(s, [](const Block& b) { return b.velocity; });
          },
          "(n, 3) velocities at the last half step (m/s), a copy")
      .def_property_readonly(
          "angular_velocities",
          [](const Simulation& s) {
            return block_vectors(s, [](const Block& b) { return b.angular_velocity; });
          },
          "(n, 3) angular velocities at the last half step, world frame (rad/s), a copy")
      .def_property_readonly(
          "contact_forces",
          [](const Simulation& s) {
            return block_vectors(s, [](const Block& b) { return b.contact_force; });
          },
          "(n, 3) sum of the contact forces on each block at the last step (N), a copy")
      .def_property_readonly(
          "masses",
          [](const Simulation& s) {
            const auto& blocks = s.world.blocks();
            py::array_t<double> a(static_cast<py::ssize_t>(blocks.size()));
            for (std::size_t i = 0; i < blocks.size(); ++i) a.mutable_at(i) = blocks[i].mass;
            return a;
          },
          "(n,) masses (kg), a copy")
      .def(
          "contacts",
          [](const Simulation& s) {
            const std::vector<const Contact*> cs = s.world.contacts();
            const std::size_t n = cs.size();
            py::array_t<std::int64_t> ab({n, std::size_t{2}});
            py::array_t<double> point({n, std::size_t{3}}), normal({n, std::size_t{3}}),
                shear({n, std::size_t{3}});
            py::array_t<double> fn(static_cast<py::ssize_t>(n)),
                closure(static_cast<py::ssize_t>(n)), area(static_cast<py::ssize_t>(n)),
                stress(static_cast<py::ssize_t>(n));
            py::array_t<std::int8_t> sliding(static_cast<py::ssize_t>(n)),
                broken(static_cast<py::ssize_t>(n));
            for (std::size_t i = 0; i < n; ++i) {
              const Contact& c = *cs[i];
              ab.mutable_at(i, 0) = c.a;
              ab.mutable_at(i, 1) = c.b;
              put3(point.mutable_data(i, 0), c.force_point());
              put3(normal.mutable_data(i, 0), c.geometry.normal);
              put3(shear.mutable_data(i, 0), c.shear.force);
              fn.mutable_at(i) = c.normal_force;
              closure.mutable_at(i) = c.geometry.overlap;
              area.mutable_at(i) = c.compressed_area();
              stress.mutable_at(i) = c.normal_stress;
              sliding.mutable_at(i) = c.sliding ? 1 : 0;
              broken.mutable_at(i) = c.shear.broken() ? 1 : 0;
            }
            py::dict d;
            d["blocks"] = ab;
            d["point"] = point;
            d["normal"] = normal;
            d["normal_force"] = fn;
            d["shear_force"] = shear;
            d["closure"] = closure;
            d["area"] = area;
            d["normal_stress"] = stress;
            d["sliding"] = sliding;
            d["broken"] = broken;
            return d;
          },
          "The current contacts, sorted by (a, b), as a dict of fresh arrays (m contacts): "
          "blocks (m, 2) indices a < b; point (m, 3) where the force acts (m); normal (m, 3) "
          "unit, from a to b; normal_force (m,) (N, compression positive, on b along +normal); "
          "shear_force (m, 3) on b (N); closure (m,) overlap along the normal (m); area (m,) "
          "compressed area (m^2); normal_stress (m,) (Pa); sliding (m,) 1 when the shear law "
          "yielded this step; broken (m,) 1 once the bond broke.");
}

}  // namespace blockdem::python
