// Reading an in-situ stress field and stress tensors from a scenario file.
#include "blockdem/scenario/in_situ_input.hpp"

#include <cmath>
#include <map>

namespace blockdem {

Eigen::Matrix3d read_stress_tensor(const CheckedTable& parent, const std::string& key) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  if (parent.is_table(key)) {
    const CheckedTable t = parent.table(key);
    const char* names[6] = {"xx", "yy", "zz", "xy", "yz", "xz"};
    const int rows[6] = {0, 1, 2, 0, 1, 0}, cols[6] = {0, 1, 2, 1, 2, 2};
    for (int k = 0; k < 6; ++k) {
      const double v = t.number(names[k], 0.0);
      if (!std::isfinite(v)) t.fail(names[k], "must be a finite stress (Pa)");
      m(rows[k], cols[k]) = m(cols[k], rows[k]) = v;
    }
    t.finish();
    return m;
  }
  const auto r = parent.rows(key, 3);
  if (r.size() != 3)
    parent.fail(key, "must be a table { xx, yy, zz, xy, yz, xz } or three rows of three numbers");
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      m(i, j) = r[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  }
  if (!m.allFinite()) parent.fail(key, "must hold finite stresses (Pa)");
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      if (!(std::abs(m(i, j) - m(j, i)) <= 1e-12 * m.cwiseAbs().maxCoeff()))
        parent.fail(key, "is not symmetric: row " + std::to_string(i + 1) + " column " +
                             std::to_string(j + 1) + " differs from row " + std::to_string(j + 1) +
                             " column " + std::to_string(i + 1));
    }
  }
  return m;
}

StressField read_in_situ(const CheckedTable& t, const Eigen::Vector3d& gravity,
                         const std::map<std::string, double>& materials) {
  const bool full = t.has("stress");
  const bool shorthand = t.has("ground_z");
  if (full == shorthand)
    t.fail(full ? "ground_z" : "stress",
           "give either stress (with reference_z and gradient_z) or the shorthand ground_z, "
           "density, k_x, k_y and trend_deg");
  StressField f;
  if (full) {
    f.stress = read_stress_tensor(t, "stress");
    f.reference_z = t.number("reference_z", 0.0);
    if (!std::isfinite(f.reference_z)) t.fail("reference_z", "must be finite (m)");
    if (t.has("gradient_z")) f.gradient_z = read_stress_tensor(t, "gradient_z");
    t.finish();
    return f;
  }
  const double ground_z = t.number("ground_z");
  if (!std::isfinite(ground_z)) t.fail("ground_z", "must be finite (m)");
  double density = 0.0;
  if (t.has("material")) {
    if (t.has("density")) t.fail("density", "give either material or density, not both");
    const std::string name = t.string("material");
    const auto it = materials.find(name);
    if (it == materials.end())
      t.fail("material", "no material named \"" + name + "\" in [[materials]]");
    density = it->second;
  } else {
    if (!t.has("density")) t.fail("density", "is required (kg/m^3), or name a material");
    density = t.positive("density", 0.0);
  }
  const double k_x = t.positive("k_x", 1.0, true);
  const double k_y = t.positive("k_y", 1.0, true);
  const double trend = t.number("trend_deg", 0.0);
  if (!(std::abs(trend) <= 360.0)) t.fail("trend_deg", "must be an angle in [-360, 360] degrees");
  const double g = gravity.norm();
  if (!(g > 0.0))
    t.fail("ground_z",
           "the shorthand weighs the rock above: it needs gravity ([settings] gravity)");
  t.finish();
  return stress_from_overburden(ground_z, density, g, k_x, k_y, trend);
}

}  // namespace blockdem
