#pragma once
// Seed 002's figures, reproduced (docs/afp.md, "Seed 002 figures"): the computations shared by
// the `seed002_figures` executable (prints them beside the paper's) and the ctest test that
// asserts them. Lengths in mm, angles in degrees (the text boundary), times in seconds.

#include <filesystem>
#include <string>

namespace stitchsim::bench {

/// One method's accumulated figures over a family of offsets.
struct DriftFigures {
  double surface_length_mm = 0.0;  ///< eq. 3: length on the surface through P_1 .. P_n
  double drift_mm = 0.0;           ///< nominal d (n - 1) minus that length
  double eq2_total_mm = 0.0;       ///< sum of the eq. 2 estimates at those points
  double seconds = 0.0;            ///< CPU time of the offsets (not the measuring)
};

struct Seed002Figures {
  bool ok = false;
  std::string message;  ///< why not, when !ok

  // Eq. 2 on a circular section of radius 2d (a cylinder), d = 6.35 mm, the paper's method.
  double circle_measured_per_step_d = 0.0;  ///< (d - distance on the surface) / d, per step
  double circle_eq2_per_step_d = 0.0;       ///< eq. 2 / d

  // The seed's wing (scenes/naca_wing.yaml), d = 3.81 mm.
  double wing_d_mm = 3.81;
  int wing_offsets_upper = 0;  ///< from the leading edge towards the upper trailing edge
  int wing_offsets_lower = 0;  ///< and towards the lower one
  int wing_points_per_curve = 0;
  double wing_station_y_mm = 0.0;  ///< span station of the measured points (the root end)
  double wing_nominal_mm = 0.0;    ///< d (790 - 1)
  DriftFigures wing_paper;
  DriftFigures wing_corrected;

  // Laminate family: plane, concentric offset circles R 635 mm, d 6.35 mm, theta 30 deg.
  double eq4_deg = 0.0;                   ///< eq. 4
  double laminate_paper_deg = 0.0;        ///< the paper's construction: arrival error at curve 2
  double laminate_paper_worst_deg = 0.0;  ///< the curve's worst crossing error
  double laminate_corrected_worst_deg = 0.0;  ///< corrected construction: worst crossing error

  // Inflected surface z = y^3 / 20 (mm), 124 offsets of d = 0.150.
  DriftFigures inflected_paper;
  DriftFigures inflected_corrected;
};

/// Computes every figure; the wing from `naca_wing_scene` through the scene loader.
Seed002Figures ComputeSeed002Figures(const std::filesystem::path& naca_wing_scene);

}  // namespace stitchsim::bench
