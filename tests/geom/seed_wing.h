#pragma once
// Seed 002's wing for the tests: root NACA 23014, chord 225.81 cm; tip NACA 23012, chord
// 113.03 cm; span 731.01 cm; no sweep, dihedral or twist.

#include "stitchsim/common/units.h"
#include "stitchsim/geom/naca.h"

namespace stitchsim::geom::testing {

inline WingSpec SeedWingSpec() {
  WingSpec spec;
  spec.root_code = "23014";
  spec.root_chord_mm = 2258.1;
  spec.tip_code = "23012";
  spec.tip_chord_mm = 1130.3;
  spec.span_mm = 7310.1;
  return spec;
}

/// The seed's wing with the angles the paper leaves open set to values that test each term.
inline WingSpec SweptTwistedSeedWingSpec() {
  constexpr double deg = kDeg;
  WingSpec spec = SeedWingSpec();
  spec.sweep_rad = 12.0 * deg;
  spec.dihedral_rad = 4.0 * deg;
  spec.washout_rad = 3.0 * deg;
  return spec;
}

}  // namespace stitchsim::geom::testing
