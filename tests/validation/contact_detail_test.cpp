// A contact keeps apart (ContactDetail) only what its geometry does not give: a point contact's
// force point, compressed area, peak stress and closure are x_c, A_c, σ_n and δ, bit for bit,
// and it holds no detail; a face-integrated contact holds its own, which copies and the bytes
// between processes carry unchanged.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "blockdem/world/contact.hpp"
#include "scenes.hpp"

namespace blockdem {
namespace {

bool same_bits(const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  return std::memcmp(x.data(), y.data(), 3 * sizeof(double)) == 0;
}
bool same_bits(double x, double y) {
  return std::memcmp(&x, &y, sizeof(double)) == 0;
}

std::vector<char> bytes_of(const Contact& c) {
  std::vector<char> out(kContactBytes);
  contact_to_bytes(c, out.data());
  return out;
}

// Every value a contact's readers see, bit for bit (not the padding between them).
bool same_state(const Contact& x, const Contact& y) {
  return x.a == y.a && x.b == y.b && x.law == y.law && x.has_history == y.has_history &&
         x.integrated == y.integrated && x.sliding == y.sliding && x.touching == y.touching &&
         same_bits(x.geometry.point, y.geometry.point) &&
         same_bits(x.geometry.normal, y.geometry.normal) &&
         same_bits(x.geometry.overlap, y.geometry.overlap) &&
         same_bits(x.geometry.area, y.geometry.area) && same_bits(x.shear.force, y.shear.force) &&
         same_bits(x.shear.elastic_displacement, y.shear.elastic_displacement) &&
         same_bits(x.shear.plastic_slip, y.shear.plastic_slip) &&
         same_bits(x.shear.elastic_energy, y.shear.elastic_energy) &&
         x.shear.bond == y.shear.bond && same_bits(x.twist.moment, y.twist.moment) &&
         same_bits(x.normal_stress, y.normal_stress) && same_bits(x.normal_force, y.normal_force) &&
         same_bits(x.shear_couple, y.shear_couple) && same_bits(x.stiffness, y.stiffness) &&
         same_bits(x.twist_stiffness, y.twist_stiffness) && same_bits(x.slip_work, y.slip_work) &&
         same_bits(x.force_point(), y.force_point()) &&
         same_bits(x.compressed_area(), y.compressed_area()) &&
         same_bits(x.peak_stress(), y.peak_stress()) &&
         same_bits(x.peak_closure(), y.peak_closure()) &&
         same_bits(x.normal_energy(), y.normal_energy()) &&
         same_bits(x.previous_normal(), y.previous_normal());
}

// A block pressed off-centre onto a fixed base (an eccentric load: the centre of pressure lies
// away from the contact point), stepped a while.
World pressed_block(ContactMode mode) {
  WorldSettings s;
  s.contact_mode = mode;
  s.damping = 0.7;
  World w = test::linear_world(1e10, 1e9, 60, s);
  w.add_block(test::box_block({0.4, 0.4, 0.05}, {0, 0, -0.025}, 2600, Motion::fixed, "base"));
  const double P = 200.0, e = 0.02, H = 0.05;
  Block b = test::box_block({0.1, 0.1, H}, {0, 0, H / 2 - 1e-8}, 2600);
  b.set_external_force({0, 0, -P});
  b.set_external_torque({0, P * e, 0});
  w.add_block(b);
  for (int k = 0; k < 300; ++k) w.step();
  return w;
}

TEST(ContactDetail, PointContactsTakeTheirValuesFromTheGeometry) {
  const World w = pressed_block(ContactMode::boon2012);
  const auto contacts = w.contacts();
  ASSERT_EQ(contacts.size(), 1u);
  const Contact& c = *contacts[0];
  EXPECT_FALSE(c.integrated);
  EXPECT_EQ(c.detail_record(), nullptr);
  EXPECT_TRUE(same_bits(c.force_point(), c.geometry.point));
  EXPECT_TRUE(same_bits(c.compressed_area(), c.geometry.area));
  EXPECT_TRUE(same_bits(c.peak_stress(), c.normal_stress));
  EXPECT_TRUE(same_bits(c.peak_closure(), c.geometry.overlap));
  EXPECT_TRUE(same_bits(c.previous_normal(), c.geometry.normal));
  EXPECT_GT(c.normal_force, 0.0);
  EXPECT_GT(c.stiffness, 0.0);
}

TEST(ContactDetail, FaceContactsKeepTheirOwnValuesThroughCopiesAndBytes) {
  const World w = pressed_block(ContactMode::face_integrated);
  const auto contacts = w.contacts();
  ASSERT_EQ(contacts.size(), 1u);
  const Contact& c = *contacts[0];
  ASSERT_TRUE(c.integrated);
  ASSERT_NE(c.detail_record(), nullptr);
  EXPECT_TRUE(c.detail_record()->has_force_values);
  EXPECT_FALSE(c.detail_record()->has_previous_normal);
  // The centre of pressure lies towards the load, away from x_c; the peak closure exceeds the
  // closure at x_c on the loaded side.
  EXPECT_GT((c.force_point() - c.geometry.point).norm(), 1e-4);
  EXPECT_GT(c.peak_closure(), 0.0);
  EXPECT_GT(c.peak_stress(), c.normal_stress);
  EXPECT_GT(c.compressed_area(), 0.0);

  const Contact copy = c;
  ASSERT_NE(copy.detail_record(), nullptr);
  EXPECT_NE(copy.detail_record(), c.detail_record());  // a copy owns its detail
  EXPECT_TRUE(same_state(copy, c));
  const Contact back = contact_from_bytes(bytes_of(c).data());
  EXPECT_TRUE(same_state(back, c));
  ASSERT_NE(back.detail_record(), nullptr);
  EXPECT_TRUE(back.detail_record()->has_force_values);

  // Back to point values: the detail goes, and the values follow the geometry again.
  Contact point = c;
  point.take_point_values();
  EXPECT_EQ(point.detail_record(), nullptr);
  EXPECT_TRUE(same_bits(point.force_point(), c.geometry.point));
}

TEST(ContactDetail, PreviousNormalIsKeptApartOnlyWhereItDiffers) {
  Contact c;
  c.geometry.normal = Eigen::Vector3d(0.0, 0.6, 0.8);
  c.set_previous_normal(Eigen::Vector3d(0.0, 0.6, 0.8));
  EXPECT_EQ(c.detail_record(), nullptr);
  c.set_previous_normal(Eigen::Vector3d(0.0, -0.0, 1.0) * 1.0);
  ASSERT_NE(c.detail_record(), nullptr);
  EXPECT_TRUE(same_bits(c.previous_normal(), Eigen::Vector3d(0.0, -0.0, 1.0)));
  // -0.0 and 0.0 differ in their bits: a turn from either gives other bits.
  c.geometry.normal = Eigen::Vector3d(0.0, 0.0, 1.0);
  c.set_previous_normal(Eigen::Vector3d(0.0, -0.0, 1.0));
  EXPECT_NE(c.detail_record(), nullptr);
  c.take_normal_as_previous();
  EXPECT_EQ(c.detail_record(), nullptr);
  EXPECT_TRUE(same_bits(c.previous_normal(), c.geometry.normal));
}

// The flags and the law live in the shear state's tail padding: assigning the shear state, as
// the shear kernels and a restore do, must leave them, and a moved or assigned contact must
// carry them (it copies its values as one block of bytes).
TEST(ContactDetail, FlagsAndLawInTheShearStateTailSurviveAssignmentsAndMoves) {
  Contact c;
  c.a = 3;
  c.b = 7;
  c.law = 5;
  c.has_history = true;
  c.sliding = true;
  c.touching = true;
  c.geometry.normal = Eigen::Vector3d(0.0, 0.6, 0.8);
  c.shear.force = Eigen::Vector3d(1.0, -2.0, 0.5);
  c.shear.bond = BondState::broken_in_shear;
  c.twist.moment = -0.25;
  c.slip_work = 1.5;
  c.set_previous_normal(Eigen::Vector3d(0.0, 0.0, 1.0));
  const Contact reference = c;

  ShearState fresh;
  fresh.plastic_slip = 0.125;
  c.shear = fresh;
  EXPECT_EQ(c.law, 5);
  EXPECT_TRUE(c.has_history && c.sliding && c.touching && !c.integrated);
  EXPECT_EQ(c.shear.bond, BondState::intact);
  c.shear = reference.shear;
  EXPECT_TRUE(same_state(c, reference));

  Contact moved(std::move(c));
  EXPECT_TRUE(same_state(moved, reference));
  Contact assigned;
  assigned = std::move(moved);
  EXPECT_TRUE(same_state(assigned, reference));
  Contact& self = assigned;
  assigned = std::move(self);
  EXPECT_TRUE(same_state(assigned, reference));
  Contact copied;
  copied = assigned;
  EXPECT_TRUE(same_state(copied, reference));
  EXPECT_NE(copied.detail_record(), assigned.detail_record());
}

}  // namespace
}  // namespace blockdem
