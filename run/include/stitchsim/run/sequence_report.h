#pragma once
// The report of `stitchsim sequence` (docs/sequence.md, "Report"), and the reader of the
// order it holds (`sequence --order`).
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/program/afp_program.h"
#include "stitchsim/run/sequence_run.h"

namespace stitchsim::run {

/// The JSON report: the run's settings, per set, per ply and overall costs, and the order chosen.
nlohmann::json SequenceReportJson(const SequenceOutcome& outcome,
                                  const program::AfpProgram& program);

/// SequenceReportJson written with one-space indentation.
void WriteSequenceJson(const SequenceOutcome& outcome, const program::AfpProgram& program,
                       std::ostream& out);

/// Reads an order (a report's "order" array: ply, course, reversed) from a JSON file and maps
/// it onto `program`'s courses; nullopt with `error` set (file, entry) when the file cannot be
/// read or is malformed, when a course is unknown, missing or repeated.
std::optional<std::vector<program::CourseVisit>> ReadOrderFile(const std::string& file,
                                                               const program::AfpProgram& program,
                                                               SequenceError& error);

}  // namespace stitchsim::run
