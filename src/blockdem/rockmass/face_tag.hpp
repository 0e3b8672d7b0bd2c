// What made each face of a cut block: a region boundary, a joint of a set (open or bonded), or
// an excavation outline. The tag follows the face from the slicer into the world.
#pragma once

namespace blockdem {

enum class FaceSource {
  region,      ///< a face of the region's boundary
  joint,       ///< a cut by a joint of a joint set
  excavation,  ///< a cut along an excavation's outline
};

struct FaceTag {
  FaceSource source = FaceSource::region;
  /// region: the boundary plane's index; joint: the joint set's index; excavation: the
  /// excavation's index.
  int index = -1;
  /// joint / excavation: which joint of the set (or which outline facet) made the cut; -1 for
  /// a region face.
  int joint = -1;
  /// The face lies wholly or partly outside the joint's extent: intact rock (a rock bridge),
  /// not an open joint.
  bool bonded = false;

  bool operator==(const FaceTag&) const = default;
};

}  // namespace blockdem
