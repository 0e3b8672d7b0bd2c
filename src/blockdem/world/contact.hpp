// A persistent contact between two blocks: geometry of this step, joint law, shear history.
#pragma once

#include <cstddef>
#include <cstring>
#include <memory>
#include <type_traits>

#include <Eigen/Core>

#include "blockdem/collision/boon2012.hpp"
#include "blockdem/collision/contact_geometry.hpp"
#include "blockdem/contact/shear_state.hpp"
#include "blockdem/contact/twist.hpp"

namespace blockdem {

/// The narrow phase's result as a contact keeps it between steps: ContactGeometry without the
/// slice polygon, which only the narrow phase itself needs (it is ~400 bytes per contact), and
/// without the overlap LP's ball, which the pair's warm start keeps. Whether the LP found
/// r* > tolerance is Contact::touching (beside the other flags, without padding).
struct ContactGeometryRecord {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    ///< contact point x_c (m)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit normal, from A to B (-)
  double overlap = 0.0;  ///< δ: chord of A∩B through x_c along n (m)
  double area = 0.0;     ///< A_c: area of the slice of A∩B at x_c (m^2)

  ContactGeometryRecord() = default;
  explicit ContactGeometryRecord(const ContactGeometry& g)
      : point(g.point), normal(g.normal), overlap(g.overlap), area(g.area) {}
};

/// What a contact holds beyond the values a point contact takes from its geometry: the force
/// point, compressed area, peak stress and peak closure of a face-integrated contact (a point
/// contact's are x_c, A_c, σ_n and δ), the previous step's normal where it is not this step's
/// (after a restore re-derived the geometry without a shear update), and the dashpot's force and
/// work of a contact with viscous damping.
struct ContactDetail {
  Eigen::Vector3d force_point = Eigen::Vector3d::Zero();  ///< (m)
  /// The viscous dashpot's normal force of the last step (N), compression positive, on b along
  /// +normal at the force point (response/contact_damping.hpp); zero without contact damping.
  /// Beside the force point: the loads' scatter reads both.
  double damping_force = 0.0;
  Eigen::Vector3d previous_normal = Eigen::Vector3d::UnitZ();  ///< (-)
  double compressed_area = 0.0;                                ///< (m^2)
  double peak_stress = 0.0;                                    ///< (Pa)
  double peak_closure = 0.0;                                   ///< (m)
  double normal_energy = 0.0;  ///< ∫ e(g) dA, the normal springs' energy (J)
  /// The energy the dashpot dissipated in the last step (J): this step's half of the
  /// trapezoidal work of its force (the other half follows with the next step's velocities).
  double damping_work = 0.0;
  /// The five force values (force point, area, peak stress, peak closure, normal energy) are the
  /// contact's own.
  bool has_force_values = false;
  bool has_previous_normal = false;  ///< previous_normal is the contact's own
};

/// A contact's fixed-size state (plain data: it travels between processes as bytes).
struct ContactValues {
  int a = -1;  ///< first block (the normal points from a to b)
  int b = -1;  ///< second block

  ContactGeometryRecord geometry;  ///< this step's geometry
  /// Shear history (force on b, plastic slip). Its last 7 bytes are padding after the bond,
  /// which the flags and the law below take (no_unique_address lets them into its tail): 192
  /// bytes of values, not 200.
  [[no_unique_address]] ShearState shear;
  // One byte of bit-fields: a contact's flags are written by the one thread that has its pair.
  bool has_history : 1 = false;  ///< false on the step the contact forms
  bool integrated : 1 = false;   ///< the force came from face integration (else point contact)
  bool sliding : 1 = false;      ///< the shear law yielded this step
  bool touching : 1 = false;     ///< this step's overlap LP found r* > tolerance (geometry is set)
  int law = -1;                  ///< index into World::joint_laws()
  TwistState twist;              ///< twisting moment about the normal (on b)

