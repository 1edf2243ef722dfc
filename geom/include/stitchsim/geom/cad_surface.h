#pragma once
// CAD surfaces backed by the OpenCASCADE kernel (linked privately: no OCCT type appears
// here). A B-spline / NURBS patch from its control net, or one face of a STEP or IGES part.
// The (u, v) domain is in millimetres: the kernel's parameters are scaled linearly so that
// u runs over [0, Lu] and v over [0, Lv], Lu and Lv the lengths of the middle iso-curves.
// Constructors never throw: a kernel failure comes back as an error string.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "stitchsim/geom/surface.h"

namespace stitchsim::geom {

/// A (rational) B-spline surface. poles[i][j]: row i along u, column j along v (mm).
struct BSplineSpec {
  std::vector<std::vector<Eigen::Vector3d>> poles;
  std::vector<std::vector<double>> weights;  ///< same shape as poles, or empty (non-rational)
  int degree_u = 1;
  int degree_v = 1;
  /// Distinct knots and their multiplicities; both empty = clamped uniform.
  std::vector<double> knots_u, knots_v;
  std::vector<int> mults_u, mults_v;
  /// Normal = -(dP/du x dP/dv) instead of +(dP/du x dP/dv).
  bool flip_normal = false;
};

/// The B-spline surface of `spec`, or nullptr with `error` set (inconsistent counts,
/// non-finite numbers, weights <= 0, knots not increasing, a degenerate patch).
std::unique_ptr<Surface> MakeBSplineSurface(const BSplineSpec& spec, std::string& error);

enum class CadFormat { kStep, kIges };

/// Which face of a part file: by index (from 0, in the order the file's shape lists its
/// faces) when `name` is empty, else the first face carrying that name (STEP only).
struct CadFaceRef {
  int index = 0;
  std::string name;
  bool flip_normal = false;  ///< normal opposite to the face's outward orientation
};

/// One face of a STEP or IGES file, read in millimetres (the file's own units honoured).
/// nullptr with `error` set for a missing, empty or unreadable file, a file without faces,
/// or a face index / name that is not there.
std::unique_ptr<Surface> ReadCadFace(const std::filesystem::path& file, CadFormat format,
                                     const CadFaceRef& face, std::string& error);

/// Writes each spec as one face of a STEP or IGES file (lengths in `unit`: "MM", "CM", "M",
/// "INCH"; the file states its unit). In STEP, face i carries names[i] when given. False
/// with `error` set. For test fixtures and exports.
bool WriteBSplineCad(const std::vector<BSplineSpec>& faces, const std::vector<std::string>& names,
                     const std::filesystem::path& file, CadFormat format, const std::string& unit,
                     std::string& error);

}  // namespace stitchsim::geom
