#include "afp_laid_material_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stitchsim::verify::detail {
namespace {

constexpr std::size_t kNoStrip = static_cast<std::size_t>(-1);
// Figures arrive for lines a steering window (50 mm) behind at most: a backward search this
// many strips deep finds them (the planner's lines are 4 mm and longer; a line is at least 1
// strip).
constexpr std::size_t kFigureSearchDepth = 4096;

}  // namespace

LaidMaterialBuilder::LaidMaterialBuilder(std::shared_ptr<LaidTows> laid)
    : laid_(std::move(laid)),
      open_(static_cast<std::size_t>(std::max(laid_->Layout().tows, 0)), kNoStrip) {
  material_.tows = laid_->Layout().tows;
  material_.tow_width_mm = laid_->Layout().width_mm;
  material_.spacing_mm = kStationSpacingMm;
  laid_->SetFigures(this);
}

LaidMaterialBuilder::~LaidMaterialBuilder() {
  if (laid_->Figures() == this) laid_->SetFigures(nullptr);
}

void LaidMaterialBuilder::AddStation(const LaidPose& pose) {
  LaidStation s;
  s.tool = pose.tool.translation().cast<float>();
  s.on_surface = pose.cross.ok;
  const Eigen::Vector3f nan3 = Eigen::Vector3f::Constant(LaidMaterial::kNotMeasured);
  const Eigen::Vector2f nan2 = Eigen::Vector2f::Constant(LaidMaterial::kNotMeasured);
  const auto k1 = static_cast<std::size_t>(material_.tows) + 1;
  if (pose.cross.ok) {
    s.normal = laid_->Surface().Normal(pose.cross.centre_uv).normalized().cast<float>();
    for (std::size_t b = 0; b < k1; ++b) {
      material_.boundary.push_back(pose.cross.boundary[b].cast<float>());
      material_.boundary_uv.push_back(pose.cross.boundary_uv[b].cast<float>());
    }
  } else {
    s.normal = Eigen::Vector3f::Constant(LaidMaterial::kNotMeasured);
    material_.boundary.insert(material_.boundary.end(), k1, nan3);
    material_.boundary_uv.insert(material_.boundary_uv.end(), k1, nan2);
  }
  material_.stations.push_back(s);
}

void LaidMaterialBuilder::OnLine(const trace::LineRecord& record) {
  const LaidLine* line = laid_->Sample(record);
  if (line == nullptr || line->poses.empty()) {
    CloseRuns();
    last_laying_ = false;
    return;
  }
  const bool same_course = !material_.strips.empty() && material_.strips.back().ply == line->ply &&
                           material_.strips.back().course == line->course;
  if (!last_laying_ || !same_course) CloseRuns();
  const bool continues = last_laying_ && same_course && record.from.matrix() == last_to_.matrix();

  LaidStrip strip;
  strip.line = line->source_line;
  strip.ply = line->ply;
  strip.course = line->course;
  strip.tows = line->tows;
  strip.feed_mm_s = static_cast<float>(record.feed_mm_per_min / 60.0);
  const std::size_t n = line->poses.size();
  const std::size_t steps = n - 1;
  const double length = (record.to.translation() - record.from.translation()).norm();
  // Every m-th sampled pose (evenly spaced along the line) and the last one.
  std::size_t m = steps;
  if (steps > 0 && length > 0.0) {
    m = std::clamp<std::size_t>(static_cast<std::size_t>(std::floor(
                                    kStationSpacingMm * static_cast<double>(steps) / length)),
                                1, steps);
  }
  if (continues) {
    strip.first_station = static_cast<std::uint32_t>(material_.stations.size() - 1);
  } else {
    strip.first_station = static_cast<std::uint32_t>(material_.stations.size());
    AddStation(line->poses.front());
  }
  for (std::size_t i = m; i < steps; i += m) AddStation(line->poses[i]);
  if (steps > 0) AddStation(line->poses.back());
  strip.station_count = static_cast<std::uint32_t>(material_.stations.size()) - strip.first_station;
  if (strip.station_count < 2) {  // a line of no length: its one pose is both ends
    AddStation(line->poses.back());
    strip.station_count = 2;
  }
  material_.strips.push_back(strip);
  const auto k = static_cast<std::size_t>(material_.tows);
  material_.steering_radius_mm.insert(material_.steering_radius_mm.end(), k,
                                      LaidMaterial::kNotMeasured);
  material_.fiber_angle_deg.insert(material_.fiber_angle_deg.end(), k, LaidMaterial::kNotMeasured);

  const std::size_t index = material_.strips.size() - 1;
  for (int t = 1; t <= material_.tows; ++t) {
    std::size_t& open = open_[static_cast<std::size_t>(t) - 1];
    const bool lays = TowLaid(line->tows, t);
    if (open != kNoStrip && !lays) {
      AddEvent(TowEvent::Kind::kCut, open, t);
      open = kNoStrip;
    } else if (open == kNoStrip && lays) {
      AddEvent(TowEvent::Kind::kAdd, index, t);
    }
    if (lays) open = index;
  }
  last_laying_ = true;
  last_to_ = record.to;
}

