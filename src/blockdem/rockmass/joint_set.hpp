// Joint sets as a rock engineer gives them: orientation (dip, dip direction), spacing (constant
// or drawn from a distribution with a seed), a point on one joint, and persistence.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace blockdem {

/// Spacing between neighbouring joints of a set, measured along the set's normal.
struct Spacing {
  enum class Distribution { constant, exponential, normal, lognormal };
  Distribution distribution = Distribution::constant;
  double mean = 1.0;                  ///< (m)
  double sd = 0.0;                    ///< standard deviation, normal and lognormal (m)
  std::optional<std::uint64_t> seed;  ///< required for every distribution but constant
};

/// The extent of one non-persistent joint in its plane: a disc or a rectangle centred on the
/// joint's centre (the rectangle's first side along strike, second along dip).
struct JointExtent {
  enum class Shape { disc, rectangle };
  Shape shape = Shape::disc;
  double radius = 0.0;                             ///< disc (m)
  Eigen::Vector2d size = Eigen::Vector2d::Zero();  ///< rectangle: along strike, along dip (m)
  double area() const;                             ///< (m^2)
};

struct JointSet {
  std::string name;
  double dip_deg = 0.0;            ///< in [0, 90] (degrees)
  double dip_direction_deg = 0.0;  ///< in [0, 360), clockwise from north (degrees)
  Spacing spacing;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< a point on one joint (m)
  std::string law;                                   ///< joint law name ("" = group rules)

  /// Absent: persistent joints (they cut every block they cross).
  std::optional<JointExtent> extent;
  /// Non-persistent: fraction of each joint plane's area (inside the region) covered by joints,
  /// placed at random positions drawn with `placement_seed` (-).
  double persistence = 0.5;
  std::optional<std::uint64_t> placement_seed;
  /// Non-persistent: explicit joint centres instead of planes from spacing and random
  /// positions (m). Each centre gives one joint on the plane through it.
  std::vector<Eigen::Vector3d> centres;

  /// Upward unit normal n = (sin δ sin α, sin δ cos α, cos δ) (x east, y north, z up).
  Eigen::Vector3d normal() const;
  /// Unit vector down the dip, in the joint plane (-).
  Eigen::Vector3d dip_vector() const;
  /// Unit horizontal vector along strike, in the joint plane (-).
  Eigen::Vector3d strike_vector() const;

  /// Throws std::invalid_argument "KEY: REASON" for an impossible value.
  void validate() const;
};

/// One joint: its plane (n·x = offset) and, when non-persistent, its centre and extent.
struct Joint {
  double offset = 0.0;  ///< n·x on the plane (m)
  bool persistent = true;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< non-persistent: centre (m)
};

/// The most spacings drawn to place one set's joints: a random spacing is drawn joint by joint
/// from the origin's joint, also across the gap between an origin outside the region and it.
constexpr double kMaxSpacingDraws = 1e8;

/// The work of placing a set's joint planes over [lo, hi] along its normal, from its mean
/// spacing, before any is placed.
struct JointPlaneEstimate {
  double planes = 0.0;  ///< joint planes crossing [lo, hi] (-)
  double draws = 0.0;   ///< spacings drawn to place them (a constant spacing draws none) (-)
};
JointPlaneEstimate estimate_joint_planes(const JointSet& set, double lo, double hi);

/// Offsets of the joint planes of a set covering [lo, hi] along its normal (m), ascending. A
/// constant spacing steps straight to the first plane in [lo, hi] from an origin outside it.
/// Throws std::invalid_argument "spacing: REASON" when a spacing does not advance the offset
/// (below the resolution of a double there), or when more than `max_planes` planes or
/// kMaxSpacingDraws draws would be needed: estimate_joint_planes says so beforehand.
std::vector<double> joint_plane_offsets(const JointSet& set, double lo, double hi,
                                        double max_planes = kMaxSpacingDraws);

/// A small, portable random source (SplitMix64): the same seed gives the same numbers with any
/// compiler and standard library.
class PortableRandom {
 public:
  explicit PortableRandom(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  double uniform();      ///< in [0, 1)
  double exponential();  ///< unit mean
  double normal();       ///< standard normal (Box-Muller)

 private:
  std::uint64_t state_;
  std::optional<double> spare_;
};

}  // namespace blockdem
