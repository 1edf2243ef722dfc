// The programme header, typed both ways: WriteIdentity's text read back through the parser
// and ReadIdentity is the identity written (every field), a header written by hand is the
// writer's text, and a malformed value is gcode-bad-header at its line.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "stitchsim/program/identity.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::program {
namespace {

std::string HeaderText(const ProgramIdentity& id) {
  std::ostringstream out;
  {
    ProgramWriter writer(out, Dialect::Default());
    writer.WriteHeader(WriteIdentity(id));
  }
  return out.str();
}

// `text` as a programme's header (a mark, the header lines, one motion line), typed.
std::optional<ProgramIdentity> ReadBack(const std::string& text, DiagnosticSink& sink) {
  std::istringstream in("%\n" + text + "G0 X0\n%\n");
  ProgramReader reader(in, Dialect::Default(), "p.nc", sink);
  return ReadIdentity(reader.ReadHeader(), "p.nc", sink);
}

// Every field set, numbers with at most six decimals (they survive the text exactly).
ProgramIdentity EveryField() {
  ProgramIdentity id;
  id.scene = "wing_cover";
  id.head = "rs535";
  id.path = "frame_flange";
  id.mode = "decoupled";
  id.raster = "serpentine";
  id.ply = "skin_45";
  id.plies = "skin_0,skin_45";
  id.laminate = "upper_skin";
  id.course = "lay45";
  id.lay_angle_deg = -45.0;
  id.angle_deg = 22.5;
  id.coverage_pct = 97.0;
  id.incline_deg = 10.125;
  id.points = 108;
  id.course_length_mm = 534.803451;
  id.stitch_length_mm = 3.175;
  id.row_spacing_mm = 5.08;
  id.heads = 2;
  id.courses = 8;
  id.tows = 16;
  id.stitches = 123456;
  return id;
}

TEST(program_identity, WrittenThenReadBackIsTheSameIdentityOverEveryField) {
  const ProgramIdentity id = EveryField();
  const ProgramHeader header = WriteIdentity(id);
  // One entry per field: a field the table forgot would be missing here.
  EXPECT_EQ(header.entries.size(), 21u);
  DiagnosticSink sink;
  const std::optional<ProgramIdentity> back = ReadBack(HeaderText(id), sink);
  EXPECT_TRUE(sink.Diagnostics().empty());
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(*back, id);
  // Field by field too, so a failure says which.
  EXPECT_EQ(back->plies, "skin_0,skin_45");
  EXPECT_EQ(back->laminate, "upper_skin");
  EXPECT_EQ(back->lay_angle_deg, -45.0);
  EXPECT_EQ(back->course_length_mm, 534.803451);
  EXPECT_EQ(back->stitch_length_mm, 3.175);
  EXPECT_EQ(back->heads, 2);
  EXPECT_EQ(back->stitches, 123456);
}

TEST(program_identity, NothingWrittenNothingRead) {
  EXPECT_TRUE(WriteIdentity(ProgramIdentity{}).empty());
  DiagnosticSink sink;
  const auto back = ReadBack("(STITCHSIM late=ignored)\n", sink);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(*back, ProgramIdentity{});
}

TEST(program_identity, HeadersWrittenByHandAreTheWritersText) {
  ProgramIdentity afp;  // docs/program-format.md's AFP example
  afp.scene = "afp_concave_cylinder";
  afp.head = "afp";
  afp.course = "lay45";
  afp.lay_angle_deg = 45.0;
  afp.incline_deg = 10.0;
  afp.points = 108;
  afp.course_length_mm = 534.8034506;
  EXPECT_EQ(HeaderText(afp),
            "(STITCHSIM scene=afp_concave_cylinder head=afp course=lay45 lay_angle_deg=45.000000 "
            "incline_deg=10.000000 points=108 course_length_mm=534.803451)\n");
  // As plan stitch writes it, set in another order than it is written.
  ProgramIdentity stitch;
  stitch.stitches = 128;
  stitch.stitch_length_mm = 4.9873;
  stitch.mode = "auto";
  stitch.path = "circle";
  stitch.head = "rs535";
  stitch.scene = "circle_8in";
  EXPECT_EQ(HeaderText(stitch),
            "(STITCHSIM scene=circle_8in head=rs535 path=circle mode=auto "
            "stitch_length_mm=4.987300 stitches=128)\n");
  // As plan ply writes one ply: the coverage whole.
  ProgramIdentity ply;
  ply.scene = "afp_panel";
  ply.head = "afp";
  ply.ply = "skin_45";
  ply.angle_deg = 45.0;
  ply.coverage_pct = 49.6;
  ply.courses = 5;
  ply.tows = 16;
  EXPECT_EQ(HeaderText(ply),
            "(STITCHSIM scene=afp_panel head=afp ply=skin_45 angle_deg=45.000000 coverage_pct=50 "
            "courses=5 tows=16)\n");
}

TEST(program_identity, AValueThatPrintsAsZeroHasNoSign) {
  ProgramIdentity id;
  id.incline_deg = -1e-9;
  id.coverage_pct = -0.2;
  id.angle_deg = -0.0000006;  // rounds to -0.000001: keeps its sign
  const ProgramHeader h = WriteIdentity(id);
  EXPECT_EQ(h.Find("incline_deg"), "0.000000");
  EXPECT_EQ(h.Find("coverage_pct"), "0");
  EXPECT_EQ(h.Find("angle_deg"), "-0.000001");
}

TEST(program_identity, AMalformedValueIsABadHeaderAtItsLine) {
  DiagnosticSink sink;
  const auto id = ReadBack(
      "(STITCHSIM scene=s head=h)\n"
      "(STITCHSIM heads=two row_spacing_mm=0 coverage_pct=nan)\n"
      "(STITCHSIM stitch_length_mm=-1 stitches=1.5)\n",
      sink);
  EXPECT_FALSE(id.has_value());
  ASSERT_EQ(sink.Diagnostics().size(), 5u);
  for (const Diagnostic& d : sink.Diagnostics()) EXPECT_EQ(d.code, "gcode-bad-header");
  // In key-table order: coverage_pct, stitch_length_mm, row_spacing_mm, heads, stitches.
  const auto& d = sink.Diagnostics();
  EXPECT_EQ(d[0].message, "header coverage_pct=nan: must be a finite number");
  EXPECT_EQ(d[0].location.line, 3);
  EXPECT_EQ(d[1].message,
            "header stitch_length_mm=-1: the stitch length must be a positive number of "
            "millimetres");
  EXPECT_EQ(d[1].location.line, 4);
  EXPECT_EQ(d[2].message,
            "header row_spacing_mm=0: the row spacing must be a positive number of millimetres");
  EXPECT_EQ(d[3].message, "header heads=two: must be a whole number >= 0");
  EXPECT_EQ(d[4].message, "header stitches=1.5: the stitch count must be a whole number >= 0");
  EXPECT_EQ(d[4].location.line, 4);
}

}  // namespace
}  // namespace stitchsim::program
