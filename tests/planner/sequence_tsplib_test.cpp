// The TSPLIB reader (issue 28; bench/data/tsplib/): distances by hand for each edge-weight type
// and format, the published optimal tours' lengths equal the published optima (optima.txt, a
// second list), PathCost of the sequencing problem equals the tour length, and bad input is a
// diagnostic with file:line.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "stitchsim/planner/sequence/tsplib.h"

namespace stitchsim::planner {
namespace {

namespace fs = std::filesystem;
const fs::path kTsplibDir = fs::path(STITCHSIM_SOURCE_DIR) / "bench" / "data" / "tsplib";

std::string AllDiagnostics(const DiagnosticSink& sink) {
  std::string out;
  for (const Diagnostic& d : sink.Diagnostics()) out += FormatDiagnostic(d) + "\n";
  return out;
}

TsplibInstance ParseOk(const std::string& text) {
  DiagnosticSink sink;
  std::optional<TsplibInstance> in = ParseTsplib(text, "inline.tsp", sink);
  EXPECT_TRUE(in.has_value()) << AllDiagnostics(sink);
  EXPECT_FALSE(sink.HasErrors()) << AllDiagnostics(sink);
  return in.value_or(TsplibInstance{});
}

TEST(Tsplib, Berlin52FirstDistancesByHand) {
  DiagnosticSink sink;
  const auto in = ReadTsplib((kTsplibDir / "berlin52.tsp").string(), sink);
  ASSERT_TRUE(in.has_value()) << AllDiagnostics(sink);
  EXPECT_EQ(in->name, "berlin52");
  EXPECT_TRUE(in->symmetric);
  ASSERT_EQ(in->dimension, 52);
  // Cities 1..5 at (565,575), (25,185), (345,750), (945,685), (845,655); nint(sqrt(dx^2+dy^2)):
  // sqrt(443700) = 666.11, sqrt(79025) = 281.11, sqrt(156500) = 395.60, sqrt(84800) = 291.20,
  // and 2 -> 3: sqrt(320^2 + 565^2) = sqrt(421625) = 649.33.
  EXPECT_EQ(in->Distance(0, 1), 666);
  EXPECT_EQ(in->Distance(0, 2), 281);
  EXPECT_EQ(in->Distance(0, 3), 396);
  EXPECT_EQ(in->Distance(0, 4), 291);
  EXPECT_EQ(in->Distance(1, 2), 649);
  EXPECT_EQ(in->Distance(2, 1), 649);
  EXPECT_EQ(in->Distance(3, 3), 0);
}

// Five cities: (0,0) (3,0) (3,4) (0,4) (1,1). Tour 1 2 3 4 5: 3 + 4 + 3 + nint(sqrt 10 = 3.16)
// + nint(sqrt 2 = 1.41) = 3 + 4 + 3 + 3 + 1 = 14.
constexpr const char* kFiveCities =
    "NAME : five\nTYPE : TSP\nCOMMENT : by hand\nDIMENSION : 5\nEDGE_WEIGHT_TYPE : EUC_2D\n"
    "NODE_COORD_SECTION\n1 0 0\n2 3 0\n3 3 4\n4 0 4\n5 1 1\nEOF\n";

TEST(Tsplib, FiveCityTourByHandAndAsASequencingProblem) {
  const TsplibInstance in = ParseOk(kFiveCities);
  EXPECT_EQ(TourLength(in, {0, 1, 2, 3, 4}), 14.0);
  for (const bool bidirectional : {false, true}) {
    const SequenceProblem p = TsplibProblem(in, bidirectional);
    ASSERT_EQ(p.courses, 4);
    EXPECT_EQ(PathCost(p, {{0, false}, {1, false}, {2, false}, {3, false}}), 14.0);
    // Zero-length courses: laying one backwards changes nothing.
    EXPECT_EQ(PathCost(p, {{0, true}, {1, false}, {2, true}, {3, true}}), 14.0);
    EXPECT_EQ(TsplibTour({{0, false}, {1, false}, {2, false}, {3, false}}),
              (std::vector<int>{0, 1, 2, 3, 4}));
    // Another order: 1 3 2 5 4: 5 + 4 + nint(sqrt 5 = 2.24) + nint(sqrt 10) + 4 = 5+4+2+3+4.
    EXPECT_EQ(PathCost(p, {{1, false}, {0, false}, {3, false}, {2, false}}), 18.0);
  }
  // The exact solver's optimum of the five cities is the perimeter with (1,1) on the way:
  // 1 5 2 3 4: nint(1.41) + nint(sqrt 5) + 4 + 3 + 4 = 1 + 2 + 4 + 3 + 4 = 14 (ties 14).
  const std::optional<SequenceSolution> exact = SolveExact(TsplibProblem(in, false));
  ASSERT_TRUE(exact.has_value());
  EXPECT_EQ(exact->cost, 14.0);
}

TEST(Tsplib, CeilAndAttDistancesByHand) {
  const std::string cities = "DIMENSION : 3\nNODE_COORD_SECTION\n1 0 0\n2 3 4.1\n3 10 0\nEOF\n";
  // d(1,2) = sqrt(25.81) = 5.080; d(1,3) = 10.
  const TsplibInstance euc = ParseOk("TYPE : TSP\nEDGE_WEIGHT_TYPE : EUC_2D\n" + cities);
  EXPECT_EQ(euc.Distance(0, 1), 5);
  EXPECT_EQ(euc.Distance(0, 2), 10);
  const TsplibInstance ceil = ParseOk("TYPE : TSP\nEDGE_WEIGHT_TYPE : CEIL_2D\n" + cities);
  EXPECT_EQ(ceil.Distance(0, 1), 6);
  EXPECT_EQ(ceil.Distance(0, 2), 10);
  // ATT: r = sqrt(d^2 / 10); t = nint(r); t < r ? t + 1 : t. d(1,2): r = 1.607, t = 2.
  // d(1,3): r = sqrt(10) = 3.162, t = 3 < r, so 4.
  const TsplibInstance att = ParseOk("TYPE : TSP\nEDGE_WEIGHT_TYPE : ATT\n" + cities);
  EXPECT_EQ(att.Distance(0, 1), 2);
  EXPECT_EQ(att.Distance(0, 2), 4);
}

TEST(Tsplib, ExplicitFormatsGiveTheSameMatrix) {
  const std::string head = "TYPE : TSP\nDIMENSION : 4\nEDGE_WEIGHT_TYPE : EXPLICIT\n";
  const TsplibInstance full =
      ParseOk(head +
              "EDGE_WEIGHT_FORMAT : FULL_MATRIX\nEDGE_WEIGHT_SECTION\n0 1 2 3\n1 0 4 5\n2 4 0 6\n"
              "3 5 6 0\nEOF\n");
  const std::pair<const char*, const char*> formats[] = {
      {"UPPER_ROW", "1 2 3\n4 5\n6\n"},
      {"LOWER_ROW", "1\n2 4\n3 5 6\n"},
      {"UPPER_DIAG_ROW", "0 1 2 3\n0 4 5\n0 6\n0\n"},
      {"LOWER_DIAG_ROW", "0\n1 0\n2 4 0\n3 5 6 0\n"}};
  for (const auto& [format, numbers] : formats) {
    const TsplibInstance in = ParseOk(head + "EDGE_WEIGHT_FORMAT : " + format +
                                      "\nEDGE_WEIGHT_SECTION\n" + numbers + "EOF\n");
    EXPECT_EQ(in.distance, full.distance) << format;
  }
  EXPECT_EQ(full.Distance(1, 3), 5);
  EXPECT_EQ(full.Distance(3, 2), 6);
}

TEST(Tsplib, AsymmetricMatrixKeepsItsDirections) {
  const TsplibInstance in = ParseOk(
      "NAME : a3\nTYPE : ATSP\nDIMENSION : 3\nEDGE_WEIGHT_TYPE : EXPLICIT\n"
      "EDGE_WEIGHT_FORMAT : FULL_MATRIX\nEDGE_WEIGHT_SECTION\n9999 1 7\n2 9999 3\n5 8 9999\nEOF\n");
  EXPECT_FALSE(in.symmetric);
  // 1 -> 2 -> 3 -> 1: 1 + 3 + 5 = 9; the other way 1 -> 3 -> 2 -> 1: 7 + 8 + 2 = 17.
  EXPECT_EQ(TourLength(in, {0, 1, 2}), 9.0);
  EXPECT_EQ(TourLength(in, {0, 2, 1}), 17.0);
  const SequenceProblem p = TsplibProblem(in, true);
  EXPECT_EQ(PathCost(p, {{0, false}, {1, true}}), 9.0);
  EXPECT_EQ(PathCost(p, {{1, false}, {0, false}}), 17.0);
}

// The published optimal tours (*.opt.tour) measured by our distances equal the published
// optima (optima.txt, TSPLIB's solution list): two TSPLIB files against one list.
TEST(Tsplib, OptimalToursHaveThePublishedLength) {
  DiagnosticSink sink;
  const auto optima = ReadTsplibOptima((kTsplibDir / "optima.txt").string(), sink);
  ASSERT_TRUE(optima.has_value()) << AllDiagnostics(sink);
  int checked = 0;
  for (const TsplibOptimum& o : *optima) {
    const fs::path tour_file = kTsplibDir / (o.name + ".opt.tour");
    if (!fs::exists(tour_file)) continue;
    const auto in = ReadTsplib((kTsplibDir / (o.name + ".tsp")).string(), sink);
    ASSERT_TRUE(in.has_value()) << AllDiagnostics(sink);
    const auto tour = ReadTsplibTour(tour_file.string(), in->dimension, sink);
    ASSERT_TRUE(tour.has_value()) << AllDiagnostics(sink);
    EXPECT_EQ(TourLength(*in, *tour), o.optimum) << o.name;
    // The same tour as an order of the sequencing problem (rotated to start at city 1).
    const auto first = std::find(tour->begin(), tour->end(), 0) - tour->begin();
    std::vector<Visit> order;
    for (std::size_t k = 1; k < tour->size(); ++k)
      order.push_back({(*tour)[(static_cast<std::size_t>(first) + k) % tour->size()] - 1, false});
    EXPECT_EQ(PathCost(TsplibProblem(*in, false), order), o.optimum) << o.name;
    ++checked;
  }
  EXPECT_EQ(checked, 4);  // berlin52, st70, eil76, kroA100
}

// Every instance of the bench reads cleanly, is the type optima.txt says, and its problem's
// PathCost of the file's own order equals TourLength of that tour.
TEST(Tsplib, EveryBenchInstanceReads) {
  DiagnosticSink sink;
  const auto optima = ReadTsplibOptima((kTsplibDir / "optima.txt").string(), sink);
  ASSERT_TRUE(optima.has_value()) << AllDiagnostics(sink);
  EXPECT_EQ(optima->size(), 27u);
  for (const TsplibOptimum& o : *optima) {
    const auto in =
        ReadTsplib((kTsplibDir / (o.name + (o.symmetric ? ".tsp" : ".atsp"))).string(), sink);
    ASSERT_TRUE(in.has_value()) << o.name << AllDiagnostics(sink);
    EXPECT_EQ(in->name, o.name);
    EXPECT_EQ(in->symmetric, o.symmetric) << o.name;
    std::vector<int> identity;
    std::vector<Visit> order;
    for (int c = 0; c < in->dimension; ++c) identity.push_back(c);
    for (int c = 1; c < in->dimension; ++c) order.push_back({c - 1, false});
    const double length = TourLength(*in, identity);
    EXPECT_EQ(PathCost(TsplibProblem(*in, false), order), length) << o.name;
    EXPECT_GT(length, o.optimum) << o.name;  // the file's order is not optimal
  }
  EXPECT_FALSE(sink.HasErrors()) << AllDiagnostics(sink);
}

struct BadCase {
  const char* what;
  std::string text;
  const char* code;
  int line;
};

TEST(Tsplib, BadInputIsADiagnosticWithItsLine) {
  const std::string head = "NAME : bad\nTYPE : TSP\nDIMENSION : 3\nEDGE_WEIGHT_TYPE : EUC_2D\n";
  const BadCase cases[] = {
      {"unknown keyword", "NAME : x\nCOLOUR : red\n", "tsplib-unknown-keyword", 2},
      {"unknown edge type",
       "TYPE : TSP\nDIMENSION : 3\nEDGE_WEIGHT_TYPE : GEO\nNODE_COORD_SECTION\n",
       "tsplib-bad-value", 4},
      {"unknown type",
       "TYPE : CVRP\nDIMENSION : 3\nEDGE_WEIGHT_TYPE : EUC_2D\nNODE_COORD_SECTION\n",
       "tsplib-bad-value", 4},
      {"truncated", head + "NODE_COORD_SECTION\n1 0 0\n2 1 1\n", "tsplib-count", 7},
      {"truncated before EOF", head + "NODE_COORD_SECTION\n1 0 0\n2 1 1\nEOF\n", "tsplib-count", 8},
      {"too many numbers", head + "NODE_COORD_SECTION\n1 0 0\n2 1 1\n3 2 2 4\nEOF\n",
       "tsplib-count", 8},
      {"numbers after the section", head + "NODE_COORD_SECTION\n1 0 0\n2 1 1\n3 2 2\n4 3 3\n",
       "tsplib-count", 9},
      {"NaN", head + "NODE_COORD_SECTION\n1 0 0\n2 nan 1\n3 2 2\n", "tsplib-bad-number", 7},
      {"not a number", head + "NODE_COORD_SECTION\n1 0 0\n2 1,5 1\n3 2 2\n", "tsplib-bad-number",
       7},
      {"duplicate node", head + "NODE_COORD_SECTION\n1 0 0\n1 1 1\n3 2 2\n", "tsplib-bad-node", 7},
      {"node out of range", head + "NODE_COORD_SECTION\n1 0 0\n2 1 1\n4 2 2\n", "tsplib-bad-node",
       8},
      {"bad dimension", "TYPE : TSP\nDIMENSION : -3\n", "tsplib-bad-value", 2},
      {"section before dimension", "TYPE : TSP\nEDGE_WEIGHT_TYPE : EUC_2D\nNODE_COORD_SECTION\n",
       "tsplib-missing", 3},
      {"no section", head + "EOF\n", "tsplib-missing", 5},
      {"ATSP half matrix",
       "TYPE : ATSP\nDIMENSION : 3\nEDGE_WEIGHT_TYPE : EXPLICIT\nEDGE_WEIGHT_FORMAT : UPPER_ROW\n"
       "EDGE_WEIGHT_SECTION\n1 2 3\n",
       "tsplib-bad-value", 5},
      {"empty file", "", "tsplib-missing", 1},
  };
  for (const BadCase& c : cases) {
    DiagnosticSink sink;
    EXPECT_FALSE(ParseTsplib(c.text, "bad.tsp", sink).has_value()) << c.what;
    ASSERT_EQ(sink.ErrorCount(), 1u) << c.what << "\n" << AllDiagnostics(sink);
    const Diagnostic& d = sink.Diagnostics()[0];
    EXPECT_EQ(d.code, c.code) << c.what << ": " << FormatDiagnostic(d);
    EXPECT_EQ(d.location.file, "bad.tsp") << c.what;
    EXPECT_EQ(d.location.line, c.line) << c.what << ": " << FormatDiagnostic(d);
  }
}

TEST(Tsplib, BadFilesToursAndOptimaAreDiagnostics) {
  DiagnosticSink sink;
  EXPECT_FALSE(ReadTsplib((kTsplibDir / "no_such.tsp").string(), sink).has_value());
  ASSERT_EQ(sink.ErrorCount(), 1u);
  EXPECT_EQ(sink.Diagnostics()[0].code, "tsplib-missing-file");
  EXPECT_NE(FormatDiagnostic(sink.Diagnostics()[0]).find("no_such.tsp"), std::string::npos);

  const std::pair<const char*, int> tours[] = {
      {"TYPE : TOUR\nTOUR_SECTION\n1\n2\n3\n", 5},      // no -1
      {"TYPE : TOUR\nTOUR_SECTION\n1\n2\n2\n-1\n", 5},  // a city twice
      {"TYPE : TOUR\nTOUR_SECTION\n1\n2\n-1\n", 5},     // -1 before every city
      {"TYPE : TOUR\n", 1}};                            // no section
  for (const auto& [text, line] : tours) {
    DiagnosticSink tour_sink;
    EXPECT_FALSE(ParseTsplibTour(text, "t.tour", 3, tour_sink).has_value()) << text;
    ASSERT_EQ(tour_sink.ErrorCount(), 1u) << text;
    EXPECT_EQ(tour_sink.Diagnostics()[0].location.line, line) << text;
  }
  DiagnosticSink tour_sink;
  const auto good = ParseTsplibTour("TOUR_SECTION\n3 1\n2 -1\nEOF\n", "t.tour", 3, tour_sink);
  ASSERT_TRUE(good.has_value()) << AllDiagnostics(tour_sink);
  EXPECT_EQ(*good, (std::vector<int>{2, 0, 1}));

  const fs::path bad_optima = fs::temp_directory_path() / "stitchsim_bad_optima.txt";
  {
    std::FILE* f = std::fopen(bad_optima.string().c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("# comment\nberlin52 TSP 7542\nst70 TSP\n", f);
    std::fclose(f);
  }
  DiagnosticSink optima_sink;
  EXPECT_FALSE(ReadTsplibOptima(bad_optima.string(), optima_sink).has_value());
  ASSERT_EQ(optima_sink.ErrorCount(), 1u);
  EXPECT_EQ(optima_sink.Diagnostics()[0].location.line, 3);
  fs::remove(bad_optima);
}

}  // namespace
}  // namespace stitchsim::planner
