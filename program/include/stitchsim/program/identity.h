#pragma once
// What a programme says about itself in its STITCHSIM header (program-format.md section 6),
// typed: the scene and head it was written for, what it plans (path, raster, ply or course)
// and its sizes. The planners write it through WriteIdentity and check / verify read it
// through ReadIdentity, over one key table (identity.cpp), so a key is spelled once. A
// malformed value is a diagnostic, never a silent fallback.

#include <optional>
#include <string>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/program/reader.h"

namespace stitchsim::program {

/// The typed header keys; each is nullopt when the header does not give it. Written in the
/// order of the fields below.
struct ProgramIdentity {
  std::optional<std::string> scene;        ///< name of the scene it was written for
  std::optional<std::string> head;         ///< name of the head it was written for
  std::optional<std::string> path;         ///< plan stitch: the scene path it stitches
  std::optional<std::string> mode;         ///< plan stitch: coupled | decoupled | auto
  std::optional<std::string> raster;       ///< plan raster: the strategy, jump | serpentine
  std::optional<std::string> ply;          ///< plan ply, one ply: its name
  std::optional<std::string> plies;        ///< plan ply, several plies: names, comma separated
  std::optional<std::string> laminate;     ///< plan laminate: the scene laminate's name
  std::optional<std::string> course;       ///< plan afp: the course's name
  std::optional<double> lay_angle_deg;     ///< plan afp by lay angle: to the u axis, degrees
  std::optional<double> angle_deg;         ///< plan ply: the ply angle, degrees
  std::optional<double> coverage_pct;      ///< plan ply: surface covered, % (written whole)
  std::optional<double> incline_deg;       ///< plan afp: head lean along the course, degrees
  std::optional<long> points;              ///< plan afp: course points, >= 0
  std::optional<double> course_length_mm;  ///< plan afp: course length, mm, >= 0
  std::optional<double> stitch_length_mm;  ///< drive advance per stitch cycle, mm, > 0
  std::optional<double> row_spacing_mm;    ///< plan raster: distance between rows, mm, > 0
  std::optional<long> heads;               ///< plan raster: heads the regions go to, >= 0
  std::optional<long> courses;             ///< plan ply: courses over all plies, >= 0
  std::optional<long> tows;                ///< plan ply: tows of the head's band, >= 0
  std::optional<long> stitches;            ///< stitch cycles the programme makes, >= 0
  friend bool operator==(const ProgramIdentity&, const ProgramIdentity&) = default;
};

/// Converts `header`'s typed keys. A value that is not a number of the right kind is
/// `gcode-bad-header` at its entry's line; nullopt then.
std::optional<ProgramIdentity> ReadIdentity(const ProgramHeader& header,
                                            const std::string& file_name, DiagnosticSink& sink);

/// The header of `id`: its keys that have a value, in the order of ProgramIdentity's fields.
/// Lengths and angles with six decimals ("5.000000"), coverage_pct whole ("50"), a value that
/// prints as zero without a sign; counts as whole numbers; text as it is.
ProgramHeader WriteIdentity(const ProgramIdentity& id);

}  // namespace stitchsim::program
