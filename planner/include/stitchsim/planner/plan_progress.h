#pragma once
// How far a long planning run has got, for a caller that shows it (the app prints it through
// common/progress.h on stderr). The planners never print.

#include <functional>

namespace stitchsim::planner {

/// Called on the planning thread with the work done so far and the total, both in the
/// planner's unit (stitches, rows, courses; its options say which); `done` only grows. `total`
/// is 0 when it is not known in advance. Null (the default): never called, nothing changes.
using PlanProgress = std::function<void(double done, double total)>;

}  // namespace stitchsim::planner
