// A polyline overlay with normals is drawn as a flat ribbon: seen along its normal it covers
// its width times its length (closed form: the camera's pixels per metre at that distance),
// seen edge on almost nothing, where a capsule of the same radius shows its full width.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "stitchsim/common/units.h"
#include "stitchsim/render/renderer.h"
#include "stitchsim/render/scene_model.h"

namespace stitchsim::render {
namespace {

constexpr int kSide = 200;
constexpr double kDistanceM = 0.5;
constexpr double kHalfWidthM = 0.01;  // the ribbon 20 mm wide
constexpr double kLengthM = 0.2;

struct EmptyWorld {
  MjModelPtr model;
  MjDataPtr data;
};

EmptyWorld Empty() {
  const auto path = std::filesystem::temp_directory_path() / "stitchsim-ribbon-test.xml";
  std::ofstream(path) << "<mujoco><worldbody><light pos='0 0 20'/></worldbody></mujoco>\n";
  char error[512] = "";
  EmptyWorld w;
  w.model.reset(mj_loadXML(path.string().c_str(), nullptr, error, sizeof(error)));
  EXPECT_TRUE(w.model) << error;
  if (w.model) w.data.reset(mj_makeData(w.model.get()));
  std::filesystem::remove(path);
  return w;
}

long Pixels(const Segmentation& s, const std::string& name) {
  long n = 0;
  for (int l : s.label) {
    if (l >= 0 && s.names[static_cast<std::size_t>(l)] == name) ++n;
  }
  return n;
}

// A straight ribbon along x at z = 0, its normal +z (three points: two segments).
Overlay Ribbon(bool flat) {
  Overlay o;
  o.label = "ribbon";
  o.radius_m = kHalfWidthM;
  o.points_m = {{-0.5 * kLengthM, 0, 0}, {0, 0, 0}, {0.5 * kLengthM, 0, 0}};
  if (flat) o.normals.assign(3, Eigen::Vector3d::UnitZ());
  return o;
}

TEST(Ribbon, FlatFromAboveCoversWidthTimesLengthAndAlmostNothingEdgeOn) {
  EmptyWorld w = Empty();
  ASSERT_TRUE(w.model);
  std::string error;
  auto r = OffscreenRenderer::Create(w.model.get(), kSide, kSide, error);
  ASSERT_TRUE(r) << error;
  mj_kinematics(w.model.get(), w.data.get());
  // Closed form: the vertical field of view spans 2 d tan(fovy / 2) over kSide pixels.
  const double fovy = w.model->vis.global.fovy * kPi / 180.0;
  const double px_per_m = kSide / (2.0 * kDistanceM * std::tan(0.5 * fovy));
  const double expected = (2 * kHalfWidthM * px_per_m) * (kLengthM * px_per_m);
  const CameraView above{Eigen::Vector3d::Zero(), kDistanceM, 0.0, -89.9};
  const CameraView edge_on{Eigen::Vector3d::Zero(), kDistanceM, 90.0, 0.0};

  const long flat_above =
      Pixels(r->RenderSegmentation(w.data.get(), above, {Ribbon(true)}), "overlay:ribbon");
  EXPECT_NEAR(flat_above, expected, 0.15 * expected);
  const long flat_edge =
      Pixels(r->RenderSegmentation(w.data.get(), edge_on, {Ribbon(true)}), "overlay:ribbon");
  const long tube_edge =
      Pixels(r->RenderSegmentation(w.data.get(), edge_on, {Ribbon(false)}), "overlay:ribbon");
  // Edge on, the 0.2 mm thick ribbon is at most a row or two; the capsule its full width.
  EXPECT_LT(flat_edge, 2 * kLengthM * px_per_m);
  EXPECT_GT(tube_edge, 0.8 * expected);
}

}  // namespace
}  // namespace stitchsim::render
