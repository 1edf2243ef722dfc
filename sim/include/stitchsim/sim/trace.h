#pragma once
// sim's names for the trace types (stitchsim/trace/trace.h), which the executor produces.

#include "stitchsim/sim/kinematics.h"
#include "stitchsim/trace/trace.h"

namespace stitchsim::sim {

using trace::LineRecord;
using trace::SampleEvent;
using trace::TraceSample;
using trace::TraceSink;

}  // namespace stitchsim::sim
