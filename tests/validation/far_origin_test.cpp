// Coordinates far from the origin: the same column of blocks at the origin and at map
// coordinates (512000, 6.1e6, 300) m gives the same contacts and forces. Without a scene origin,
// plane offsets of ~6e6 m carry round-off of ~1e-9 m, a thousandth of these joints' closures.
// The VTK frames give the points in the user's coordinates too.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/vtu.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "blockdem/world/stage.hpp"
#include "support/temp_path.hpp"

namespace blockdem::test {
namespace {

// A column of three blocks on a fixed base, a lateral load on the top one (shear in every
// joint), positions given relative to (x0, y0, z0).
std::string column(double x0, double y0, double z0) {
  std::ostringstream s;
  s.precision(17);
  s << "[settings]\ndamping = 0.5\n"
       "[[materials]]\nname = \"rock\"\ndensity = 2600.0\n"
       "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
       "shear = { law = \"linear\", stiffness = 1e9, friction_deg = 40 }\n";
  auto block = [&](const char* name, double z, double size_z, bool fixed, double load) {
    s << "[[blocks]]\nname = \"" << name << "\"\nmaterial = \"rock\"\nsize = [0.5, 0.5, " << size_z
      << "]\nposition = [" << x0 + 0.25 << ", " << y0 - 0.125 << ", " << z0 + z << "]\n";
    if (fixed) s << "motion = \"fixed\"\n";
    if (load != 0.0) s << "external_force = [" << load << ", 0.0, 0.0]\n";
  };
  block("base", -0.125, 0.25, true, 0.0);
  block("b1", 0.125, 0.25, false, 0.0);
  block("b2", 0.375, 0.25, false, 0.0);
  block("b3", 0.625, 0.25, false, 100.0);
  s << "[[stages]]\nname = \"load\"\nkind = \"steps\"\nsteps = 3000\ngravity = [0.0, 0.0, -9.81]\n";
  return s.str();
}

World run_column(double x0, double y0, double z0) {
  const Scenario sc = parse_scenario(column(x0, y0, z0), "column.toml");
  World w = build_world(sc);
  run_stage(w, sc.stages[0]);
  return w;
}

// Oracle: the column at the origin. Tolerance: 1e-9 relative on every contact force, and 2e-9 m
// on the contact points in the user's coordinates (one ulp of 6.1e6 m is 9.3e-10 m).
TEST(FarFromOrigin, MapCoordinatesGiveTheContactsAndForcesOfTheOrigin) {
  const Eigen::Vector3d shift(512000.0, 6.1e6, 300.0);
  const World near = run_column(0.0, 0.0, 0.0);
  const World far = run_column(shift.x(), shift.y(), shift.z());
  const auto cn = near.contacts();
  const auto cf = far.contacts();
  ASSERT_EQ(cn.size(), 3u);
  ASSERT_EQ(cf.size(), cn.size());
  for (std::size_t k = 0; k < cn.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(cf[k]->a, cn[k]->a);
    EXPECT_EQ(cf[k]->b, cn[k]->b);
    const Eigen::Vector3d fn = cn[k]->force_on_b(), ff = cf[k]->force_on_b();
    ASSERT_GT(fn.norm(), 100.0);
    ASSERT_GT(cn[k]->shear.force.norm(), 10.0) << "the joint must carry shear";
    EXPECT_LE((ff - fn).norm(), 1e-9 * fn.norm());
    const Eigen::Vector3d pn = cn[k]->geometry.point + near.settings().origin;
    const Eigen::Vector3d pf = cf[k]->geometry.point + far.settings().origin;
    EXPECT_LE((pf - shift - pn).norm(), 2e-9);
  }
  EXPECT_EQ(near.settings().origin, Eigen::Vector3d::Zero()) << "a scene near 0 is not moved";
}

// The "Points" array of a .vtu file written with raw appended data (UInt64 sizes, Float64 x 3).
std::vector<Eigen::Vector3d> vtu_points(const std::filesystem::path& file) {
  const std::string bytes = read_file_bytes(file);
  const std::size_t name = bytes.find("Name=\"Points\"");
  const std::size_t at = bytes.find("offset=\"", name) + 8;
  const std::uint64_t offset = std::stoull(bytes.substr(at, bytes.find('"', at) - at));
  const std::string marker = "<AppendedData encoding=\"raw\">\n   _";
  const std::size_t data = bytes.find(marker) + marker.size();
  std::uint64_t n = 0;
  std::memcpy(&n, bytes.data() + data + offset, sizeof n);
  std::vector<Eigen::Vector3d> points(n / (3 * sizeof(double)));
  for (std::size_t i = 0; i < points.size(); ++i)
    std::memcpy(points[i].data(), bytes.data() + data + offset + 8 + 24 * i, 24);
  return points;
}

// Oracle: the frames of the column at the origin, shifted. Tolerance: 3e-9 m (about three ulps
// of 6.1e6 m; the two runs' displacements agree far closer).
TEST(FarFromOrigin, VtkFramesGivePointsInTheUsersCoordinates) {
  const Eigen::Vector3d shift(512000.0, 6.1e6, 300.0);
  const World near = run_column(0.0, 0.0, 0.0);
  const World far = run_column(shift.x(), shift.y(), shift.z());
  ASSERT_GT(far.settings().origin.norm(), 1e6) << "the far scene runs relative to its centre";
  const std::filesystem::path dir = temp_path("far_vtu");
  std::filesystem::create_directories(dir);
  for (const char* kind : {"blocks", "contacts"}) {
    SCOPED_TRACE(kind);
    const bool blocks = kind[0] == 'b';
    const auto write = [&](const World& w, const std::filesystem::path& f) {
      if (blocks)
        write_vtu_blocks(f, w, 0);
      else
        write_vtu_contacts(f, w);
    };
    write(near, dir / "near.vtu");
    write(far, dir / "far.vtu");
    const auto pn = vtu_points(dir / "near.vtu");
    const auto pf = vtu_points(dir / "far.vtu");
    ASSERT_EQ(pn.size(), blocks ? 32u : 3u) << "8 vertices per block, 3 contacts";
    ASSERT_EQ(pf.size(), pn.size());
    for (std::size_t i = 0; i < pn.size(); ++i) EXPECT_LE((pf[i] - shift - pn[i]).norm(), 3e-9);
  }
}

}  // namespace
}  // namespace blockdem::test
