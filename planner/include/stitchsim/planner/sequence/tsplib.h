#pragma once
// TSPLIB instances (G. Reinelt, TSPLIB95; bench/data/tsplib/) as sequencing problems: the
// public instances with published optima that the course-ordering solver is measured against
// (issue 28). Reads the symmetric (TSP) and asymmetric (ATSP) files, their distances computed
// as TSPLIB defines them (integers), and the optimal tours (*.opt.tour).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/planner/sequence/solver.h"

namespace stitchsim::planner {

/// One TSPLIB instance. Filled by ReadTsplib; immutable afterwards.
struct TsplibInstance {
  std::string name;       ///< NAME of the file
  bool symmetric = true;  ///< TYPE: TSP (true) or ATSP (false)
  int dimension = 0;      ///< cities, numbered 1..dimension in the file, 0..dimension-1 here
  /// dimension^2 TSPLIB distances (integer-valued), row-major: distance[i * dimension + j] from
  /// city i to city j (0-based). The diagonal is as the file gives it (ATSP files put a large
  /// number there) and is never used by a tour.
  std::vector<double> distance;
  double Distance(int from, int to) const {
    return distance[static_cast<std::size_t>(from) * static_cast<std::size_t>(dimension) +
                    static_cast<std::size_t>(to)];
  }
};

/// Parses a TSPLIB file's text; `file` names it in diagnostics ("file:line: ..."). Supported:
/// TYPE TSP / ATSP; EDGE_WEIGHT_TYPE EUC_2D (nint), CEIL_2D, ATT (pseudo-Euclidean), EXPLICIT
/// with EDGE_WEIGHT_FORMAT FULL_MATRIX, UPPER_ROW, LOWER_ROW, UPPER_DIAG_ROW, LOWER_DIAG_ROW.
/// Bad input (unknown keyword or type, wrong count of numbers, a number that is not finite,
/// a missing section) reports to `sink` and gives nullopt.
std::optional<TsplibInstance> ParseTsplib(std::string_view text, const std::string& file,
                                          DiagnosticSink& sink);
/// Reads and parses the file at `path` (a missing or unreadable file is a diagnostic too).
std::optional<TsplibInstance> ReadTsplib(const std::string& path, DiagnosticSink& sink);

/// Parses a TSPLIB tour (TYPE TOUR, TOUR_SECTION ending in -1): the cities, 0-based, in
/// order. Checks that it visits each of `dimension` cities exactly once.
std::optional<std::vector<int>> ParseTsplibTour(std::string_view text, const std::string& file,
                                                int dimension, DiagnosticSink& sink);
std::optional<std::vector<int>> ReadTsplibTour(const std::string& path, int dimension,
                                               DiagnosticSink& sink);

/// Length of the closed tour through `cities` (0-based), back to its first city.
double TourLength(const TsplibInstance& instance, const std::vector<int>& cities);

/// The instance as one precedence set with a MoveTable: city 0 (TSPLIB's city 1) is the start
/// and the finish, city c >= 1 is course c - 1, a course of zero length (laid backwards it costs
/// the same as forwards). PathCost of an order equals TourLength of 0 followed by the courses'
/// cities.
SequenceProblem TsplibProblem(const TsplibInstance& instance, bool bidirectional);

/// The cities (0-based, starting at city 0) of an order of TsplibProblem's courses.
std::vector<int> TsplibTour(const std::vector<Visit>& order);

/// One line of bench/data/tsplib/optima.txt: an instance's published optimal tour length.
struct TsplibOptimum {
  std::string name;       ///< instance NAME
  bool symmetric = true;  ///< TSP or ATSP
  double optimum = 0.0;   ///< published optimal tour length, TSPLIB distance units
};
/// Reads optima.txt ("name TSP|ATSP length" a line, '#' comments); bad lines are diagnostics.
std::optional<std::vector<TsplibOptimum>> ReadTsplibOptima(const std::string& path,
                                                           DiagnosticSink& sink);

}  // namespace stitchsim::planner
