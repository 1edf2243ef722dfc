#include "stitchsim/process/afp_steering.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace stitchsim::process {

double TangentPlaneCircleRadius(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c, const Eigen::Vector3d& n) {
  Eigen::Vector3d u = b - a, v = c - b;
  u -= u.dot(n) * n;
  v -= v.dot(n) * n;
  const double twice_area = 2.0 * std::abs(u.cross(v).dot(n));
  const double sides = u.norm() * v.norm() * (u + v).norm();
  if (sides <= 0.0 || twice_area <= 1e-15 * sides) return std::numeric_limits<double>::infinity();
  return sides / twice_area;
}

void SteeringWindow::Reset() {
  vertices_.clear();
  next_ = 0;
}

int SteeringWindow::PendingTag() const {
  return next_ < vertices_.size() ? vertices_[next_].tag : INT_MAX;
}

void SteeringWindow::Add(const Eigen::Vector3d& centre, const Eigen::Vector3d& normal, int tag,
                         std::vector<Radius>& out) {
  const double s =
      vertices_.empty() ? 0.0 : vertices_.back().s + (centre - vertices_.back().centre).norm();
  vertices_.push_back({centre, normal, s, tag});
  const double half = kSteeringHalfWindowMm;
  while (next_ < vertices_.size() && vertices_.back().s >= vertices_[next_].s + half) {
    const Vertex& b = vertices_[next_];
    if (b.s - vertices_.front().s >= half) {
      std::size_t ia = next_, ic = next_;
      while (vertices_[ia].s > b.s - half) --ia;  // the nearest at least a half window before
      while (vertices_[ic].s < b.s + half) ++ic;  // ... and after
      out.push_back(
          {TangentPlaneCircleRadius(vertices_[ia].centre, b.centre, vertices_[ic].centre, b.normal),
           b.tag, vertices_[ia].centre, b.centre, vertices_[ic].centre});
    }
    ++next_;
    // Keep the last vertex a half window before the next one to measure.
    while (next_ < vertices_.size() && vertices_.size() >= 2 &&
           vertices_[1].s <= vertices_[next_].s - half) {
      vertices_.pop_front();
      --next_;
    }
  }
}

}  // namespace stitchsim::process
