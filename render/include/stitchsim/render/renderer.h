#pragma once
// Headless rendering of a MuJoCo scene through OSMesa (no display, no GPU).

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace stitchsim::render {

/// An RGB image, rows top to bottom.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
};

/// Extra geometry drawn over the model: a polyline (capsules) or a set of points (spheres).
struct Overlay {
  std::string label;                      ///< category name used in segmentation counts
  std::vector<Eigen::Vector3d> points_m;  ///< world frame, metres
  bool polyline = true;                   ///< false: one sphere per point
  double radius_m = 0.004;
  float rgba[4] = {0.1f, 0.9f, 0.2f, 1.0f};
};

/// Free camera, MuJoCo convention (azimuth/elevation in degrees).
struct CameraView {
  Eigen::Vector3d lookat_m = Eigen::Vector3d::Zero();
  double distance_m = 8.0;
  double azimuth_deg = 60.0;
  double elevation_deg = -28.0;
};

/// Per-pixel segmentation: which model geom or overlay covers each pixel.
struct Segmentation {
  int width = 0;
  int height = 0;
  std::vector<int> label;               ///< index into `names`, -1 = background
  std::vector<std::string> names;       ///< geom name, or "overlay:<label>"
  std::vector<std::string> body_names;  ///< body of the geom ("" for overlays)
};

class OffscreenRenderer {
 public:
  /// Creates the OSMesa context and MuJoCo's render context. Returns nullptr with `error` set.
  static std::unique_ptr<OffscreenRenderer> Create(mjModel* model, int width, int height,
                                                   std::string& error);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  /// Renders the model in the state of `data` (kinematics must be up to date).
  Image Render(mjData* data, const CameraView& camera, const std::vector<Overlay>& overlays);
  /// Renders a segmentation image of the same view.
  Segmentation RenderSegmentation(mjData* data, const CameraView& camera,
                                  const std::vector<Overlay>& overlays);

 private:
  OffscreenRenderer() = default;
  void Draw(mjData* data, const CameraView& camera, const std::vector<Overlay>& overlays,
            bool segment);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes an 8-bit RGB PNG whole-or-nothing (temporary file, then rename). Error or empty.
std::string WritePng(const std::filesystem::path& path, const Image& image);

/// Reads an RGB(A) PNG (used by tests).
bool ReadPng(const std::filesystem::path& path, Image& image, std::string& error);

}  // namespace stitchsim::render
