// Fuzz target: the STL reader (ASCII and binary). ReadStl takes a path, so each input is
// written to a scratch file first.
// Properties: failure leaves the mesh untouched and says why; a mesh read has finite
// vertices and valid, non-degenerate triangles, and what WriteStl makes of it reads back as
// such a mesh or fails cleanly (float rounding may weld every triangle away).

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "stitchsim/geom/stl.h"

namespace stitchsim::fuzz {
namespace {

void CheckMesh(const geom::TriangleMesh& mesh) {
  Require(!mesh.triangles.empty(), "ReadStl succeeded with no triangles");
  for (const auto& v : mesh.vertices) Require(v.allFinite(), "non-finite vertex");
  const int n = static_cast<int>(mesh.vertices.size());
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) Require(t[k] >= 0 && t[k] < n, "triangle index out of range");
    Require(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], "degenerate triangle kept");
  }
}

}  // namespace
}  // namespace stitchsim::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stitchsim;
  const auto path = fuzz::WriteScratch("part.stl", data, size);
  geom::TriangleMesh mesh;
  mesh.vertices = {{1, 2, 3}};  // a marker: a failed read must not touch the output
  std::string error;
  if (!geom::ReadStl(path, 25.4, mesh, error)) {
    fuzz::Require(!error.empty(), "ReadStl failed without a message");
    fuzz::Require(mesh.vertices.size() == 1 && mesh.triangles.empty(),
                  "a failed ReadStl changed the mesh");
    return 0;
  }
  fuzz::CheckMesh(mesh);
  // Binary out, binary in: float rounding may weld more vertices, never break the mesh.
  const auto copy = fuzz::ScratchDir() / "copy.stl";
  fuzz::Require(geom::WriteStl(copy, mesh, error), "WriteStl failed: " + error);
  geom::TriangleMesh again;
  if (geom::ReadStl(copy, 1.0, again, error)) fuzz::CheckMesh(again);
  return 0;
}
