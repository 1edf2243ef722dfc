#include "snapshots.h"

#include "commands.h"
#include "stitchsim/run/snapshots.h"

namespace stitchsim::app {

int WriteSnapshotFolder(const VerifySession& vs, const verify::Verifier& verifier,
                        const verify::Report& report, const std::string& dir) {
  const run::SnapshotInputs in{&vs.ls, vs.model.get(), &vs.description, &verifier, &report};
  DiagnosticSink sink;
  const run::Status status = run::WriteSnapshotFolder(in, dir, sink);
  return PrintRunOutcome(sink, status);
}

}  // namespace stitchsim::app
