#pragma once
// Laydown figures of an AFP programme (issue 29; docs/report-format.md, "Laydown"): per ply
// (the programme's M70 P<n>) and for the whole programme, the laydown time at the programmed
// feeds with the head's slow zones around cuts and adds, the same through the controller's
// ramps, the off-part time, the material laid and the rate. Read from the line records alone
// (no samples); pure.
//
// A lay-up run is a chain of laying lines (course, feed move, head down, some tow set) of one
// course, each starting where the last ended; a non-laying line, another course or a jump ends
// it. The run starts and ends at rest. Along the run (x, mm, the tool point's path: each line's
// chord), every tow laid from the run's start or from a line where it was not laid before is
// added there; a tow laid on one line and not the next, or laid to the run's end, is cut there.
// Within `cut_add_zone_mm` either side of every cut and add (clipped to the run) the feed is
// min(feed, cut_add_feed_mm_s).

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "stitchsim/trace/trace.h"
#include "stitchsim/verify/report.h"

namespace stitchsim::verify {

/// A stretch of a lay-up run at one speed limit.
struct FeedPiece {
  double length_mm = 0.0;  ///< along the tool point's path, mm
  double feed_mm_s = 0.0;  ///< speed limit on it, mm/s (> 0)
};

/// Seconds to travel `pieces` in order from rest to rest at the controller's ramps: on each
/// piece the speed is at most its feed and changes at a = feed / ramp_time_s (the time law's
/// acceleration at the programmed speed, docs/timing.md); the speed is continuous, so a
/// slower piece is entered at its own feed at most (the faster one brakes before it).
/// The cell's axis limits and the look-ahead window are not applied here.
double RampedTime(const std::vector<FeedPiece>& pieces, double ramp_time_s);

/// Seconds at the programmed feeds: the sum of length / feed.
double FeedTime(const std::vector<FeedPiece>& pieces);

/// A run's pieces: lines (length, feed) with the feed capped at `zone_feed_mm_s` within
/// `zone_mm` either side of each event position (mm along the run). zone_mm 0: the lines.
std::vector<FeedPiece> SlowZonePieces(const std::vector<FeedPiece>& lines,
                                      const std::vector<double>& events_mm, double zone_mm,
                                      double zone_feed_mm_s);

/// What the meter needs of the head and the scene.
struct LaydownParams {
  int tows = 16;                   ///< the head's tows
  double tow_width_mm = 6.35;      ///< the head's tow width, mm
  double cut_add_feed_mm_s = 0.0;  ///< feed within the zones, mm/s; 0: no slow zones
  double cut_add_zone_mm = 0.0;    ///< zone either side of a cut or add, mm
  double ramp_time_s = 0.25;       ///< the controller's ramp (dialect; docs/timing.md), s
  /// Areal weight of ply n (M70 P<n>) at [n - 1], g/m^2; a ply past it weighs the default.
  std::vector<double> areal_weight_g_m2;
  double default_areal_weight_g_m2 = 300.0;  ///< assumption: domain.md's typical prepreg tow
};

struct RuleContext;
/// The meter's parameters from the scene's head and plies and the context's ramp time.
LaydownParams LaydownFor(const RuleContext& ctx);

/// Streams line records (programme order) into the figures. Memory: one run's lines.
class LaydownMeter {
 public:
  explicit LaydownMeter(LaydownParams params);
  void OnLine(const trace::LineRecord& line);
  /// Closes the open run (the programme's end).
  void Finish();
  /// Per ply in ply order (those that laid or moved), then the whole programme (ply 0).
  std::vector<LaydownFigures> Figures() const;
  bool SawAnything() const { return !plies_.empty(); }

 private:
  void CloseRun();
  void Event(double x, bool add, int tow);
  double ArealWeight(int ply) const;

  LaydownParams params_;
  std::map<int, LaydownFigures> plies_;  ///< by ply number (0: before any M70)
  // The open run.
  bool open_ = false;
  int ply_ = 0, course_ = 0;
  std::uint64_t mask_ = 0;
  double x_ = 0.0;
  Eigen::Vector3d end_ = Eigen::Vector3d::Zero();
  std::vector<FeedPiece> lines_;
  std::vector<double> events_;
  std::vector<double> tow_start_;  ///< per tow (index tow - 1): where its piece began
};

}  // namespace stitchsim::verify
