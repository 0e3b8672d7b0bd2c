// One joint law per face: a block's planes can carry their own joint law (the joint set that
// made the face); a contact takes its law from the faces in contact, else from the group rules.
#pragma once

#include <span>
#include <vector>

#include "blockdem/collision/contact_geometry.hpp"
#include "blockdem/dynamics/block.hpp"

namespace blockdem {

/// The face of `block` that meets a contact: the plane best aligned with `outward` (the
/// contact normal seen from this block) among those passing within `reach` (m) of the contact
/// point; any plane when none does. Returns the plane index and its alignment n_i·outward.
std::pair<int, double> contact_face(const Block& block, const Eigen::Vector3d& outward,
                                    const Eigen::Vector3d& point, double reach);

/// The joint law of a contact between blocks a and b from their per-plane laws (-1: none of
/// its own; an empty list: no face laws). When both faces name a law, the better-aligned face
/// wins (a on a tie): a face-to-face contact between two cut blocks has the same law on both
/// sides. Without a face law: `group_law` (the group rules' answer, -1 for none).
int face_law_for_contact(const Block& a, std::span<const int> laws_a, const Block& b,
                         std::span<const int> laws_b, const ContactGeometry& g, int group_law);

}  // namespace blockdem
