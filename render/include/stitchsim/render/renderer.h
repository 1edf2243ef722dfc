#pragma once
// Headless rendering of a MuJoCo scene through OSMesa (no display, no GPU).

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
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
  /// Polyline only: the last segment is drawn as an arrow pointing at the last point.
  bool arrow_head = false;
  /// Polyline only, one per point when given (world, unit): each segment is drawn as a flat
  /// ribbon instead of a capsule, a thin box 2 * radius_m wide across the segment, lying in
  /// the plane normal to its ends' mean normal (laid tows on a part), `ribbon_thickness_m`
  /// thick.
  std::vector<Eigen::Vector3d> normals;
  double ribbon_thickness_m = 0.0002;
};

/// A geom drawn in another colour for one picture.
struct GeomColour {
  int geom = -1;                             ///< model geom id
  std::array<float, 4> rgba = {1, 0, 0, 1};  ///< alpha < 1: see-through, still segmented
};

/// Per-draw overrides of the model's look (highlighting, seeing through what is in the way).
struct DrawStyle {
  std::vector<int> transparent;  ///< geom ids drawn see-through (segmentation leaves them out)
  float transparent_alpha = 0.2f;
  std::vector<int> hidden;          ///< geom ids not drawn at all (nor segmented)
  std::vector<GeomColour> colours;  ///< recoloured geoms
  /// When set, every model geom not recoloured is drawn in this colour (greying out the rest
  /// of the cell; see-through ones too).
  std::optional<std::array<float, 4>> others;
  /// Overlay labels left out of the segmentation (drawn, never counted as hiding anything).
  std::vector<std::string> unsegmented_overlays;
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
  std::vector<int> geoms;               ///< model geom id (-1 for overlays and decor)
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
  Image Render(mjData* data, const CameraView& camera, const std::vector<Overlay>& overlays,
               const DrawStyle& style = {});
  /// Renders a segmentation image of the same view; transparent and hidden geoms (and the
  /// style's unsegmented overlays) are left out.
  Segmentation RenderSegmentation(mjData* data, const CameraView& camera,
                                  const std::vector<Overlay>& overlays,
                                  const DrawStyle& style = {});

 private:
  OffscreenRenderer() = default;
  void Draw(mjData* data, const CameraView& camera, const std::vector<Overlay>& overlays,
            const DrawStyle& style, bool segment);
  void AddOverlays(const std::vector<Overlay>& overlays, const DrawStyle& style, bool segment);
  void ApplyStyle(const DrawStyle& style, bool segment);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Camera looking along `forward` (world, need not be unit; not vertical) at `lookat_m`
/// from `distance_m` away.
CameraView LookAlong(const Eigen::Vector3d& lookat_m, const Eigen::Vector3d& forward,
                     double distance_m);
/// The unit direction the camera looks along (world).
Eigen::Vector3d ViewDirection(const CameraView& view);

/// Writes an 8-bit RGB PNG whole-or-nothing (temporary file, then rename). Error or empty.
std::string WritePng(const std::filesystem::path& path, const Image& image);

/// Reads an RGB(A) PNG (used by tests).
bool ReadPng(const std::filesystem::path& path, Image& image, std::string& error);

}  // namespace stitchsim::render