void LaidMaterialBuilder::CloseRuns() {
  for (int t = 1; t <= material_.tows; ++t) {
    std::size_t& open = open_[static_cast<std::size_t>(t) - 1];
    if (open != kNoStrip) AddEvent(TowEvent::Kind::kCut, open, t);
    open = kNoStrip;
  }
}

void LaidMaterialBuilder::AddEvent(TowEvent::Kind kind, std::size_t strip, int tow) {
  const LaidStrip& s = material_.strips[strip];
  TowEvent e;
  e.kind = kind;
  e.line = s.line;
  e.ply = s.ply;
  e.course = s.course;
  e.tow = tow;
  e.strip = static_cast<std::uint32_t>(strip);
  const std::size_t station =
      kind == TowEvent::Kind::kAdd ? s.first_station : s.first_station + s.station_count - 1;
  e.uv = 0.5F * (material_.BoundaryUv(station, tow - 1) + material_.BoundaryUv(station, tow));
  e.point = Eigen::Vector3f::Constant(LaidMaterial::kNotMeasured);
  if (e.uv.allFinite()) e.point = laid_->Surface().Point(e.uv.cast<double>()).cast<float>();
  material_.events.push_back(e);
}

void LaidMaterialBuilder::Finish() {
  CloseRuns();
  last_laying_ = false;
  material_.stations.shrink_to_fit();
  material_.boundary.shrink_to_fit();
  material_.boundary_uv.shrink_to_fit();
  material_.strips.shrink_to_fit();
  material_.steering_radius_mm.shrink_to_fit();
  material_.fiber_angle_deg.shrink_to_fit();
  material_.events.shrink_to_fit();
}

std::size_t LaidMaterialBuilder::FindStrip(int line) const {
  const std::size_t n = material_.strips.size();
  for (std::size_t i = n; i > 0 && n - i < kFigureSearchDepth; --i) {
    if (material_.strips[i - 1].line == line) return i - 1;
  }
  return kNoStrip;
}

void LaidMaterialBuilder::KeepFigure(std::vector<float>& figures, int line, int tow, double value,
                                     bool smallest) {
  const std::size_t s = FindStrip(line);
  if (s == kNoStrip || tow < 1 || tow > material_.tows) return;
  float& kept =
      figures[s * static_cast<std::size_t>(material_.tows) + static_cast<std::size_t>(tow - 1)];
  const auto v = static_cast<float>(value);
  if (std::isnan(kept) || (smallest ? v < kept : v > kept)) kept = v;
}

void LaidMaterialBuilder::SteeringRadius(int line, int tow, double radius_mm) {
  KeepFigure(material_.steering_radius_mm, line, tow, radius_mm, true);
}

void LaidMaterialBuilder::FiberAngle(int line, int tow, double deg) {
  KeepFigure(material_.fiber_angle_deg, line, tow, deg, false);
}

}  // namespace stitchsim::verify::detail
