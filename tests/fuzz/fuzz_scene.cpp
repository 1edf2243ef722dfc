// Fuzz target: the scene loader. LoadScene takes a path, so each input is written as
// scene.yaml into a scratch folder that also holds part.stl (a two-triangle plate), so mesh
// surfaces and constraints that name it load too. Heads resolve to models/heads.
// Properties: a scene comes back exactly when no error was reported; every diagnostic has a
// known code family.

#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "stitchsim/geom/stl.h"
#include "stitchsim/scene/scene.h"

namespace {

void WritePlateStl() {
  static const bool written = [] {
    stitchsim::geom::TriangleMesh plate;
    plate.vertices = {{0, 0, 0}, {100, 0, 0}, {100, 100, 0}, {0, 100, 0}};
    plate.triangles = {{0, 1, 2}, {0, 2, 3}};
    std::string error;
    const bool ok =
        stitchsim::geom::WriteStl(stitchsim::fuzz::ScratchDir() / "part.stl", plate, error);
    stitchsim::fuzz::Require(ok, error);
    return ok;
  }();
  (void)written;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stitchsim;
  WritePlateStl();
  const auto path = fuzz::WriteScratch("scene.yaml", data, size);
  DiagnosticSink sink;
  const auto loaded = scene::LoadScene(path, sink);
  fuzz::RequireCodes(sink, {"scene-", "head-"});
  fuzz::Require((loaded != nullptr) == !sink.HasErrors(),
                "a scene came back with errors, or none without one", &sink);
  return 0;
}
