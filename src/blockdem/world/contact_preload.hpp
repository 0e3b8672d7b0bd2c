// Joint contacts prestressed at set-up by an in-situ stress field: per pair of blocks that share a
// face, the closure its normal law needs to carry the field's normal traction there, and the
// field's shear force and twisting moment, all held in block A's body frame.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "blockdem/collision/face_contact.hpp"
#include "blockdem/dynamics/block.hpp"

namespace blockdem {

/// A pair's prestress: the joint's closure is the blocks' own overlap across the shared face plus
/// the closure of the field, linear over the face. The narrow phase that finds the contact sees
/// A's face plane `plane_a` moved out by `shift` (the largest closure over the face), so that the
/// blocks overlap while the joint is closed anywhere; the face contact's cells are those of the
/// shared face (collision/face_contact.hpp, ClosureOffset).
struct ContactPreload {
  int a = -1;          ///< first block (the normal points from a to b)
  int b = -1;          ///< second block
  int plane_a = -1;    ///< A's plane of the shared face
  int plane_b = -1;    ///< B's plane of the shared face
  double shift = 0.0;  ///< (m)
  // In A's body frame: the closure δ(x) = closure + gradient · (x - point) and the field's shear
  // force on B at the set-up.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();        ///< the face's centroid (m)
  double closure = 0.0;                                   ///< δ at point (m)
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();     ///< in the face (-)
  Eigen::Vector3d shear_force = Eigen::Vector3d::Zero();  ///< on B (N)
  double twisting_moment = 0.0;  ///< on B, about the face normal and its centroid (N m)

  /// The closure of the field over the face, in the world (m).
  ClosureOffset offset_in_world(const Block& block_a) const {
    ClosureOffset o;
    o.plane_a = plane_a;
    o.plane_b = plane_b;
    o.point = block_a.to_world(point);
    o.value = closure;
    o.gradient = block_a.rotation() * gradient;
    return o;
  }
};

/// The prestressed pairs of a world, sorted by (a, b), with the place of each block's first pair
/// as block A: a pair is found by a scan of its block's few pairs (a rock mass's block is A of
/// about three), not by a binary search over the whole list, whose steps would each miss the cache
/// in a large model (112 bytes per pair: 310 MB at a million blocks).
class ContactPreloads {
 public:
  bool empty() const { return list_.empty(); }
  std::size_t size() const { return list_.size(); }
  std::span<const ContactPreload> all() const { return list_; }

  /// Takes the pairs' prestresses (any order; one per pair).
  void assign(std::vector<ContactPreload> list) {
    list_ = std::move(list);
    const auto by_key = [](const ContactPreload& x, const ContactPreload& y) {
      return key(x) < key(y);
    };
    if (!std::is_sorted(list_.begin(), list_.end(), by_key))
      std::sort(list_.begin(), list_.end(), by_key);
    index();
  }
  /// The pair's prestress, or null.
  const ContactPreload* find(int a, int b) const {
    if (a < 0 || static_cast<std::size_t>(a) + 1 >= first_.size()) return nullptr;
    const std::size_t end = first_[static_cast<std::size_t>(a) + 1];
    for (std::size_t k = first_[static_cast<std::size_t>(a)]; k < end; ++k) {
      if (list_[k].b == b) return &list_[k];
    }
    return nullptr;
  }
  /// After blocks were removed: `new_index[i]` is block i's new index, -1 for a removed block
  /// (the order of the others is kept, so the list stays sorted).
  void renumber(const std::vector<int>& new_index) {
    std::size_t kept = 0;
    for (ContactPreload& p : list_) {
      const int a = new_index[static_cast<std::size_t>(p.a)];
      const int b = new_index[static_cast<std::size_t>(p.b)];
      if (a < 0 || b < 0) continue;
      p.a = a;
      p.b = b;
      list_[kept++] = p;
    }
    list_.resize(kept);
    index();
  }

 private:
  static std::pair<int, int> key(const ContactPreload& p) { return {p.a, p.b}; }
  /// first_[a] .. first_[a + 1]: the places of the pairs whose block A is a (the list is sorted).
  void index() {
    first_.clear();
    if (list_.empty()) return;
    first_.assign(static_cast<std::size_t>(list_.back().a) + 2, 0);
    for (const ContactPreload& p : list_) ++first_[static_cast<std::size_t>(p.a) + 1];
    for (std::size_t i = 1; i < first_.size(); ++i) first_[i] += first_[i - 1];
  }
  std::vector<ContactPreload> list_;
  std::vector<std::uint64_t> first_;
};

}  // namespace blockdem
