#pragma once
// Private to verify: fills a LaidMaterial (stitchsim/verify/afp_laid_material.h) from the
// afp.* rules' shared sampler (afp_laid.h) as the verifier streams the programme. Asked for a
// line before the rules (Verifier::OnLine), it samples the line once and the rules reuse that
// sampling (LaidTows caches the last line); the rules hand it their per-tow figures through
// LaidFigures as they measure them.

#include <memory>
#include <vector>

#include "afp_laid.h"
#include "stitchsim/verify/afp_laid_material.h"

namespace stitchsim::verify::detail {

class LaidMaterialBuilder final : public LaidFigures {
 public:
  /// The most a strip's stations lie apart along its line: the steering rule's half window
  /// (process::kSteeringHalfWindowMm, 25 mm), the spacing of the vertices it measures a long
  /// line's turn at, so a turn it reports shows in the stations.
  static constexpr double kStationSpacingMm = 25.0;

  /// Hands `laid` this builder as its LaidFigures; the builder must outlive its use.
  explicit LaidMaterialBuilder(std::shared_ptr<LaidTows> laid);
  LaidMaterialBuilder(const LaidMaterialBuilder&) = delete;
  LaidMaterialBuilder& operator=(const LaidMaterialBuilder&) = delete;
  ~LaidMaterialBuilder() override;

  void OnLine(const trace::LineRecord& record);
  /// Closes the open tow runs (their cuts) and trims the storage.
  void Finish();
  const LaidMaterial& Material() const { return material_; }

  void SteeringRadius(int line, int tow, double radius_mm) override;
  void FiberAngle(int line, int tow, double deg) override;

 private:
  // Appends the station of `pose` (its boundaries too).
  void AddStation(const LaidPose& pose);
  // Ends every open tow run: their cuts.
  void CloseRuns();
  // Records tow `tow`'s add or cut on strip `strip` at its first (add) or last (cut) station.
  void AddEvent(TowEvent::Kind kind, std::size_t strip, int tow);
  // The strip of `line` among the latest ones (npos: none).
  std::size_t FindStrip(int line) const;
  // Keeps `value` as `line`'s figure for `tow` in `figures` when it is the smallest
  // (`smallest`) or largest so far.
  void KeepFigure(std::vector<float>& figures, int line, int tow, double value, bool smallest);

  std::shared_ptr<LaidTows> laid_;
  LaidMaterial material_;
  /// Per head tow (index t - 1): the strip the tow's open run last laid on, or npos.
  std::vector<std::size_t> open_;
  /// The last line was a laying one: its strip continues into the next of its course.
  bool last_laying_ = false;
  Eigen::Isometry3d last_to_ = Eigen::Isometry3d::Identity();
};

}  // namespace stitchsim::verify::detail
