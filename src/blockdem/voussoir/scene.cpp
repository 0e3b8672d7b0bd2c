// The [voussoir] scene builder: reads and checks the table, builds the beam, and checks that the
// preload can be reached with the joint law.
#include "blockdem/voussoir/scene.hpp"

#include "blockdem/voussoir/recorder.hpp"

#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

namespace blockdem {
namespace {

// The beams the builder makes: up to a thousand blocks (the studies have 6), each length from a
// millimetre to a kilometre (a laboratory beam's are 23-100 mm).
constexpr std::int64_t kMaxBeamBlocks = 1000;
constexpr double kMinBeamLength = 1e-3;  // (m)
constexpr double kMaxBeamLength = 1e3;   // (m)
// And a span of at most 10 km: blocks farther out are not resolved (a 0.05 m deep block 500 km
// from the middle has no volume in double precision).
constexpr double kMaxBeamSpan = 1e4;  // (m)

VoussoirSpec read_voussoir(const CheckedTable& t) {
  VoussoirSpec v;
  const std::string beam = t.choice("beam", "full", {"full", "half"});
  if (beam == "half") {
    v.block_depth = 0.023;
    v.g_levels = {2, 5, 10, 20, 30, 40, 50, 60, 70, 80, 90};
  }
  const std::int64_t blocks = t.integer("blocks", v.blocks);
  if (blocks < 1) t.fail("blocks", "a beam needs at least one block");
  if (blocks > kMaxBeamBlocks)
    t.fail("blocks",
           "must be at most " + std::to_string(kMaxBeamBlocks) + ", got " + std::to_string(blocks));
  v.blocks = static_cast<int>(blocks);
  // Lengths a beam's blocks can be built from: a millimetre to a kilometre.
  const auto length = [&t](const char* key, double fallback) {
    const double x = t.positive(key, fallback);
    if (!(x >= kMinBeamLength && x <= kMaxBeamLength)) {
      std::ostringstream msg;
      msg << "must be between " << kMinBeamLength << " and " << kMaxBeamLength << " m, got " << x;
      t.fail(key, msg.str());
    }
    return x;
  };
  v.block_length = length("block_length", v.block_length);
  v.block_width = length("block_width", v.block_width);
  v.block_depth = length("block_depth", v.block_depth);
  v.abutment_length = length("abutment_length", v.abutment_length);
  v.abutment_height = length("abutment_height", v.abutment_height);
  if (!(v.span() <= kMaxBeamSpan)) {
    std::ostringstream msg;
    msg << "the span blocks x block_length (" << v.span() << " m) must be at most " << kMaxBeamSpan
        << " m";
    t.fail("block_length", msg.str());
  }
  v.density = t.positive("density", v.density);
  v.preload_force = t.positive("preload_force", v.preload_force);
  v.preload_tolerance = t.positive("preload_tolerance", v.preload_tolerance);
  if (t.has("g_levels")) {
    v.g_levels = t.numbers("g_levels");
  }
  if (t.has("g_max") && t.has("g_levels"))
    t.fail("g_max", "give either g_levels or g_max, not both");
  if (t.has("g_max")) {
    // g_max alone: the default levels up to it (and g_max itself).
    const double g_max = t.number("g_max");
    if (!(g_max >= 1.0)) t.fail("g_max", "must be at least 1 (the preload is at 1 g)");
    std::vector<double> kept;
    for (double g : v.g_levels) {
      if (g < g_max) kept.push_back(g);
    }
    kept.push_back(g_max);
    v.g_levels = kept;
  }
  v.servo_side = t.choice("servo_side", v.servo_side, {"both", "left", "right"});
  v.plane_motion = t.boolean("plane_motion", v.plane_motion);
  v.unbalanced_tolerance = t.positive("unbalanced_tolerance", v.unbalanced_tolerance);
  v.kinetic_tolerance = t.positive("kinetic_tolerance", v.kinetic_tolerance);
  v.max_steps_per_level = t.integer("max_steps_per_level", v.max_steps_per_level);
  v.ramp_steps = t.integer("ramp_steps", v.ramp_steps);
  // Step counts beyond 1e12 would take years, and their sum would overflow.
  if (!(v.max_steps_per_level > 0 && v.max_steps_per_level <= 1000000000000))
    t.fail("max_steps_per_level", "must be between 1 and 1e12");
  if (!(v.ramp_steps >= 0 && v.ramp_steps <= 1000000000000))
    t.fail("ramp_steps", "must be between 0 and 1e12");
  v.find_collapse = t.boolean("find_collapse", v.find_collapse);
  v.collapse_tolerance = t.number("collapse_tolerance", v.collapse_tolerance);
  v.law.name = "joint";
  read_joint_law_tables(t, v.law);
  try {
    v.validate();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    const auto colon = what.find(':');
    t.fail(colon == std::string::npos ? "" : what.substr(0, colon),
           colon == std::string::npos ? what : what.substr(colon + 2));
  }
  t.finish();
  return v;
}

}  // namespace

std::unique_ptr<RunObserver> VoussoirScene::observer(const std::filesystem::path& out, const World&,
                                                     bool resumed) const {
  return std::make_unique<VoussoirRecorder>(out, spec, layout, resumed);
}

const VoussoirScene* voussoir_scene(const Scenario& scenario) {
  return dynamic_cast<const VoussoirScene*>(scenario.built.get());
}

void VoussoirSceneBuilder::build(const CheckedTable& t, Scenario& sc) const {
  auto scene = std::make_shared<VoussoirScene>();
  scene->spec = read_voussoir(t);
  VoussoirModel m = build_voussoir(scene->spec);
  // The preload must be reachable: the end-face stress it needs must come at a closure the run
  // accepts (below max_overlap_fraction of a block's radius).
  const VoussoirSpec& v = scene->spec;
  const double needed = v.preload_force / (v.block_width * v.block_depth);
  const double max_closure =
      sc.settings.max_overlap_fraction * m.blocks[m.layout.beam.front()].shape.bounding_radius();
  const double available = normal_stress(v.law.normal, max_closure);
  if (!(needed < available)) {
    std::ostringstream msg;
    msg << "a preload of " << v.preload_force << " N needs a joint stress of " << needed
        << " Pa, which the normal law reaches only beyond the largest closure a run accepts ("
        << max_closure << " m, where it gives " << available
        << " Pa): the preload cannot be reached";
    throw ScenarioError(sc.file, "voussoir.preload_force", msg.str());
  }
  const int law = static_cast<int>(sc.joint_laws.size());
  for (auto& b : m.blocks) sc.blocks.push_back(std::move(b));
  sc.joint_laws.push_back(m.law);
  sc.joint_rules.push_back(JointRule{"", "", law});
  for (auto& s : m.stages) sc.stages.push_back(std::move(s));
  scene->layout = m.layout;
  sc.built = std::move(scene);
}

}  // namespace blockdem
