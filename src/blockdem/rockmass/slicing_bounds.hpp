// The work a rock mass's joint sets would cause, estimated before any joint is placed: a rock
// mass that would not fit in memory or time is refused with the set, the estimate and the limit.
#pragma once

#include "blockdem/rockmass/convex_cell.hpp"
#include "blockdem/rockmass/rock_slicer.hpp"

namespace blockdem {

/// Upper bounds of what slicing `region` by the spec's joint sets makes (joint planes, joints,
/// blocks), from each set's mean spacing and extent.
///
/// Blocks: k families of parallel planes, N_i planes in family i, divide space into at most
/// e_0 + e_1 + e_2 + e_3 convex cells, e_j the elementary symmetric sums of the N_i (the
/// regions of a plane arrangement in 3D, Zaslavsky 1975, counted over the independent subsets
/// of at most three planes; the product of (1 + N_i) for up to three families). Each set is
/// one family: a non-persistent set's joints lie on its planes and cut through whole blocks,
/// so they make no more blocks than its planes would. Excavation outlines are not counted
/// (they add blocks only along them).
///
/// Joints of a non-persistent set: on each plane, persistence × (its section of the region) /
/// (one joint's area), and no section of a convex region of diameter D exceeds π D²/4.
///
/// Throws std::invalid_argument "joint_sets[I].KEY: REASON" naming the set, the estimate and
/// the limit when the blocks exceed settings.max_blocks, a set's joints settings.max_joints, or
/// a set's spacings to draw kMaxSpacingDraws.
void check_slicing_work(const RockMassSpec& spec, const ConvexCell& region);

}  // namespace blockdem
