// One serialisation of a block's and a contact's state: each record is one function that both
// writes and reads it (the archive says which), so a field cannot be written and forgotten on
// read, over the byte streams of the restart file (StateWriter/StateReader) and of the MPI wire
// (WireWriter/WireReader).
//
// Where a block's dynamic state and a contact (pair-store) record are written and read:
// - restart file: World::save_state/load_state (world_state.cpp) write every block with
//   block_record, every pair slot with slot_record (its contact through contact_record), and the
//   divergence checkpoint's blocks and kept contacts with checkpoint_block_record and
//   history_record; under MPI, save_state_to_root (decomposition_replica.cpp) merges the same
//   records to process 0 from the processes that keep them exact.
// - MPI wire: the ghosts of each distributed step (decomposition_step.cpp) and the replica
//   refresh (decomposition_replica.cpp) send a block's pose and velocities with motion_record;
//   the pair slots of a step, a migration (decomposition_migrate.cpp) and a refresh travel as
//   the plain bytes of PairSlot and of a contact (put_slot, contact_to_bytes: complete by
//   construction, the static_asserts in contact.hpp and world.hpp guard their sizes); the
//   divergence checkpoint's parts as the plain bytes of its records (gather_checkpoint).
// - divergence checkpoint in memory: World::save_checkpoint/restore_checkpoint (world.cpp) keep
//   the pose and velocities (World::BlockState) and what a contact needs after a restore
//   (World::ContactHistory); the restart file writes them with the records above.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "blockdem/collision/boon2012.hpp"
#include "blockdem/contact/shear_state.hpp"
#include "blockdem/dynamics/block.hpp"
#include "blockdem/world/contact.hpp"
#include "blockdem/world/state_stream.hpp"

namespace blockdem {

/// Writes each field a record visits (`loading` is false: the record reads its object).
template <class Writer>
class SaveArchive {
 public:
  static constexpr bool loading = false;
  explicit SaveArchive(Writer& w) : w_(w) {}
  template <class T>
  requires std::is_arithmetic_v<T>
  void operator()(const T& v) { w_.pod(v); }
  /// A vector, and a quaternion (x, y, z, w as Eigen keeps them), coefficient by coefficient.
  void operator()(const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) w_.pod(v[i]);
  }
  void operator()(const Eigen::Quaterniond& q) {
    for (int i = 0; i < 4; ++i) w_.pod(q.coeffs()[i]);
  }
  /// `v` stored as `Stored` (a flag or an enum as a fixed-width integer).
  template <class Stored, class T>
  void as(const T& v) {
    w_.pod(static_cast<Stored>(v));
  }
  void text(const std::string& s) { w_.str(s); }
  /// A list's length (the record then visits its elements).
  template <class List>
  void count(const List& list) {
    w_.size(list.size());
  }

 private:
  Writer& w_;
};

/// Reads each field a record visits (`loading` is true: the record fills its object).
template <class Reader>
class LoadArchive {
 public:
  static constexpr bool loading = true;
  explicit LoadArchive(Reader& r) : r_(r) {}
  template <class T>
  requires std::is_arithmetic_v<T>
  void operator()(T& v) { v = r_.template pod<T>(); }
  void operator()(Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) v[i] = r_.template pod<double>();
  }
  void operator()(Eigen::Quaterniond& q) {
    for (int i = 0; i < 4; ++i) q.coeffs()[i] = r_.template pod<double>();
  }
  /// `v` stored as `Stored`; a flag is true for any non-zero byte.
  template <class Stored, class T>
  void as(T& v) {
    v = static_cast<T>(r_.template pod<Stored>());
  }
  void text(std::string& s) { s = r_.str(); }
  /// A list's length: the list is resized to it (the record then visits its elements).
  template <class List>
  void count(List& list) {
    list.resize(r_.size());
  }

 private:
  Reader& r_;
};

/// The object a record visits: const when saving, mutable when loading.
template <class Ar, class T>
using Field = std::conditional_t<Ar::loading, T&, const T&>;

