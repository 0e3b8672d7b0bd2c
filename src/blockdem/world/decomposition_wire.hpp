// The decomposition's records on the wire (world/decomposition*.cpp): a process's step figures,
// a block's state as a ghost needs it (through state_record.hpp's motion_record, as the restart
// file and a replica refresh send it), a pair slot with its contact state, and the byte helpers
// that write and read them. Every process runs the same program, so the slots and contacts are
// raw bytes of plain data.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "blockdem/dynamics/block.hpp"
#include "blockdem/world/contact.hpp"
#include "blockdem/world/energy_budget.hpp"
#include "blockdem/world/state_record.hpp"

namespace blockdem::decomposition_wire {

/// A process's figures of one step, gathered to every process (a few bytes per process).
struct StepHeader {
  double seconds = 0.0;      ///< time in this step's own pair work (s)
  std::uint64_t slots = 0;   ///< pairs it evaluated (-)
  std::uint64_t failed = 0;  ///< 1: a pair of this process refused a value; 2: another error
};

/// A ghost on the wire: the block's index, then its pose and velocities at the half step
/// (motion_record, state_record.hpp), all that a ghost needs.
constexpr std::size_t kGhostBytes = sizeof(std::int64_t) + kMotionRecordBytes;

inline void put_ghost(std::vector<char>& out, const Block& b) {
  WireWriter w(out);
  SaveArchive ar(w);
  ar.as<std::int64_t>(b.index);
  motion_record(ar, b);
}

/// Rebalance when the slowest process's pair work exceeds the mean by this factor (-)...
constexpr double kImbalanceThreshold = 1.25;
/// ... and at least this many steps have passed since the last partition (-).
constexpr std::int64_t kMinStepsBetweenPartitions = 100;
/// ... and the slowest process loses more than this per step against the mean (s): below it the
/// measured times are mostly noise, and an imbalance costs nothing worth a partition.
constexpr double kMinImbalanceSeconds = 1e-3;
/// ... and the processes' pair counts are uneven by this factor too (-): the bisection balances
/// pair counts, so only then can a new partition help (and counts carry no timing noise).
constexpr double kPairCountThreshold = 1.1;

inline void put_bytes(std::vector<char>& out, const void* p, std::size_t n) {
  // An empty part's data() may be null, which memcpy may not be given even for no bytes.
  if (n == 0) return;
  const std::size_t at = out.size();
  out.resize(at + n);
  std::memcpy(out.data() + at, p, n);
}

template <class T>
inline void put(std::vector<char>& out, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  put_bytes(out, &value, sizeof(T));
}

template <class T>
inline T get(const std::vector<char>& in, std::size_t offset) {
  T value;
  std::memcpy(static_cast<void*>(&value), in.data() + offset, sizeof(T));
  return value;
}

inline void put3(std::vector<char>& out, const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) put(out, v[k]);
}

inline Eigen::Vector3d get3(const std::vector<char>& in, std::size_t offset) {
  return {get<double>(in, offset), get<double>(in, offset + 8), get<double>(in, offset + 16)};
}

/// A pair slot on the wire: its bytes, then its contact's when a force acts (`contact`, non-null
/// exactly then; contact_to_bytes). A slot holds fixed-size data only (no pointers, no heap
/// storage), and every process runs the same program.
template <class Slot>
inline void put_slot(std::vector<char>& out, const Slot& s, const Contact* contact) {
  static_assert(std::is_trivially_destructible_v<Slot>, "a pair slot must be plain data");
  put_bytes(out, &s, sizeof(Slot));
  if (!s.active) return;
  char bytes[kContactBytes];
  contact_to_bytes(*contact, bytes);
  put_bytes(out, bytes, kContactBytes);
}

/// Reads put_slot's record at `at` (advanced past it), not beyond `end`; false when malformed.
template <class Slot>
inline bool get_slot(const std::vector<char>& in, std::size_t& at, std::size_t end, Slot& s,
                     Contact& contact) {
  if (at + sizeof(Slot) > end) return false;
  std::memcpy(static_cast<void*>(&s), in.data() + at, sizeof(Slot));
  at += sizeof(Slot);
  if (!s.active) return true;
  if (at + kContactBytes > end) return false;
  contact = contact_from_bytes(in.data() + at);
  at += kContactBytes;
  return true;
}

/// A block that mark_resting marks resting: fixed, with zero velocities.
inline bool at_rest(const Block& b) {
  return b.motion == Motion::fixed && (b.velocity.array() == 0.0).all() &&
         (b.angular_velocity.array() == 0.0).all();
}

/// The slot list's index of the pair whose key (a n + b) is `key`, among the slots `counts`
/// accepts, or -1: the first too-deep overlap a reduction found, located in a process's slots.
template <class Slots, class Accept>
inline std::int64_t slot_of_key(const Slots& slots, std::size_t n, double key,
                                const Accept& counts) {
  if (!std::isfinite(key)) return -1;
  for (std::size_t k = 0; k < slots.size(); ++k) {
    const auto& c = slots[k];
    if (static_cast<double>(c.a) * static_cast<double>(n) + c.b == key && counts(c))
      return static_cast<std::int64_t>(k);
  }
  return -1;
}

inline bool boxes_overlap(const Eigen::Vector3d& min_a, const Eigen::Vector3d& max_a,
                          const Eigen::Vector3d& min_b, const Eigen::Vector3d& max_b) {
  return (min_a.array() <= max_b.array()).all() && (min_b.array() <= max_a.array()).all();
}

}  // namespace blockdem::decomposition_wire
