// The [rock_mass] scene builder.
#include "blockdem/rockmass/scene.hpp"

#include <exception>
#include <stdexcept>
#include <thread>
#include <unordered_set>

namespace blockdem {

const RockMassScene* rock_mass_scene(const Scenario& scenario) {
  return dynamic_cast<const RockMassScene*>(scenario.built.get());
}

void RockMassSceneBuilder::build(const CheckedTable&, Scenario&) const {
  throw std::logic_error("the [rock_mass] builder reads the root table: call build_from_root");
}

void RockMassSceneBuilder::build_from_root(const CheckedTable& root, Scenario& sc) const {
  std::map<std::string, int> laws;
  for (std::size_t i = 0; i < sc.joint_laws.size(); ++i)
    laws[sc.joint_laws[i].name] = static_cast<int>(i);
  auto scene = std::make_shared<RockMassScene>();
  scene->model = read_rock_mass(root, sc.materials, laws, sc.in_situ, cut_threads_);
  if (scene->model.default_law < 0 && sc.joint_laws.size() > 1) {
    root.fail("rock_mass.law",
              "several joint laws: name the law of faces without one of their own (e.g. the "
              "excavation outline)");
  }
  // The blocks are made on a thread of their own (and the threads it starts for them): glibc's
  // allocator gives a new thread an arena of its own, so the blocks' shapes, planes and names do
  // not fill the holes that the cut's temporaries left among the sliced cells. A run frees the
  // cells before it builds its world (their pages then go back to the system whole, not held by a
  // block's data in each); made among them, the 1e5-block rock mass of bench/memory_ranks.sh kept
  // 65 MB of freed cells resident (bench/scaling-log.md, "The set-up without every pair, and
  // blocks made apart from the cells"; `blockdem generate`, which holds both, peaks 4 % higher).
  // Another allocator changes only where the bytes are.
  RockMassBlocks made;
  std::exception_ptr error;
  std::thread([&] {
    try {
      made = make_rock_mass_blocks(scene->model);
    } catch (...) {
      error = std::current_exception();
    }
  }).join();
  if (error) std::rethrow_exception(error);
  // Face laws run parallel to the scenario's blocks; blocks given by hand have none.
  sc.face_laws.resize(sc.blocks.size());
  sc.face_sets.resize(sc.blocks.size());
  // Rock-mass names are distinct (rock_1, rock_2, ...): only the blocks given by hand can clash.
  std::unordered_set<std::string> hand_names;
  for (const auto& b : sc.blocks) hand_names.insert(b.name);
  const std::size_t rock_blocks = made.blocks.size();
  if (sc.blocks.empty()) {
    // The rock mass alone: its lists become the scenario's (no copy of a million blocks).
    sc.blocks = std::move(made.blocks);
    sc.face_laws = std::move(made.face_laws);
    sc.face_sets = std::move(made.face_sets);
    made.blocks.clear();
  }
  sc.blocks.reserve(sc.blocks.size() + made.blocks.size());
  sc.face_laws.reserve(sc.blocks.size() + made.blocks.size());
  sc.face_sets.reserve(sc.blocks.size() + made.blocks.size());
  for (std::size_t i = 0; i < made.blocks.size(); ++i) {
    if (hand_names.count(made.blocks[i].name) != 0) {
      root.fail("blocks",
                "block \"" + made.blocks[i].name + "\" clashes with a rock-mass block name");
    }
    sc.blocks.push_back(std::move(made.blocks[i]));
    sc.face_laws.push_back(std::move(made.face_laws[i]));
    sc.face_sets.push_back(std::move(made.face_sets[i]));
  }
  for (auto& [name, blocks] : made.excavated) {
    // Removing nothing is refused when the rock mass is cut; removing every block leaves a run
    // with no rock (a half-space of the wrong sign does that).
    if (blocks.size() == rock_blocks)
      sc.warnings.push_back("excavation \"" + name + "\" removes every block of the rock mass (" +
                            std::to_string(rock_blocks) +
                            "): check its outline (a plane's sign, a slope's dip direction)");
    sc.excavations[name] = std::move(blocks);
  }
  if (scene->model.default_law >= 0)
    sc.joint_rules.push_back(JointRule{"", "", scene->model.default_law});
  for (const auto& set : scene->model.spec.joint_sets) sc.joint_sets.push_back(set.name);
  sc.built = std::move(scene);
}

}  // namespace blockdem
