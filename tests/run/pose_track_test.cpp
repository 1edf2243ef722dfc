// The HTML report's line-end poses: thinning by powers of two keeps the lines the report
// points at and every line from the one a serial run may still point at; the lines kept are
// counted by hand.
#include "stitchsim/run/pose_track.h"

#include <gtest/gtest.h>

#include <vector>

namespace stitchsim::run {
namespace {

PoseTrack Lines(int first, int last, std::size_t max_poses) {
  PoseTrack track(max_poses);
  for (int line = first; line <= last; ++line) {
    LinePose p;
    p.line = line;
    p.time_s = static_cast<float>(line) * 0.5f;
    track.Add(p);
  }
  return track;
}

std::vector<int> LinesOf(const PoseTrack& track) {
  std::vector<int> lines;
  for (const LinePose& p : track.Poses()) lines.push_back(p.line);
  return lines;
}

TEST(PoseTrack, ThinningDoublesTheStrideAndKeepsThePointedLines) {
  // Lines 1..100, at most 30 kept: stride 2 leaves 50, stride 4 leaves 25 (4, 8, ..., 100),
  // plus the pointed lines 7 and 33 (odd: no stride keeps them).
  PoseTrack track = Lines(1, 100, 30);
  track.Thin({7, 33}, 1000);
  std::vector<int> expected;
  for (int line = 4; line <= 100; line += 4) expected.push_back(line);
  expected.insert(expected.begin() + 1, 7);   // after 4
  expected.insert(expected.begin() + 9, 33);  // after 32
  EXPECT_EQ(LinesOf(track), expected);
}

TEST(PoseTrack, LinesFromTheCutOnAreNeverThinned) {
  // Lines 1..64 with every line from 41 on kept: 24 of those; stride 2 leaves 20 + 24 = 44
  // > 30, stride 4 leaves 10 + 24 = 34 > 30, stride 8 leaves 5 + 24 = 29.
  PoseTrack track = Lines(1, 64, 30);
  track.Thin({}, 41);
  EXPECT_EQ(track.Poses().size(), 29u);
  EXPECT_EQ(track.Poses().front().line, 8);
  EXPECT_EQ(track.Poses()[4].line, 40);
  EXPECT_EQ(track.Poses()[5].line, 41);
}

TEST(PoseTrack, ALineGivenAgainReplacesItsPoseAndAppendSkipsLinesAlreadyHeld) {
  PoseTrack track = Lines(1, 5, 100);
  LinePose again;
  again.line = 5;
  again.time_s = 99.0f;
  track.Add(again);
  ASSERT_EQ(track.Poses().size(), 5u);
  EXPECT_EQ(track.Poses().back().time_s, 99.0f);
  track.Append(Lines(4, 8, 100));  // 4 and 5 are held already
  EXPECT_EQ(LinesOf(track), (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(track.Poses()[4].time_s, 99.0f);
}

}  // namespace
}  // namespace stitchsim::run
