// ParaView-ready output: VTK XML unstructured grids (.vtu, binary appended data) of the blocks
// and the contacts at one time level, and .pvd collections that give each frame its model time.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "blockdem/world/world.hpp"

namespace blockdem {

/// Contact status written to VTK and documented in docs/outputs.md.
enum class ContactStatus { closed = 0, open = 1, sliding = 2, broken = 3 };
/// broken (the bond has broken) before sliding (the shear law yielded in the last step) before
/// open (no compression) before closed.
ContactStatus contact_status(const Contact& contact);

/// Writes every block as a VTK polyhedron cell at the world's level state (World::level_state)
/// with cell data block_id, name, group, stage, displacement (m), velocity (m/s), rotation (the
/// rotation vector since the start, rad) and angular_velocity (rad/s), and the field TimeValue,
/// the model time of that level (World::level_time, s).
void write_vtu_blocks(const std::filesystem::path& path, const World& world, int stage);

/// Writes every contact as a vertex at its force point with point data block_a, block_b, normal,
/// normal_force (N), shear_force (N, vector on block b), normal_stress (Pa), closure (m), area (m²)
/// and status (ContactStatus), and the field TimeValue (World::level_time, s).
void write_vtu_contacts(const std::filesystem::path& path, const World& world);

/// Writes every bolt as lines, one cell per tendon element (one for a point-anchored bolt),
/// at the blocks' present poses, with cell data bolt (its index), axial_force (N, tension
/// positive) and state (Bolt::State: 0 intact, 1 yielded, 2 ruptured, 3 removed; a removed
/// bolt where it was installed), and the field TimeValue (s).
void write_vtu_bolts(const std::filesystem::path& path, const World& world);

/// A frame of a run spread over processes (WorldSettings::distribution) is written in pieces,
/// one per process, and a parallel index (.pvtu) that names them: ParaView and VTK's
/// vtkXMLPUnstructuredGridReader open the index as one data set. The pieces have the fields of
/// the whole frames above.
/// The piece of process `process`: the blocks it owns (World::block_owners; every block is
/// process 0's before the first partition), in increasing index. Needs only those blocks' states
/// (the world need not be whole). Returns the cell count.
std::size_t write_vtu_block_piece(const std::filesystem::path& path, const World& world, int stage,
                                  int process);
/// The piece of process `process` of the contacts: those of the pairs it owns
/// (world/pair_owner.hpp), in (a, b) order. Needs only those contacts (World::counted_contacts:
/// the world need not be whole). Returns the contact count.
std::size_t write_vtu_contact_piece(const std::filesystem::path& path, const World& world,
                                    int process);
/// The .pvtu index of a block frame or a contact frame: the arrays the pieces carry and the
/// pieces' files (`pieces`: relative to the index's folder).
void write_pvtu_blocks(const std::filesystem::path& path, const World& world,
                       const std::vector<std::string>& pieces);
void write_pvtu_contacts(const std::filesystem::path& path, const World& world,
                         const std::vector<std::string>& pieces);

/// A .pvd collection: one DataSet per frame with its model time. Rewritten whole after each
/// add(), so the file on disk always lists every frame written so far.
class PvdCollection {
 public:
  explicit PvdCollection(std::filesystem::path path) : path_(std::move(path)) {}
  /// `file`: the frame's path relative to the .pvd's folder. Throws std::runtime_error when the
  /// file cannot be written.
  void add(double time, const std::string& file);
  /// Lists a frame without writing the file (a process that does not write the outputs keeps
  /// the same list).
  void remember(double time, const std::string& file) { frames_.emplace_back(time, file); }
  /// The frames listed so far (model time, file), e.g. to continue the collection after a restart.
  const std::vector<std::pair<double, std::string>>& frames() const { return frames_; }
  /// Continues a collection that already lists `frames` (the file is not rewritten until add()).
  void set_frames(std::vector<std::pair<double, std::string>> frames) {
    frames_ = std::move(frames);
  }

 private:
  std::filesystem::path path_;
  std::vector<std::pair<double, std::string>> frames_;
};

}  // namespace blockdem
