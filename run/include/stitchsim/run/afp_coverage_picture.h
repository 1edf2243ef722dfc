#pragma once
// The per-ply AFP coverage map (verify --snapshots: coverage_ply<n>.png; docs/report-format.md,
// "AFP coverage snapshots"): the ply's (u, v) plane with mm axes and a scale bar (u and v at one
// scale), the afp.coverage map (laid, gaps, overlaps, bare band, laid outside; gaps and
// overlaps thinner than a pixel enlarged), the laid material on it (course outlines, tow
// boundaries, fibre direction arrows, add and cut points), a title block (ply, angle, courses,
// tows laid, verdict, each afp rule's worst figure) and a legend.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "stitchsim/render/renderer.h"
#include "stitchsim/render/text.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::run {

/// One tick a picture's axis shows: the value its label prints (mm) and the pixel column (u
/// axis) or row (v axis) of the tick mark, in the picture.
struct AxisTick {
  double mm = 0.0;
  int pixel = 0;
};

/// One ply's coverage picture.
struct CoveragePicture {
  int ply = 0;       ///< M70 P<n>
  std::string name;  ///< the ply's name (the scene's)
  render::Image image;
  /// The title block's lines as drawn: the ply and its verdict; its angle, courses and tows
  /// laid; then the afp rules' worst figures.
  std::vector<std::string> title;
  std::vector<AxisTick> u_ticks;  ///< the u axis' ticks drawn, left to right
  std::vector<AxisTick> v_ticks;  ///< the v axis' ticks drawn, bottom to top
  double px_per_mm = 0.0;         ///< the map's scale, both axes (the scale bar's)
  double scale_bar_mm = 0.0;      ///< the scale bar's length, mm
};

/// The pictures of a finished verifier run, one per ply afp.coverage measured (empty when it
/// did not run); the laid material (Verifier::Laid(), empty without stitch marks) is drawn when
/// kept. `scene` is the run's (ply angles); `fonts` from render::OpenSnapshotFonts. The map
/// is as large as fits `map_px` (width, height; pixels) at one scale on u and v, at most 4 px
/// a mm; the title, axes and legend come around it.
std::vector<CoveragePicture> AfpCoveragePictures(const verify::Verifier& verifier,
                                                 const scene::Scene& scene,
                                                 const render::SnapshotFonts& fonts,
                                                 const Eigen::Vector2i& map_px = {1000, 900});

}  // namespace stitchsim::run
