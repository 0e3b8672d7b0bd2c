// Joints prestressed by an in-situ stress field at set-up: for every pair of blocks that share a
// face, the closure its normal law needs to carry the field's normal traction, its shear force and
// twisting moment (response/in_situ.hpp), kept in block A's body frame.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "blockdem/response/in_situ.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

std::size_t World::prestress_joints(const StressField& field,
                                    const std::vector<std::pair<int, int>>& pairs) {
  if (const std::string why = field.problem(); !why.empty())
    throw std::invalid_argument("the in-situ stress " + why);
  const std::int64_t n = static_cast<std::int64_t>(pairs.size());
  std::vector<std::optional<ContactPreload>> found(pairs.size());
  std::vector<std::string> errors(pairs.size());
  const int threads = thread_count();
#pragma omp parallel for num_threads(threads) schedule(dynamic, 64) if (threads > 1 && n > 64)
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
      const FaceTraction t = face_traction(field, face->polygon, face->normal);
      const LinearClosure c = closure_for_traction(normal, face->polygon, face->normal, t);
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
      p.shear_force = to_body * t.shear_force(face->normal);
      p.twisting_moment = t.twisting_moment(face->normal);
      found[static_cast<std::size_t>(k)] = p;
    } catch (const std::invalid_argument& e) {
      std::ostringstream s;
      s << "the joint between blocks \"" << a.name << "\" and \"" << b.name << "\" (law \""
        << laws_[static_cast<std::size_t>(law)].name << "\"): " << e.what();
      errors[static_cast<std::size_t>(k)] = s.str();
    }
  }
  // The first failing pair in (a, b) order, whatever the thread count.
  for (const std::string& e : errors) {
    if (!e.empty()) throw std::invalid_argument(e);
  }
  std::vector<ContactPreload> list;
  for (auto& p : found) {
    if (p) list.push_back(*p);
  }
  preloads_.assign(std::move(list));
  return preloads_.size();
}

}  // namespace blockdem
