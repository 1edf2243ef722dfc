#pragma once
// The afp.coverage rule's maps as pictures (docs/afp.md, "Coverage"): one per ply the
// programme laid, a top view of the surface's (u, v) box, one pixel per cell or per block of
// cells (a block shows its worst state: doubled over bare over laid). For the AFP snapshot.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "stitchsim/verify/verifier.h"

namespace stitchsim::verify {

/// What a pixel shows.
enum class CoverageState : std::uint8_t {
  kNone = 0,     ///< outside the ply, nothing laid
  kLaid,         ///< laid once (inside or in the boundary band)
  kBare,         ///< inside the ply, nothing laid: a gap
  kDoubled,      ///< inside the ply, laid twice or more: an overlap
  kOutside,      ///< laid outside the ply
  kBoundaryBare  ///< inside, in the boundary band, nothing laid (the policy's gaps)
};

struct CoverageImage {
  int ply = 0;       ///< M70 P<n>
  std::string name;  ///< the ply's name
  int width = 0, height = 0;
  /// Row-major, row 0 at the largest v (top of the picture), column 0 at the smallest u.
  std::vector<CoverageState> pixels;
  Eigen::Vector2d lo_uv = Eigen::Vector2d::Zero(), hi_uv = Eigen::Vector2d::Zero();
};

/// The coverage pictures of a finished verifier run (empty when afp.coverage did not run),
/// each at most `max_side` pixels on its longer side.
std::vector<CoverageImage> CoverageImages(const Verifier& verifier, int max_side = 1600);

}  // namespace stitchsim::verify
