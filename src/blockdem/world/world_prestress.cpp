// Joints prestressed by an in-situ stress field at set-up: for every pair of blocks that share a
// face, the closure its normal law needs to carry the field's normal traction, its shear force and
// twisting moment (response/in_situ.hpp), kept in block A's body frame.
#include <algorithm>
#include <cstdint>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/response/in_situ.hpp"
#include "blockdem/world/pass_support.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

std::size_t World::prestress_joints(const StressField& field,
                                    const std::vector<std::pair<int, int>>& pairs) {
  if (const std::string why = field.problem(); !why.empty())
    throw std::invalid_argument("the in-situ stress " + why);
  const std::int64_t n = static_cast<std::int64_t>(pairs.size());
  // Each thread lists the prestresses it found and its first failing pair: the list is sorted by
  // (a, b) when it is assigned, and the failure reported is the first in the pairs' order, so
  // neither depends on the thread count. (Not a result per candidate pair: 152 bytes each, most
  // of them empty, for the millions of pairs of a large rock mass.)
  const int threads = std::max(thread_count(), 1);
  std::vector<std::vector<ContactPreload>> found(static_cast<std::size_t>(threads));
  std::vector<std::pair<std::int64_t, std::string>> failed(static_cast<std::size_t>(threads),
                                                           {n, std::string()});
#pragma omp parallel num_threads(threads) if (threads > 1 && n > 64)
  {
    const auto t = static_cast<std::size_t>(pass_support::team_rank());
    std::vector<ContactPreload>& mine = found[t];
    // Room for a joint in every third pair of the thread's share (a rock mass's blocks share a
    // face with about one neighbour in four): address space only until it is written, and no
    // copies of a list grown by doubling.
    mine.reserve(static_cast<std::size_t>(n / threads / 3 + 16));
    pass_support::prefer_huge_pages(mine.data(), mine.capacity() * sizeof(ContactPreload));
#pragma omp for schedule(dynamic, 64)
    for (std::int64_t k = 0; k < n; ++k) {
      const auto [i, j] = pairs[static_cast<std::size_t>(k)];
      if (!steps_pair(i, j)) continue;
      const Block& a = blocks_[static_cast<std::size_t>(i)];
      const Block& b = blocks_[static_cast<std::size_t>(j)];
      const auto face = shared_face_of(a, b);
      if (!face) continue;
      const int law = shared_face_law(i, j, *face, law_for(i, j));
      if (law < 0) continue;
      const NormalLaw& normal = laws_[static_cast<std::size_t>(law)].normal;
      try {
        const FaceTraction t_face = face_traction(field, face->polygon, face->normal);
        const LinearClosure c = closure_for_traction(normal, face->polygon, face->normal, t_face);
        ContactPreload p;
        p.a = i;
        p.b = j;
        p.plane_a = face->plane_a;
        p.plane_b = face->plane_b;
        p.shift = 0.0;
        for (const Eigen::Vector3d& x : face->polygon) p.shift = std::max(p.shift, c.at(x));
        // In A's body frame.
        const Eigen::Matrix3d to_body = a.rotation().transpose();
        p.point = to_body * (c.point - a.position);
        p.closure = c.value;
        p.gradient = to_body * c.gradient;
        p.shear_force = to_body * t_face.shear_force(face->normal);
        p.twisting_moment = t_face.twisting_moment(face->normal);
        mine.push_back(p);
      } catch (const std::invalid_argument& e) {
        if (k < failed[t].first) {
          std::ostringstream s;
          s << "the joint between blocks \"" << a.name << "\" and \"" << b.name << "\" (law \""
            << laws_[static_cast<std::size_t>(law)].name << "\"): " << e.what();
          failed[t] = {k, s.str()};
        }
      }
    }
  }
  // The first failing pair in (a, b) order, whatever the thread count.
  const auto first = std::min_element(
      failed.begin(), failed.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  if (first->first < n) throw std::invalid_argument(first->second);
  // Each thread took its chunks of pairs in increasing order, so its list is sorted by (a, b):
  // the lists are merged, not joined and sorted.
  const auto by_pair = [](const ContactPreload& x, const ContactPreload& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  };
  std::vector<ContactPreload> list = std::move(found[0]);
  for (std::size_t t = 1; t < found.size(); ++t) {
    std::vector<ContactPreload> merged;
    merged.reserve(list.size() + found[t].size());
    pass_support::prefer_huge_pages(merged.data(), merged.capacity() * sizeof(ContactPreload));
    std::merge(list.begin(), list.end(), found[t].begin(), found[t].end(),
               std::back_inserter(merged), by_pair);
    std::vector<ContactPreload>().swap(found[t]);
    list.swap(merged);
  }
  preloads_.assign(std::move(list));
  return preloads_.size();
}

}  // namespace blockdem