  double normal_stress = 0.0;  ///< σ_n (Pa); face-integrated: mean over the compressed area
  double normal_force = 0.0;   ///< F_n (N), compression positive, acts on b along +normal
  // This step's terms of the pair (zero unless a force acts), for the time step and the energy
  // budget.
  double stiffness = 0.0;        ///< k_n A + k_s A (N/m)
  double twist_stiffness = 0.0;  ///< k_s J (N m/rad)
  double slip_work = 0.0;        ///< energy dissipated by slip (J)
  /// The couple about the normal (on b) that moves the shear force from the force point to the
  /// point where the shear spring acts (N m): ((x_s - x_f) × F_s) · n.
  double shear_couple = 0.0;

  /// The couple about the normal on b (N m): the twisting moment and the shear couple.
  double couple_about_normal() const { return twist.moment + shear_couple; }
};

struct Contact : ContactValues {
  Contact() = default;
  Contact(const Contact& other) : ContactValues(other) { copy_detail(other); }
  Contact(Contact&& other) noexcept : detail_(std::move(other.detail_)) { copy_values(other); }
  Contact& operator=(const Contact& other) {
    if (this != &other) {
      copy_values(other);
      copy_detail(other);
    }
    return *this;
  }
  Contact& operator=(Contact&& other) noexcept {
    copy_values(other);
    detail_ = std::move(other.detail_);
    return *this;
  }
  ~Contact() = default;

  /// Where the normal and shear forces act (m): x_c for a point contact, the centre of pressure
  /// of an integrated face contact.
  const Eigen::Vector3d& force_point() const {
    return force_values() ? detail_->force_point : geometry.point;
  }
  /// Area carrying stress (m^2); a point contact's slice area.
  double compressed_area() const {
    return force_values() ? detail_->compressed_area : geometry.area;
  }
  /// Largest normal stress over the contact (Pa); a point contact's σ_n.
  double peak_stress() const { return force_values() ? detail_->peak_stress : normal_stress; }
  /// Largest closure over the contact (m); a point contact's δ.
  double peak_closure() const { return force_values() ? detail_->peak_closure : geometry.overlap; }
  /// Energy stored in the normal springs (J): ∫ e(g) dA of an integrated face contact, else
  /// ½ F_n δ (exact for the linear law at a uniform closure).
  double normal_energy() const {
    return force_values() ? detail_->normal_energy : 0.5 * normal_force * geometry.overlap;
  }
  /// The normal of the last shear update (-): this step's normal but after a restore.
  const Eigen::Vector3d& previous_normal() const {
    return detail_ && detail_->has_previous_normal ? detail_->previous_normal : geometry.normal;
  }

  /// The force values are the point contact's (they follow the geometry and σ_n).
  void take_point_values() {
    if (!detail_) return;
    detail_->has_force_values = false;
    drop_empty_detail();
  }
  /// A face-integrated contact's own force values.
  void set_force_values(const Eigen::Vector3d& point, double area, double stress, double closure,
                        double energy) {
    ContactDetail& d = detail();
    d.force_point = point;
    d.compressed_area = area;
    d.peak_stress = stress;
    d.peak_closure = closure;
    d.normal_energy = energy;
    d.has_force_values = true;
  }
  /// The previous normal is this step's geometry.normal from now on.
  void take_normal_as_previous() {
    if (!detail_) return;
    detail_->has_previous_normal = false;
    drop_empty_detail();
  }
  /// The previous normal is `n`: kept apart only if its bits differ from geometry.normal's (set
  /// the geometry first).
  void set_previous_normal(const Eigen::Vector3d& n) {
    if (std::memcmp(n.data(), geometry.normal.data(), 3 * sizeof(double)) == 0) {
      take_normal_as_previous();
      return;
    }
    ContactDetail& d = detail();
    d.previous_normal = n;
    d.has_previous_normal = true;
  }
  /// The record kept apart, or null (a point contact in the common case).
  const ContactDetail* detail_record() const { return detail_.get(); }