/// The MPI wire's stream: appends to a process's part (a std::vector<char>, as the
/// distribution sends it), in the machine's byte order (every process runs the same program).
class WireWriter {
 public:
  explicit WireWriter(std::vector<char>& out) : out_(out) {}
  template <class T>
  requires std::is_trivially_copyable_v<T>
  void pod(const T& value) {
    const std::size_t at = out_.size();
    out_.resize(at + sizeof(T));
    std::memcpy(out_.data() + at, &value, sizeof(T));
  }

 private:
  std::vector<char>& out_;
};

/// Reads what a WireWriter wrote, from `at` (advanced) up to `end`; a part that ends early is
/// malformed (std::logic_error naming `what`: every process runs the same program).
class WireReader {
 public:
  WireReader(const std::vector<char>& in, std::size_t& at, std::size_t end, const char* what)
      : in_(in), at_(at), end_(end), what_(what) {}
  template <class T>
  requires std::is_trivially_copyable_v<T> T pod() {
    if (at_ > end_ || sizeof(T) > end_ - at_)
      throw std::logic_error(std::string(what_) + ": a process sent a malformed part");
    T value;
    std::memcpy(static_cast<void*>(&value), in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }

 private:
  const std::vector<char>& in_;
  std::size_t& at_;
  std::size_t end_;
  const char* what_;
};

// A record below lists every field of its struct that it stores. A static_assert on the
// struct's size stands beside it: a field added to the struct fails it, and the message tells
// the reader to add the field to the record (or to say here why the record leaves it out).
static_assert(sizeof(Servo) == 64, "Servo changed: update servo_record (state_record.hpp)");
static_assert(sizeof(ShearState) == 72,
              "ShearState changed: update shear_record (state_record.hpp)");
static_assert(sizeof(Boon2012Cache) == 184,
              "Boon2012Cache changed: update warm_start_record (state_record.hpp)");
// Most of a block is the scenario's (shape, mass, density, name); a field that a step or a stage
// changes must go in block_record (world_state.cpp) and, if a ghost reads it, in motion_record.
static_assert(sizeof(Block) == 432,
              "Block changed: update block_record (world_state.cpp) or motion_record");

/// A servo: every field.
template <class Ar>
void servo_record(Ar& ar, Field<Ar, Servo> s) {
  ar(s.axis);
  ar(s.target_force);
  ar(s.gain);
  ar(s.max_speed);
  ar(s.tolerance);
  ar.template as<std::uint8_t>(s.hold);
}

/// A contact's shear history: every field (a bond state out of range is refused on read).
template <class Ar>
void shear_record(Ar& ar, Field<Ar, ShearState> s) {
  ar(s.force);
  ar(s.elastic_displacement);
  ar(s.plastic_slip);
  ar(s.elastic_energy);
  auto bond = static_cast<std::int32_t>(s.bond);
  ar(bond);
  if constexpr (Ar::loading) {
    if (bond < 0 || bond > static_cast<std::int32_t>(BondState::unbonded))
      throw StateError("saved bond state is corrupt");
    s.bond = static_cast<BondState>(bond);
  }
}

/// The narrow phase's warm start of a pair: every field but the ball's `restarted`, a diagnostic
/// of the last solve that no later solve reads.
template <class Ar>
void warm_start_record(Ar& ar, Field<Ar, Boon2012Cache> c) {
  ar.template as<std::int32_t>(c.planes_a);
  ar.template as<std::int32_t>(c.planes_b);
  ar(c.ball.radius);
  ar(c.ball.center);
  ar.template as<std::uint8_t>(c.ball.bounded);
  ar.template as<std::int32_t>(c.ball.iterations);
  for (auto& i : c.ball.active) ar.template as<std::int32_t>(i);
  ar.template as<std::int32_t>(c.ball.num_active);
  ar.template as<std::uint8_t>(c.has_ball);
  ar(c.last_point);
  ar.template as<std::uint8_t>(c.has_point);
  for (auto& i : c.slice.edge_planes) ar.template as<std::int32_t>(i);
  ar.template as<std::uint64_t>(c.slice.count);
  if constexpr (Ar::loading) {
    if (c.slice.count > c.slice.edge_planes.size()) throw StateError("saved contact is corrupt");
  }
}

/// A block's pose and velocities (its motion state between steps): the centroid, the
/// orientation, the velocity and angular velocity at the half step and the angular momentum.
/// `B` is a Block or any record with these five members (the divergence checkpoint's).
template <class Ar, class B>
void motion_record(Ar& ar, B& b) {
  ar(b.position);
  ar(b.orientation);
  ar(b.velocity);
  ar(b.angular_velocity);
  ar(b.angular_momentum);
}

/// Bytes of motion_record on the wire (five vectors, one of them a quaternion).
constexpr std::size_t kMotionRecordBytes = 16 * sizeof(double);

// The restart file's records. Each is one function for both directions; the bytes are those of
// every version-5 file. The World's types they visit are template parameters (B: Block, C:
// Contact, W: Boon2012Cache, S: a pair slot, H: World::ContactHistory).

/// A block: its name, motion state, scaling, motion and servo, loads (`loads`, when given, in
/// place of the block's own: the resting blocks' merged loads under MPI), world planes and box as
/// the last step left them (a restart does not refresh them), the displacements' reference and
/// the faces' laws (checked against `law_count` on read).
template <class Ar, class B, class V, class L>
void block_record(Ar& ar, B& b, V& box_min, V& box_max, L& laws, const Eigen::Vector3d* loads,
                  int law_count) {
  ar.text(b.name);
  motion_record(ar, b);
  ar(b.mass_scale);
  ar(b.inertia_scale);
  ar.template as<std::int32_t>(b.motion);
  Servo servo = b.servo();
  servo_record(ar, servo);
  if constexpr (Ar::loading) {
    b.set_servo(servo);
    ar(b.force);
    ar(b.torque);
    ar(b.contact_force);
  } else {
    ar(loads ? loads[0] : b.force);
    ar(loads ? loads[1] : b.torque);
    ar(loads ? loads[2] : b.contact_force);
  }
  ar.count(b.world_planes);
  for (auto& h : b.world_planes) {
    ar(h.normal);
    ar(h.offset);
  }
  ar(box_min);
  ar(box_max);
  ar(b.initial_position);
  ar(b.initial_orientation);
  ar.count(laws);
  for (auto& law : laws) {
    ar.template as<std::int32_t>(law);
    if constexpr (Ar::loading) {
      if (law < -1 || law >= law_count)
        throw StateError("block '" + b.name + "' has a face law the scenario does not have");
    }
  }
}

// A contact's values and the record kept apart (contact.hpp): a field added to either must go in
// contact_record (or in slot_record, for the step's terms of a pair). The record leaves out
// shear_couple, as every version-5 file does: it comes back zero, and the next per-pair pass sets
// it; and the dashpot's force and work of the last step (contact damping): they come back zero.
static_assert(sizeof(ContactValues) == 200 && sizeof(ContactDetail) == 104,
              "the contact changed: update contact_record (world_state.cpp)");

/// A slot's contact and warm start, as one record (the layout of a pair before its state was kept
/// apart). The contact's flags are bit-fields and its force values and previous normal are kept
/// apart only where they are not the point contact's: each goes through a local.
template <class Ar, class C, class W>
void contact_record(Ar& ar, C& c, W& cache) {
  ar.template as<std::int32_t>(c.a);
  ar.template as<std::int32_t>(c.b);
  ar.template as<std::int32_t>(c.law);
  bool touching = c.touching;
  ar.template as<std::uint8_t>(touching);
  auto& g = c.geometry;
  ar(g.point);
  ar(g.normal);
  ar(g.overlap);
  ar(g.area);
  // The overlap LP's ball, which a contact kept in this record's place: the warm start's (read
  // with it below).
  double ball_radius = cache.ball.radius;
  Eigen::Vector3d ball_center = cache.ball.center;
  ar(ball_radius);
  ar(ball_center);
  shear_record(ar, c.shear);
  bool has_history = c.has_history;
  ar.template as<std::uint8_t>(has_history);
  Eigen::Vector3d previous_normal = c.previous_normal();
  ar(previous_normal);
  ar(c.normal_stress);
  Eigen::Vector3d force_point = c.force_point();
  ar(force_point);
  bool integrated = c.integrated;
  ar.template as<std::uint8_t>(integrated);
  double compressed_area = c.compressed_area(), peak_stress = c.peak_stress();
  double peak_closure = c.peak_closure(), normal_energy = c.normal_energy();
  ar(compressed_area);
  ar(peak_stress);
  ar(peak_closure);
  ar(normal_energy);
  ar(c.normal_force);
  bool sliding = c.sliding;
  ar.template as<std::uint8_t>(sliding);
  ar(c.twist.moment);
  warm_start_record(ar, cache);
  if constexpr (Ar::loading) {
    c.touching = touching;
    c.has_history = has_history;
    c.integrated = integrated;
    c.sliding = sliding;
    c.set_previous_normal(previous_normal);
    c.set_force_values(force_point, compressed_area, peak_stress, peak_closure, normal_energy);
    const auto same = [](const auto& x, const auto& y) {
      static_assert(sizeof(x) == sizeof(y));
      return std::memcmp(&x, &y, sizeof(x)) == 0;
    };
    if (same(force_point, c.geometry.point) && same(compressed_area, c.geometry.area) &&
        same(peak_stress, c.normal_stress) && same(peak_closure, c.geometry.overlap) &&
        same(normal_energy, 0.5 * c.normal_force * c.geometry.overlap))
      c.take_point_values();
  }
}

/// A slot's own fields after its contact's record: its group law, whether its bond broke in the
/// step, the step's terms of the pair (its contact's where a force acts, else zero, as the
/// per-pair pass leaves them) and whether a force acts.
template <class Ar, class S, class C>
void slot_record(Ar& ar, S& s, C& c) {
  ar.template as<std::int32_t>(s.group_law);
  bool broke = s.broke;
  ar.template as<std::uint8_t>(broke);
  double slip_work = s.active ? c.slip_work : 0.0;
  double stiffness = s.active ? c.stiffness : 0.0;
  double twist_stiffness = s.active ? c.twist_stiffness : 0.0;
  ar(slip_work);
  ar(stiffness);
  ar(twist_stiffness);
  bool active = s.active;
  ar.template as<std::uint8_t>(active);
  if constexpr (Ar::loading) {
    s.broke = broke;
    s.active = active;
    c.slip_work = slip_work;
    c.stiffness = stiffness;
    c.twist_stiffness = twist_stiffness;
  }
}

/// A block of the divergence checkpoint: its motion state (in the order version 5 files keep),
/// motion and servo.
template <class Ar, class S, class M>
void checkpoint_block_record(Ar& ar, S& s, M& motion, Field<Ar, Servo> servo) {
  ar(s.position);
  ar(s.velocity);
  ar(s.angular_velocity);
  ar(s.angular_momentum);
  ar(s.orientation);
  ar.template as<std::int32_t>(motion);
  servo_record(ar, servo);
}

/// A kept slot of the divergence checkpoint (World::ContactHistory): every field.
template <class Ar, class H>
void history_record(Ar& ar, H& h) {
  ar.template as<std::int32_t>(h.a);
  ar.template as<std::int32_t>(h.b);
  ar.template as<std::int32_t>(h.law);
  ar.template as<std::uint8_t>(h.has_history);
  shear_record(ar, h.shear);
  ar(h.twist.moment);
  ar(h.previous_normal);
  ar(h.point);
  ar(h.closure);
  ar(h.area);
}

}  // namespace blockdem
