// Voussoir-beam measurements.
#include "blockdem/voussoir/measures.hpp"

#include <cmath>
#include <limits>
#include <map>

namespace blockdem {

VoussoirReference capture_reference(const World& world) {
  VoussoirReference r;
  for (const auto& b : world.blocks()) {
    r.positions.push_back(b.position);
    r.orientations.push_back(b.orientation);
  }
  return r;
}

namespace {

// Displacement since the reference of the material point at world position x_ref (reference).
Eigen::Vector3d point_displacement(const Block& b, const VoussoirReference& ref,
                                   const Eigen::Vector3d& x_ref) {
  const Eigen::Vector3d body =
      ref.orientations[b.index].conjugate() * (x_ref - ref.positions[b.index]);
  return b.to_world(body) - x_ref;
}

}  // namespace

VoussoirLevel measure_voussoir(const World& world, const VoussoirSpec& spec,
                               const VoussoirLayout& layout, const VoussoirReference& ref,
                               double g_level) {
  VoussoirLevel lv;
  lv.g_level = g_level;
  const auto& blocks = world.blocks();
  const double s = spec.span();
  const double t = spec.block_depth;

  // Abutment reactions: the contact force each abutment receives, along x.
  const double right_x = blocks[layout.right_abutment].contact_force.x();
  const double left_x = -blocks[layout.left_abutment].contact_force.x();
  if (spec.servo_side == "both") {
    lv.thrust = 0.5 * (right_x + left_x);
    lv.thrust_left = left_x;
  } else {
    const bool servo_right = spec.servo_side == "right";
    lv.thrust = servo_right ? right_x : left_x;
    lv.thrust_left = servo_right ? left_x : right_x;
  }

  // Joints, left to right.
  std::map<std::pair<int, int>, const Contact*> by_pair;
  for (const Contact* c : world.contacts()) by_pair[{c->a, c->b}] = c;
  std::vector<int> chain;
  chain.push_back(layout.left_abutment);
  for (int i : layout.beam) chain.push_back(i);
  chain.push_back(layout.right_abutment);
  for (std::size_t k = 0; k + 1 < chain.size(); ++k) {
    VoussoirJoint j;
    j.left = chain[k];
    j.right = chain[k + 1];
    auto it = by_pair.find({std::min(j.left, j.right), std::max(j.left, j.right)});
    if (it != by_pair.end()) {
      const Contact& c = *it->second;
      j.in_contact = true;
      j.x = c.force_point().x();
      j.z = c.force_point().z();
      j.normal_force = c.normal_force;
      // Force on the left block from the right one is -f if the left block is c.b, ... orient:
      const Eigen::Vector3d on_b = c.force_on_b();
      const Eigen::Vector3d on_right = c.b == j.right ? on_b : Eigen::Vector3d(-on_b);
      j.horizontal_force = on_right.x();  // compression pushes the right block to +x
      j.shear_force = c.shear.force.norm();
      j.normal_stress = c.normal_stress;
      j.closure = c.peak_closure();
      j.area = c.compressed_area();
      j.peak_stress = c.peak_stress();
      j.compressed_depth = c.compressed_area() / spec.block_width;
      j.plastic_slip = c.shear.plastic_slip;
      j.sliding = c.sliding;
      lv.max_normal_stress = std::max(lv.max_normal_stress, c.peak_stress());
    }
    lv.joints.push_back(j);
  }

  // Blocks: displacements, bottom-face deflection and rotation about y since the reference.
  lv.beam_weight = 0.0;
  for (int i : layout.beam) {
    const Block& b = blocks[i];
    lv.beam_weight += b.mass * g_level * kOneG;
    VoussoirBlockState st;
    st.index = i;
    const Eigen::Vector3d u = b.position - ref.positions[i];
    st.ux = u.x();
    st.uz = u.z();
    const Eigen::Vector3d bottom_ref(ref.positions[i].x(), ref.positions[i].y(),
                                     ref.positions[i].z() - t / 2);
    st.deflection = -point_displacement(b, ref, bottom_ref).z();
    const Eigen::AngleAxisd rot(b.orientation * ref.orientations[i].conjugate());
    st.rotation = rot.angle() * rot.axis().y();
    lv.blocks.push_back(st);
  }

  // Midspan deflection: the bottom of the beam at x = S/2 (a block's bottom-face centre for an
  // odd count, the mean of the two bottom corners at the middle joint for an even one).
  const int n = static_cast<int>(layout.beam.size());
  if (n % 2 == 1) {
    lv.midspan_deflection = lv.blocks[n / 2].deflection;
  } else {
    const Block& l = blocks[layout.beam[n / 2 - 1]];
    const Block& r = blocks[layout.beam[n / 2]];
    const Eigen::Vector3d corner(ref.positions[l.index].x() + spec.block_length / 2,
                                 ref.positions[l.index].y(), ref.positions[l.index].z() - t / 2);
    const Eigen::Vector3d corner_r(ref.positions[r.index].x() - spec.block_length / 2,
                                   ref.positions[r.index].y(), ref.positions[r.index].z() - t / 2);
    lv.midspan_deflection =
        -0.5 * (point_displacement(l, ref, corner).z() + point_displacement(r, ref, corner_r).z());
  }

  // Abutment slip: downward movement of the end faces' centres.
  {
    const Block& first = blocks[layout.beam.front()];
    const Block& last = blocks[layout.beam.back()];
    const Eigen::Vector3d end_l(ref.positions[first.index].x() - spec.block_length / 2,
                                ref.positions[first.index].y(), ref.positions[first.index].z());
    const Eigen::Vector3d end_r(ref.positions[last.index].x() + spec.block_length / 2,
                                ref.positions[last.index].y(), ref.positions[last.index].z());
    lv.abutment_slip = -0.5 * (point_displacement(first, ref, end_l).z() +
                               point_displacement(last, ref, end_r).z());
  }

  // Statics of the half span: H z = W S / 8.
  lv.equilibrium_residual = std::numeric_limits<double>::quiet_NaN();
  if (n % 2 == 0) {
    const VoussoirJoint& mid = lv.joints[static_cast<std::size_t>(n / 2)];
    const VoussoirJoint& a = lv.joints.front();
    const VoussoirJoint& b = lv.joints.back();
    if (mid.in_contact && a.in_contact && b.in_contact) {
      lv.lever_arm = mid.z - 0.5 * (a.z + b.z);
      const double ws8 = lv.beam_weight * s / 8.0;
      lv.equilibrium_residual = std::abs(mid.horizontal_force * lv.lever_arm - ws8) / ws8;
    }
  }

  // Line of thrust through the joints' contact points.
  std::vector<double> xs, zs;
  for (const auto& j : lv.joints) {
    if (!j.in_contact) continue;
    xs.push_back(j.x);
    zs.push_back(j.z);
  }
  try {
    lv.fit = fit_thrust_line(
        Eigen::Map<Eigen::VectorXd>(xs.data(), static_cast<Eigen::Index>(xs.size())),
        Eigen::Map<Eigen::VectorXd>(zs.data(), static_cast<Eigen::Index>(zs.size())),
        lv.beam_weight / s);
  } catch (const std::exception& e) {
    lv.fit_error = e.what();
  }
  return lv;
}

}  // namespace blockdem
