// The AFP snapshot: one picture per ply the programme laid, a top view of the surface's
// (u, v) box from the afp.coverage rule's map (docs/afp.md, "Coverage"; the colour key is in
// docs/report-format.md, "Snapshots").
#include <filesystem>

#include "stitchsim/render/renderer.h"
#include "stitchsim/run/snapshots.h"
#include "stitchsim/verify/afp_coverage_image.h"

namespace stitchsim::run {
namespace {

// The colour key, by verify::CoverageState.
constexpr std::uint8_t kCoverageColours[][3] = {
    {255, 255, 255},  // nothing
    {60, 110, 200},   // laid tows: blue
    {220, 30, 30},    // gap (bare inside the ply): red
    {250, 190, 0},    // overlap (doubled): amber
    {160, 160, 160},  // laid outside the ply: grey
    {250, 170, 170},  // bare in the boundary band (the coverage policy's): pink
};

}  // namespace

Status WriteAfpCoverageSnapshots(const verify::Verifier& verifier, const std::string& dir) {
  for (const verify::CoverageImage& img : verify::CoverageImages(verifier)) {
    render::Image out;
    out.width = img.width;
    out.height = img.height;
    out.rgb.reserve(img.pixels.size() * 3);
    for (const verify::CoverageState s : img.pixels) {
      const auto* c = kCoverageColours[static_cast<int>(s)];
      out.rgb.insert(out.rgb.end(), c, c + 3);
    }
    const auto path =
        std::filesystem::path(dir) / ("coverage_ply" + std::to_string(img.ply) + ".png");
    if (std::string err = render::WritePng(path, out); !err.empty()) {
      return Status::Error("io-write", "cannot write " + path.string() + ": " + err);
    }
  }
  return Status::Ok();
}

}  // namespace stitchsim::run
