#pragma once
// What a programme says about itself in its STITCHSIM header (program-format.md section 6),
// typed and checked once: the scene and head it was written for, its stitch length and how
// many stitches it makes. A malformed value is a diagnostic, never a silent fallback.

#include <optional>
#include <string>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/program/reader.h"

namespace stitchsim::program {

/// The typed header keys; each is nullopt when the header does not give it.
struct ProgramIdentity {
  std::optional<std::string> scene;        ///< name of the scene it was written for
  std::optional<std::string> head;         ///< name of the head it was written for
  std::optional<double> stitch_length_mm;  ///< drive advance per stitch cycle, mm, > 0
  std::optional<long> stitches;            ///< stitch cycles the programme makes, >= 0
};

/// Converts `header`'s typed keys. A value that is not a number of the right kind is
/// `gcode-bad-header` at its entry's line; nullopt then.
std::optional<ProgramIdentity> ReadIdentity(const ProgramHeader& header,
                                            const std::string& file_name, DiagnosticSink& sink);

}  // namespace stitchsim::program