  /// The dashpot's normal force (N) and the energy it dissipated in the step (J); zero without
  /// contact damping (ContactDetail).
  double damping_force() const { return detail_ ? detail_->damping_force : 0.0; }
  double damping_work() const { return detail_ ? detail_->damping_work : 0.0; }
  /// Sets the dashpot's values; zeros on a contact without a record leave it without one.
  void set_damping(double force, double work) {
    if (!detail_ && force == 0.0 && work == 0.0) return;
    ContactDetail& d = detail();
    d.damping_force = force;
    d.damping_work = work;
    drop_empty_detail();
  }

  /// Total force on b (N), springs and dashpot; the force on a is its negative.
  Eigen::Vector3d force_on_b() const {
    return (normal_force + damping_force()) * geometry.normal + shear.force;
  }

 private:
  bool force_values() const { return detail_ && detail_->has_force_values; }
  ContactDetail& detail() {
    if (!detail_) detail_ = std::make_unique<ContactDetail>();
    return *detail_;
  }
  void drop_empty_detail() {
    if (!detail_->has_force_values && !detail_->has_previous_normal &&
        detail_->damping_force == 0.0 && detail_->damping_work == 0.0)
      detail_.reset();
  }
  /// The values as one block of bytes: the defaulted copy copies the shear state without its
  /// tail (the flags and the law live there) and then those field by field, which the settle,
  /// moving every contact, felt (memmove: a contact may be moved onto itself).
  void copy_values(const Contact& other) {
    std::memmove(static_cast<void*>(static_cast<ContactValues*>(this)),
                 static_cast<const ContactValues*>(&other), sizeof(ContactValues));
  }
  void copy_detail(const Contact& other) {
    if (!other.detail_) {
      detail_.reset();
    } else if (detail_) {
      *detail_ = *other.detail_;
    } else {
      detail_ = std::make_unique<ContactDetail>(*other.detail_);
    }
  }

  /// Held out of line: mode boon2012 needs it only for contacts restored from a checkpoint, and
  /// each contact of a large scene costs 8 bytes instead of 72.
  std::unique_ptr<ContactDetail> detail_;
};

// A change of either record must be deliberate: the contact store is the largest array of a
// large scene with the pair store (bench/README.md, "Memory at 1e5 blocks").
static_assert(std::is_trivially_destructible_v<ContactValues> && sizeof(ContactValues) == 200,
              "ContactValues changed size");
static_assert(sizeof(Contact) == 208, "Contact changed size");
static_assert(std::is_trivially_destructible_v<ContactDetail> && sizeof(ContactDetail) == 104,
              "ContactDetail changed size");

/// A contact as bytes between processes of the same program: its values, then its detail (all
/// zero bytes and both flags false when it has none).
constexpr std::size_t kContactBytes = sizeof(ContactValues) + sizeof(ContactDetail);
inline void contact_to_bytes(const Contact& c, char* out) {
  std::memcpy(out, static_cast<const ContactValues*>(&c), sizeof(ContactValues));
  const ContactDetail none{};
  const ContactDetail* d = c.detail_record();
  std::memcpy(out + sizeof(ContactValues), d != nullptr ? d : &none, sizeof(ContactDetail));
}
inline Contact contact_from_bytes(const char* in) {
  Contact c;
  std::memcpy(static_cast<void*>(static_cast<ContactValues*>(&c)), in, sizeof(ContactValues));
  ContactDetail d;
  std::memcpy(static_cast<void*>(&d), in + sizeof(ContactValues), sizeof(ContactDetail));
  if (d.has_force_values)
    c.set_force_values(d.force_point, d.compressed_area, d.peak_stress, d.peak_closure,
                       d.normal_energy);
  if (d.has_previous_normal) c.set_previous_normal(d.previous_normal);
  return c;
}

/// Back to a fresh contact (no history, no forces), keeping the pair and its bond state: a bond
/// that broke stays broken, and an intact one stays intact, while the pair remains a candidate.
inline void forget_history(Contact& c) {
  if (!c.has_history) return;
  Contact fresh;
  fresh.a = c.a;
  fresh.b = c.b;
  fresh.law = c.law;
  fresh.shear.bond = c.shear.bond;
  c = std::move(fresh);
}

}  // namespace blockdem
