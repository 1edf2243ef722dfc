// Seed 002's figures beside the paper's (docs/afp.md, "Seed 002 figures"). Run the Release
// build from anywhere: build/bench/seed002_figures [scene]  (default scenes/naca_wing.yaml of
// the data folder). Exit 0, or 1 with a message when a figure cannot be computed.
#include "seed002_figures.h"

#include <cstdio>
#include <string>

#include "stitchsim/common/files.h"

int main(int argc, char** argv) {
  using stitchsim::bench::DriftFigures;
  const std::filesystem::path scene =
      argc > 1 ? std::filesystem::path(argv[1]) : stitchsim::DataDir() / "scenes/naca_wing.yaml";
  const auto f = stitchsim::bench::ComputeSeed002Figures(scene);
  if (!f.ok) {
    std::fprintf(stderr, "seed002_figures: %s\n", f.message.c_str());
    return 1;
  }
  const double d = f.wing_d_mm;
  const int offsets = f.wing_offsets_upper + f.wing_offsets_lower;
  std::printf("Seed 002 figures (stitchsim beside the paper)\n\n");
  std::printf(
      "1. Eq. 2, circular section of radius 2d (d 6.35 mm), the paper's offset, per step\n");
  std::printf("   measured on the surface %.4f d, eq. 2 %.4f d      paper: 0.073 d\n\n",
              f.circle_measured_per_step_d, f.circle_eq2_per_step_d);
  std::printf("2. The wing, %s: %d offsets of d %.2f mm, %d points\n", scene.string().c_str(),
              offsets, d, offsets + 1);
  std::printf(
      "   geometry: no sweep, dihedral or twist (scene); reference = the leading edge\n"
      "   (the fiber axis x = -200, z = 0 from y = 100 to 3100 mm, projected along +x);\n"
      "   %d offsets over the upper skin and %d over the lower, both from the leading\n"
      "   edge; the points are the curves' root ends (y = %.0f mm); %d points a curve\n",
      f.wing_offsets_upper, f.wing_offsets_lower, f.wing_station_y_mm, f.wing_points_per_curve);
  std::printf("   nominal length d (n - 1) = %.3f mm               paper: 3006.09 mm\n",
              f.wing_nominal_mm);
  const auto row = [](const char* what, const DriftFigures& r, double step, const char* paper) {
    std::printf(
        "   %-10s length %.4f, drift %.3g (%.3g %% of d), eq. 2 total %.3g (%.3g %% of "
        "d)\n              %s\n",
        what, r.surface_length_mm, r.drift_mm, r.drift_mm / step * 100, r.eq2_total_mm,
        r.eq2_total_mm / step * 100, paper);
  };
  row("paper's", f.wing_paper, d,
      "paper: length 3005.91 mm, drift 0.18 mm (4.7 %), eq. 2 total 0.24 mm (6.2 %)");
  row("corrected", f.wing_corrected, d, "target: drift < 0.1 % of d");
  std::printf(
      "   (eq. 2 reads the normals of the points placed: for the corrected offset it\n"
      "   estimates what the paper's construction would lose, not the drift)\n\n");
  std::printf("3. Laminate family, d 6.35 mm, R 635 mm, theta 30 deg\n");
  std::printf("   eq. 4 %.3f deg (theta minus the arrival angle: it arrives steeper)\n", f.eq4_deg);
  std::printf("   paper's construction: arrives %.3f deg off theta, the curve's worst %.3f deg\n",
              f.laminate_paper_deg, f.laminate_paper_worst_deg);
  std::printf("   corrected: worst crossing %.4f deg\n", f.laminate_corrected_worst_deg);
  std::printf("              paper: about 1.0 deg; target < 0.05 deg\n\n");
  std::printf("4. Inflected surface z = y^3 / 20 (radius down to 2.5 mm), 124 offsets of 0.150\n");
  row("paper's", f.inflected_paper, 0.150,
      "paper (its own, sharper surface): drift 0.050 (33.3 %), eq. 2 total 0.0508 (33.9 %)");
  row("corrected", f.inflected_corrected, 0.150, "target: drift < 0.1 % of d");
  std::printf("\n5. Timing, %d offsets on the wing (%d points a curve), CPU time:\n", offsets,
              f.wing_points_per_curve);
  for (const auto* r : {&f.wing_paper, &f.wing_corrected}) {
    std::printf("   %-10s %.3f s, %.0f offsets/s      target: 790 offsets < 1 s\n",
                r == &f.wing_paper ? "paper's" : "corrected", r->seconds, offsets / r->seconds);
  }
  return 0;
}
