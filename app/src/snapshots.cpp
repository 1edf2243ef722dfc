#include "snapshots.h"

#include "commands.h"
#include "stitchsim/run/snapshots.h"

namespace stitchsim::app {

int WriteSnapshotFolder(const run::RunModel& vs, const verify::Verifier& verifier,
                        const verify::Report& report, const std::string& dir) {
  const run::SnapshotInputs in{&vs.loaded, vs.process.get(), &vs.description, &verifier, &report};
  DiagnosticSink sink;
  const run::Status status = run::WriteSnapshotFolder(in, dir, sink);
  return PrintRunOutcome(sink, status);
}

}  // namespace stitchsim::app
