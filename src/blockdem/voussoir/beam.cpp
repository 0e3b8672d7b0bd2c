// Voussoir beam geometry and loading sequence.
#include "blockdem/voussoir/beam.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "blockdem/numerics/number_text.hpp"
#include "blockdem/world/stability.hpp"

namespace blockdem {

void VoussoirSpec::validate() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (blocks < 1) fail("blocks: a beam needs at least one block, got " + std::to_string(blocks));
  auto positive = [&](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v))
      fail(std::string(name) + ": must be positive, got " + number_text(v));
  };
  positive(block_length, "block_length");
  positive(block_width, "block_width");
  positive(block_depth, "block_depth");
  positive(abutment_length, "abutment_length");
  positive(abutment_height, "abutment_height");
  positive(density, "density");
  positive(preload_force, "preload_force");
  positive(preload_tolerance, "preload_tolerance");
  positive(unbalanced_tolerance, "unbalanced_tolerance");
  positive(kinetic_tolerance, "kinetic_tolerance");
  if (abutment_height < block_depth) {
    fail("abutment_height: must be at least the beam depth (" + number_text(block_depth) +
         " m) so the abutments cover the beam's end faces");
  }
  if (g_levels.empty()) fail("g_levels: at least one gravity level after the preload is needed");
  double previous = 1.0;
  for (double g : g_levels) {
    if (!(g >= 1.0) || !std::isfinite(g))
      fail("g_levels: every level must be at least 1 g, got " + number_text(g));
    if (g < previous) fail("g_levels: levels must not decrease");
    previous = g;
  }
  if (servo_side != "left" && servo_side != "right" && servo_side != "both") {
    fail("servo_side: must be \"both\", \"left\" or \"right\"");
  }
  if (max_steps_per_level <= 0) fail("max_steps_per_level: must be positive");
  if (ramp_steps < 0) fail("ramp_steps: must be zero or positive");
  if (!(collapse_tolerance > 0.0)) fail("collapse_tolerance: must be positive (g)");
  // The search brackets a level up to the highest: a width doubles cannot resolve there would
  // repeat the same trial.
  const double narrowest = kNarrowestRelativeBracket * g_levels.back();
  if (collapse_tolerance < narrowest)
    fail("collapse_tolerance: must be at least " + number_text(narrowest) +
         " g (1e-12 of the highest level: a narrower bracket is below the resolution of the "
         "search), got " +
         number_text(collapse_tolerance));
}

VoussoirModel build_voussoir(const VoussoirSpec& spec) {
  spec.validate();
  VoussoirModel m;
  m.law = spec.law;
  const double s = spec.span();
  const double t = spec.block_depth;
  const double w = spec.block_width;
  auto box = [](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    return Polyhedron::box(hi - lo).transformed(Eigen::Matrix3d::Identity(), 0.5 * (lo + hi));
  };
  // Abutments: fixed, tops flush with the beam top, covering the end faces and reaching below.
  const double ha = spec.abutment_height;
  Block left = make_block(box({-spec.abutment_length, -w / 2, -ha}, {0, w / 2, 0}), spec.density,
                          "abutment_left", "abutment");
  Block right = make_block(box({s, -w / 2, -ha}, {s + spec.abutment_length, w / 2, 0}),
                           spec.density, "abutment_right", "abutment");
  left.motion = Motion::fixed;
  right.motion = Motion::fixed;
  auto make_servo = [&](Block& b, double direction) {
    b.motion = Motion::servo;
    b.edit_servo().axis = Eigen::Vector3d(direction, 0.0, 0.0);
    b.edit_servo().target_force = spec.preload_force;
    b.edit_servo().tolerance = spec.preload_tolerance;
  };
  if (spec.servo_side != "right") make_servo(left, 1.0);
  if (spec.servo_side != "left") make_servo(right, -1.0);
  m.blocks.push_back(left);
  m.blocks.push_back(right);
  m.layout.left_abutment = 0;
  m.layout.right_abutment = 1;
  for (int i = 0; i < spec.blocks; ++i) {
    const double x0 = i * spec.block_length;
    char name[32];
    std::snprintf(name, sizeof name, "block_%d", i + 1);
    Block b = make_block(box({x0, -w / 2, -t}, {x0 + spec.block_length, w / 2, 0}), spec.density,
                         name, "beam");
    if (spec.plane_motion) {
      b.blocked_translation = {false, true, false};
      b.blocked_rotation = {true, false, true};
    }
    m.blocks.push_back(std::move(b));
    m.layout.beam.push_back(i + 2);
  }

  // Stages: the preload at 1 g, then the gravity levels.
  Stage pre;
  pre.name = "preload";
  pre.gravity = Eigen::Vector3d(0, 0, -kOneG);
  pre.hold_servos_after = true;
  pre.unbalanced_tolerance = spec.unbalanced_tolerance;
  pre.kinetic_tolerance = spec.kinetic_tolerance;
  pre.max_steps = spec.max_steps_per_level;
  m.stages.push_back(pre);
  for (double g : spec.g_levels) {
    Stage st = pre;
    st.hold_servos_after = false;
    char name[32];
    std::snprintf(name, sizeof name, "%gg", g);
    st.name = name;
    st.gravity = Eigen::Vector3d(0, 0, -g * kOneG);
    st.ramp_steps = spec.ramp_steps;
    st.max_steps = spec.max_steps_per_level + spec.ramp_steps;
    // A beam that snaps through stops at once (its blocks pass half their size) instead of
    // falling until a divergence check trips.
    st.stop_on_mechanism = true;
    st.find_collapse = spec.find_collapse;
    st.collapse_tolerance = spec.collapse_tolerance;
    m.stages.push_back(st);
  }
  return m;
}

}  // namespace blockdem
