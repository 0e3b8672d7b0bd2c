// Joint laws given anew between stages: by joint set or block group, a law or each face's elastic
// twin; the contacts keep their state and take the new law.
#include <map>
#include <stdexcept>
#include <string>

#include "blockdem/world/world.hpp"

namespace blockdem {

void World::set_face_sets(int block, std::span<const int> set_per_plane) {
  if (block < 0 || block >= static_cast<int>(blocks_.size()))
    throw std::invalid_argument("set_face_sets: no block " + std::to_string(block));
  if (set_per_plane.size() != blocks_[block].shape.planes().size())
    throw std::invalid_argument("set_face_sets: block '" + blocks_[block].name +
                                "' has another number of planes");
  face_sets_.set(static_cast<std::size_t>(block), set_per_plane);
}

namespace {

// The index of the law named `name`, or -1.
int law_named(const std::vector<JointLaw>& laws, const std::string& name) {
  for (std::size_t i = 0; i < laws.size(); ++i) {
    if (laws[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

bool is_twin(const std::string& name) {
  return name.size() > kElasticSuffix.size() &&
         name.compare(name.size() - kElasticSuffix.size(), kElasticSuffix.size(), kElasticSuffix) ==
             0;
}

}  // namespace

void World::change_laws(const std::vector<LawChange>& changes) {
  // The new law of a face whose law is `old` (-1: the group rules' law of the block's own pair).
  const auto new_law = [&](const LawChange& c, int old, int block) {
    if (!c.elastic) return c.law;
    const int base = old >= 0 ? old : law_for(block, block);
    if (base < 0) return old;
    const std::string& name = laws_[static_cast<std::size_t>(base)].name;
    if (is_twin(name)) return base;
    const int twin = law_named(laws_, name + std::string(kElasticSuffix));
    if (twin < 0) throw std::invalid_argument("no elastic twin of joint law \"" + name + "\"");
    return twin;
  };
  for (const LawChange& c : changes) {
    if (!c.elastic && (c.law < 0 || c.law >= static_cast<int>(laws_.size())))
      throw std::invalid_argument("change_laws: unknown joint law " + std::to_string(c.law));
  }
  // Per block, the laws its faces left for others: a contact of the block with one of them
  // takes the other (the open bonds keep their law between steps).
  std::vector<std::map<int, int>> moved(blocks_.size());
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    const std::size_t planes = blocks_[i].shape.planes().size();
    for (const LawChange& c : changes) {
      const std::span<const int> sets = face_sets_.of(i);
      const bool whole = c.joint_set < 0 && blocks_[i].group() == c.group;
      if (!whole && (c.joint_set < 0 || sets.empty())) continue;
      const std::span<int> laws = face_laws_.edit(i, planes, -1);
      for (std::size_t j = 0; j < planes; ++j) {
        if (!whole && sets[j] != c.joint_set) continue;
        const int old = laws[j];
        const int law = new_law(c, old, static_cast<int>(i));
        if (law == old) continue;
        moved[i][old >= 0 ? old : law_for(static_cast<int>(i), static_cast<int>(i))] = law;
        laws[j] = law;
      }
    }
  }
  for (Contact& ct : contacts_) {
    for (const int block : {ct.a, ct.b}) {
      const auto it = moved[static_cast<std::size_t>(block)].find(ct.law);
      if (it != moved[static_cast<std::size_t>(block)].end()) {
        ct.law = it->second;
        break;
      }
    }
  }
}

void World::reset_displacements() {
  for (Block& b : blocks_) {
    b.initial_position = b.position;
    b.initial_orientation = b.orientation;
  }
}

}  // namespace blockdem
