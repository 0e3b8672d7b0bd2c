// The records of World's pair store: one candidate pair's slot and the narrow phase's warm start
// as a slot keeps it.
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Core>

#include "blockdem/collision/slice_polygon.hpp"
#include "blockdem/contact/joint_strength.hpp"

namespace blockdem {

/// The narrow phase's warm start (Boon2012Cache) as a pair slot keeps it: the same values in
/// 104 bytes instead of 184, plane indices as 16-bit integers, without the solver's diagnostics
/// (iterations, restarted), which no warm start reads.
struct NarrowWarmStart {
  double radius = 0.0;                                             ///< ball.radius
  Eigen::Vector3d center = Eigen::Vector3d::Zero();                ///< ball.center
  Eigen::Vector3d last_point = Eigen::Vector3d::Zero();            ///< last_point
  std::array<std::int16_t, 4> active = {-1, -1, -1, -1};           ///< ball.active
  std::array<std::int16_t, SliceVertices::kInline> edge_planes{};  ///< slice.edge_planes
  std::int16_t planes_a = -1;                                      ///< planes_a
  std::int16_t planes_b = -1;                                      ///< planes_b
  std::uint8_t num_active = 0;                                     ///< ball.num_active
  std::uint8_t slice_count = 0;                                    ///< slice.count
  std::uint8_t flags = kBounded;  ///< has_ball, ball.bounded, has_point
  static constexpr std::uint8_t kHasBall = 1, kBounded = 2, kHasPoint = 4;
};

/// One candidate pair: the pair, its laws and flags and the narrow-phase warm start (kept for
/// near pairs too). The state of a contact lives apart, in World's contact store, for the pairs
/// that have one, with this step's stiffness terms and slip work: the pair store of a large scene
/// holds ~1.5 candidate pairs per contact (a rock mass ~15), and a near pair needs no contact
/// state.
struct PairSlot {
  int a = -1;                 ///< first block
  int b = -1;                 ///< second block
  int group_law = -1;         ///< the group rules' law for the pair (-1: none)
  std::int32_t contact = -1;  ///< index of the pair's state in contacts_, or -1
  /// Warm start of the narrow phase between steps. Its last byte is padding, which the flags
  /// below take (no_unique_address lets them into its tail): 120 bytes per slot, not 128.
  [[no_unique_address]] NarrowWarmStart narrow_cache;
  // One byte of bit-fields: a slot's flags are written by the one thread that has the slot.
  /// The pair's bond while it has no contact state (a bond that broke stays broken). Two
  /// bits: BondState's values run to 3.
  BondState bond : 2 = BondState::intact;
  bool broke : 1 = false;    ///< the pair's bond broke in this step
  bool active : 1 = false;   ///< a force acts (the contact is in contacts())
  bool pending : 1 = false;  ///< this step's new contact state waits in pending_
};
// The pair store is the largest array of a large scene with the contact store: a change of
// size must be deliberate (bench/README.md, "Memory at 1e5 blocks"; "The contact and pair
// stores at 1e5 blocks, slimmer").
static_assert(sizeof(NarrowWarmStart) == 104 && sizeof(PairSlot) == 120,
              "the pair slot changed size");

}  // namespace blockdem
