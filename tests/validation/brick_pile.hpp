// A 3D running-bond pile of cubes on a fixed base plate, as a world built in code and as a
// scenario file (the layout of bench/make_pile.py), for the determinism tests.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include "scenes.hpp"
#include "support/sanitized_run.hpp"

namespace blockdem::test {

/// The pile: `layers` layers of cubes of edge `size` (m); even layers n x n cubes, odd layers
/// (n-1) x (n-1) shifted by half a cube in x and y, each resting on four below. Layers are
/// pre-closed by `preclose` (m), side faces touch exactly. Every free block starts with a small
/// velocity of its own (m/s), so that pairs open, close and slide.
struct BrickPile {
  int n = 10;
  int layers = 4;
  double size = 0.046;      ///< (m)
  double density = 1207.0;  ///< (kg/m^3)
  double preclose = 5e-8;   ///< (m)
  double kick = 0.05;       ///< amplitude of the initial velocities (m/s)

  /// Settings under which the pile slides on its base, so that blocks cross the boundaries of
  /// a distributed world's parts: gravity tilted to about 10 g, mode boon2012, one thread.
  static WorldSettings sliding_settings() {
    WorldSettings s;
    s.gravity = Eigen::Vector3d(60.0, 25.0, -98.1);
    s.contact_mode = ContactMode::boon2012;
    s.threads = 1;
    return s;
  }

  int block_count() const {
    int c = 1;
    for (int l = 0; l < layers; ++l) c += (l % 2 == 0 ? n * n : (n - 1) * (n - 1));
    return c;
  }

  /// Calls f(name, centre, velocity) for every cube, then the base plate is separate.
  template <class F>
  void for_each_cube(F&& f) const {
    int k = 0;
    for (int l = 0; l < layers; ++l) {
      const int m = l % 2 == 0 ? n : n - 1;
      const double shift = l % 2 == 0 ? 0.0 : 0.5 * size;
      const double z = (l + 0.5) * size - (l + 1) * preclose;
      for (int i = 0; i < m; ++i) {
        for (int j = 0; j < m; ++j, ++k) {
          const Eigen::Vector3d c(shift + (i + 0.5) * size, shift + (j + 0.5) * size, z);
          // A fixed pseudo-random velocity per cube (no library generator: the same everywhere).
          const Eigen::Vector3d v(kick * std::sin(1.3 * k + 0.2), kick * std::sin(2.1 * k + 1.1),
                                  0.5 * kick * std::sin(0.7 * k + 2.3));
          std::string name = "c";
          name += std::to_string(k);
          f(name, c, v);
        }
      }
    }
  }
  Eigen::Vector3d base_size() const { return {(n + 2) * size, (n + 2) * size, size}; }
  Eigen::Vector3d base_centre() const { return {0.5 * n * size, 0.5 * n * size, -0.5 * size}; }

  /// The world: linear joints k_n = 10 GPa/m, k_s = 1 GPa/m, φ = `friction_deg`.
  World world(const WorldSettings& settings, double friction_deg) const {
    World w = linear_world(10e9, 1e9, friction_deg, settings);
    w.add_block(box_block(base_size(), base_centre(), density, Motion::fixed, "base"));
    for_each_cube([&](const std::string& name, const Eigen::Vector3d& c, const Eigen::Vector3d& v) {
      Block b = box_block(Eigen::Vector3d::Constant(size), c, density, Motion::free, name);
      b.velocity = v;
      w.add_block(b);
    });
    return w;
  }

  /// The same pile as a scenario file.
  std::string toml(const std::string& contact_mode, double friction_deg,
                   const Eigen::Vector3d& gravity, int steps) const {
    std::ostringstream s;
    s.precision(17);
    s << "title = \"brick pile\"\n[settings]\ndamping = 0.0\ncontact_mode = \"" << contact_mode
      << "\"\ngravity = [" << gravity.x() << ", " << gravity.y() << ", " << gravity.z() << "]\n"
      << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 10e9 }\n"
      << "shear = { law = \"linear\", stiffness = 1e9, friction_deg = " << friction_deg << " }\n";
    auto block = [&](const std::string& name, const Eigen::Vector3d& sz, const Eigen::Vector3d& c,
                     const char* motion, const Eigen::Vector3d& v) {
      s << "[[blocks]]\nname = \"" << name << "\"\ndensity = " << density << "\nsize = [" << sz.x()
        << ", " << sz.y() << ", " << sz.z() << "]\nposition = [" << c.x() << ", " << c.y() << ", "
        << c.z() << "]\nmotion = \"" << motion << "\"\n";
      if (v != Eigen::Vector3d::Zero())
        s << "velocity = [" << v.x() << ", " << v.y() << ", " << v.z() << "]\n";
    };
    block("base", base_size(), base_centre(), "fixed", Eigen::Vector3d::Zero());
    for_each_cube([&](const std::string& name, const Eigen::Vector3d& c, const Eigen::Vector3d& v) {
      block(name, Eigen::Vector3d::Constant(size), c, "free", v);
    });
    s << "[[stages]]\nname = \"shake\"\nkind = \"steps\"\nsteps = " << steps << "\n";
    s << "[[stages]]\nname = \"more\"\nkind = \"steps\"\nsteps = " << steps << "\n";
    return s.str();
  }
};

/// The pile of the tests that spread a world over parts in threads: under the sanitizers, where
/// a step is 20 to 40 times slower, 3 layers of 6 x 6, 5 x 5 and 6 x 6 cubes (97 cubes)
/// instead of 4 layers of 10 x 10 and 9 x 9 (362 cubes): the same passes, exchanges and checks on
/// fewer blocks, and the same assertions.
inline BrickPile distributed_test_pile() {
  BrickPile pile;
  if (sanitized_run()) {
    pile.n = 6;
    pile.layers = 3;
  }
  return pile;
}

}  // namespace blockdem::test
