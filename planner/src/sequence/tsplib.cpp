// TSPLIB reader (G. Reinelt, "TSPLIB 95", Universitaet Heidelberg): the header's KEY : VALUE
// lines, then sections of whitespace-separated numbers; distances as the document defines them.
#include "stitchsim/planner/sequence/tsplib.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <memory>
#include <sstream>

#include "stitchsim/common/files.h"
#include "stitchsim/common/limits.h"

namespace stitchsim::planner {
namespace {

/// Largest DIMENSION read: the full matrix is dimension^2 doubles (200 MB at 5,000).
constexpr int kMaxTsplibDimension = 5000;

struct TspLine {
  int number = 0;  // 1-based
  std::vector<std::string_view> tokens;
  std::string_view text;
};

std::string_view TrimTsp(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

std::vector<TspLine> SplitTspLines(std::string_view text) {
  std::vector<TspLine> lines;
  int number = 0;
  while (!text.empty() || number == 0) {
    const auto end = text.find('\n');
    TspLine line;
    line.number = ++number;
    line.text = TrimTsp(text.substr(0, end));
    for (std::string_view rest = line.text; !rest.empty();) {
      const auto stop = rest.find_first_of(" \t\r");
      line.tokens.push_back(rest.substr(0, stop));
      if (stop == std::string_view::npos) break;
      rest = TrimTsp(rest.substr(stop));
    }
    lines.push_back(std::move(line));
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return lines;
}

bool IsSectionName(std::string_view t) {
  return t == "NODE_COORD_SECTION" || t == "EDGE_WEIGHT_SECTION" || t == "DISPLAY_DATA_SECTION" ||
         t == "TOUR_SECTION" || t == "EOF";
}

/// A line that ends a section of numbers: a section name, EOF or a KEY : VALUE line.
bool IsKeywordLine(const TspLine& line) {
  return !line.tokens.empty() &&
         (IsSectionName(line.tokens[0]) || line.text.find(':') != std::string_view::npos);
}

std::string NumberText(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::optional<double> ParseTspNumber(std::string_view token) {
  double value = 0.0;
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

/// Reading one file: its lines, where it is, and where its findings go.
struct TspText {
  std::vector<TspLine> lines;
  std::size_t at = 0;  // index of the line being read
  const std::string& file;
  DiagnosticSink& sink;

  bool Fail(const char* code, int line, const std::string& message) {
    sink.Error(std::string("tsplib-") + code, SourceLocation{file, line, 0}, message);
    return false;
  }
  int LastLine() const { return lines.empty() ? 0 : lines.back().number; }
  /// The `count` numbers of the section whose name is on line `at`; `at` ends on the section's
  /// last line. A keyword or the end of the text before `count` numbers is an error, as are
  /// extra numbers on the last line and tokens that are not finite numbers.
  std::optional<std::vector<double>> Numbers(std::size_t count, std::string_view section) {
    std::vector<double> values;
    values.reserve(count);
    const int section_line = lines[at].number;
    while (values.size() < count) {
      if (++at >= lines.size() || IsKeywordLine(lines[at])) {
        const int where = at < lines.size() ? lines[at].number : LastLine();
        Fail("count", where,
             std::string(section) + " (line " + std::to_string(section_line) + ") ends after " +
                 std::to_string(values.size()) + " of its " + std::to_string(count) +
                 " numbers (truncated, or DIMENSION wrong)");
        return std::nullopt;
      }
      for (std::string_view token : lines[at].tokens) {
        const std::optional<double> v = ParseTspNumber(token);
        if (!v) {
          Fail("bad-number", lines[at].number,
               "'" + std::string(token) + "' is not a finite number (in " + std::string(section) +
                   ")");
          return std::nullopt;
        }
        if (values.size() == count) {
          Fail("count", lines[at].number,
               std::string(section) + " has more than its " + std::to_string(count) +
                   " numbers (DIMENSION wrong?)");
          return std::nullopt;
        }
        values.push_back(*v);
      }
    }
    return values;
  }
};

/// "KEY : VALUE" (also "KEY: VALUE", "KEY :VALUE"); false for any other line.
bool SplitKeyValue(std::string_view text, std::string_view& key, std::string_view& value) {
  const auto colon = text.find(':');
  if (colon == std::string_view::npos) return false;
  key = TrimTsp(text.substr(0, colon));
  value = TrimTsp(text.substr(colon + 1));
  return true;
}

/// The header's values that decide how the sections are read.
struct TspHeader {
  std::string name, type, edge_weight_type, edge_weight_format;
  int dimension = 0;
};

bool ReadHeaderLine(TspText& t, std::string_view key, std::string_view value, TspHeader& h) {
  const int line = t.lines[t.at].number;
  if (key == "NAME") {
    h.name = value;
  } else if (key == "TYPE") {
    h.type = value;
  } else if (key == "COMMENT") {
  } else if (key == "DIMENSION") {
    const std::optional<double> d = ParseTspNumber(value);
    if (!d || *d < 1 || *d > kMaxTsplibDimension || *d != std::floor(*d))
      return t.Fail("bad-value", line,
                    "DIMENSION '" + std::string(value) + "' is not a whole number in 1.." +
                        std::to_string(kMaxTsplibDimension));
    h.dimension = static_cast<int>(*d);
  } else if (key == "EDGE_WEIGHT_TYPE") {
    h.edge_weight_type = value;
  } else if (key == "EDGE_WEIGHT_FORMAT") {
    h.edge_weight_format = value;
  } else if (key == "NODE_COORD_TYPE" || key == "DISPLAY_DATA_TYPE") {
    if (value != "TWOD_COORDS" && value != "NO_COORDS" && value != "TWOD_DISPLAY" &&
        value != "COORD_DISPLAY" && value != "NO_DISPLAY")
      return t.Fail("bad-value", line,
                    std::string(key) + " '" + std::string(value) + "' is not supported");
  } else {
    return t.Fail("unknown-keyword", line, "unknown keyword '" + std::string(key) + "'");
  }
  return true;
}

/// Numbers of EDGE_WEIGHT_SECTION for a format; 0 for an unknown format.
std::size_t ExplicitCount(const std::string& format, std::size_t n) {
  if (format == "FULL_MATRIX") return n * n;
  if (format == "UPPER_ROW" || format == "LOWER_ROW") return n * (n - 1) / 2;
  if (format == "UPPER_DIAG_ROW" || format == "LOWER_DIAG_ROW") return n * (n + 1) / 2;
  return 0;
}

/// The matrix of an explicit section: row by row, the part of each row the format lists.
std::vector<double> ExplicitMatrix(const std::string& format, int n, const std::vector<double>& w) {
  if (format == "FULL_MATRIX") return w;
  const auto un = static_cast<std::size_t>(n);
  std::vector<double> m(un * un, 0.0);
  std::size_t k = 0;
  for (int i = 0; i < n; ++i) {
    int from = 0, to = n;  // the columns row i lists, [from, to)
    if (format == "UPPER_ROW") from = i + 1;
    if (format == "UPPER_DIAG_ROW") from = i;
    if (format == "LOWER_ROW") to = i;
    if (format == "LOWER_DIAG_ROW") to = i + 1;
    for (int j = from; j < to; ++j, ++k) {
      m[static_cast<std::size_t>(i) * un + static_cast<std::size_t>(j)] = w[k];
      m[static_cast<std::size_t>(j) * un + static_cast<std::size_t>(i)] = w[k];
    }
  }
  return m;
}

/// TSPLIB's distance of two points for a coordinate edge-weight type (nint = floor(x + 0.5)).
double CoordDistance(const std::string& type, double dx, double dy) {
  const double r = std::sqrt(dx * dx + dy * dy);
  if (type == "CEIL_2D") return std::ceil(r);
  if (type == "ATT") {
    const double rij = std::sqrt((dx * dx + dy * dy) / 10.0);
    const double tij = std::floor(rij + 0.5);
    return tij < rij ? tij + 1.0 : tij;
  }
  return std::floor(r + 0.5);  // EUC_2D
}

bool IsCoordType(const std::string& type) {
  return type == "EUC_2D" || type == "CEIL_2D" || type == "ATT";
}

/// The coordinates section: lines "i x y", each city 1..n once.
std::optional<std::vector<double>> ReadCoords(TspText& t, int n) {
  const std::size_t first = t.at + 1;
  const std::optional<std::vector<double>> v =
      t.Numbers(3u * static_cast<std::size_t>(n), "NODE_COORD_SECTION");
  if (!v) return std::nullopt;
  std::vector<double> xy(2u * static_cast<std::size_t>(n));
  std::vector<bool> seen(static_cast<std::size_t>(n), false);
  for (int k = 0; k < n; ++k) {
    const double id = (*v)[3u * static_cast<std::size_t>(k)];
    if (id < 1 || id > n || id != std::floor(id) || seen[static_cast<std::size_t>(id) - 1]) {
      // The line of entry k: the k-th non-empty line after the section name (one entry a line).
      int line = t.lines[t.at].number;
      for (std::size_t i = first, entries = 0; i <= t.at; ++i) {
        if (!t.lines[i].tokens.empty() && entries++ == static_cast<std::size_t>(k)) {
          line = t.lines[i].number;
          break;
        }
      }
      t.Fail("bad-node", line,
             "node number " + NumberText(id) + " is not a new city in 1.." + std::to_string(n));
      return std::nullopt;
    }
    const auto c = static_cast<std::size_t>(id) - 1;
    seen[c] = true;
    xy[2 * c] = (*v)[3u * static_cast<std::size_t>(k) + 1];
    xy[2 * c + 1] = (*v)[3u * static_cast<std::size_t>(k) + 2];
  }
  return xy;
}

/// Checks the header against what this reader supports, before any section is read.
bool CheckTspHeader(TspText& t, const TspHeader& h, std::string_view section) {
  const int line = t.lines[t.at].number;
  if (h.type != "TSP" && h.type != "ATSP")
    return t.Fail("bad-value", line, "TYPE '" + h.type + "' is not TSP or ATSP");
  if (h.dimension == 0)
    return t.Fail("missing", line, "DIMENSION must come before " + std::string(section));
  if (h.edge_weight_type == "EXPLICIT") {
    if (ExplicitCount(h.edge_weight_format, static_cast<std::size_t>(h.dimension)) == 0)
      return t.Fail("bad-value", line,
                    "EDGE_WEIGHT_FORMAT '" + h.edge_weight_format + "' is not supported");
    if (h.type == "ATSP" && h.edge_weight_format != "FULL_MATRIX")
      return t.Fail("bad-value", line, "an ATSP needs EDGE_WEIGHT_FORMAT FULL_MATRIX");
  } else if (!IsCoordType(h.edge_weight_type)) {
    return t.Fail("bad-value", line,
                  "EDGE_WEIGHT_TYPE '" + h.edge_weight_type +
                      "' is not supported (EUC_2D, CEIL_2D, ATT, EXPLICIT)");
  }
  return true;
}

/// Reads a section named on line t.at into `xy` or `weights`; false on an error.
bool ReadSection(TspText& t, const TspHeader& h, std::string_view section,
                 std::optional<std::vector<double>>& xy,
                 std::optional<std::vector<double>>& weights) {
  if (!CheckTspHeader(t, h, section)) return false;
  const auto n = static_cast<std::size_t>(h.dimension);
  if (section == "NODE_COORD_SECTION") {
    xy = ReadCoords(t, h.dimension);
    return xy.has_value();
  }
  if (section == "EDGE_WEIGHT_SECTION") {
    if (h.edge_weight_type != "EXPLICIT")
      return t.Fail("bad-value", t.lines[t.at].number,
                    "EDGE_WEIGHT_SECTION needs EDGE_WEIGHT_TYPE EXPLICIT");
    weights = t.Numbers(ExplicitCount(h.edge_weight_format, n), section);
    return weights.has_value();
  }
  return t.Numbers(3 * n, section).has_value();  // DISPLAY_DATA_SECTION: read, unused
}

}  // namespace

std::optional<TsplibInstance> ParseTsplib(std::string_view text, const std::string& file,
                                          DiagnosticSink& sink) {
  TspText t{SplitTspLines(text), 0, file, sink};
  TspHeader h;
  std::optional<std::vector<double>> xy, weights;
  for (; t.at < t.lines.size(); ++t.at) {
    const TspLine& line = t.lines[t.at];
    if (line.tokens.empty()) continue;
    std::string_view key, value;
    if (line.tokens[0] == "EOF") break;
    if (IsSectionName(line.tokens[0]) && line.tokens.size() == 1) {
      if (line.tokens[0] == "TOUR_SECTION") {
        t.Fail("unknown-keyword", line.number, "TOUR_SECTION in a TSP file");
        return std::nullopt;
      }
      if (!ReadSection(t, h, line.tokens[0], xy, weights)) return std::nullopt;
      continue;
    }
    if (!SplitKeyValue(line.text, key, value)) {
      const bool number = ParseTspNumber(line.tokens[0]).has_value();
      t.Fail(number ? "count" : "unknown-keyword", line.number,
             number ? "numbers outside a section (more than DIMENSION asks for?)"
                    : "unknown keyword '" + std::string(line.tokens[0]) + "'");
      return std::nullopt;
    }
    if (!ReadHeaderLine(t, key, value, h)) return std::nullopt;
  }
  const bool coords = IsCoordType(h.edge_weight_type);
  if ((coords && !xy) || (!coords && !weights) || h.dimension == 0) {
    t.Fail("missing", t.LastLine(),
           coords ? "no NODE_COORD_SECTION" : "no EDGE_WEIGHT_SECTION (or no EDGE_WEIGHT_TYPE)");
    return std::nullopt;
  }
  TsplibInstance out;
  out.name = h.name;
  out.symmetric = h.type == "TSP";
  out.dimension = h.dimension;
  const auto n = static_cast<std::size_t>(h.dimension);
  if (!coords) {
    out.distance = ExplicitMatrix(h.edge_weight_format, h.dimension, *weights);
    return out;
  }
  out.distance.assign(n * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      out.distance[i * n + j] = CoordDistance(h.edge_weight_type, (*xy)[2 * j] - (*xy)[2 * i],
                                              (*xy)[2 * j + 1] - (*xy)[2 * i + 1]);
  return out;
}

namespace {
std::optional<std::string> ReadTspFile(const std::string& path, DiagnosticSink& sink) {
  FileText f = ReadRegularFile(path, limits::kMaxModelFileBytes);
  if (!f.ok()) {
    sink.Error(f.problem == FileProblem::kMissing ? "tsplib-missing-file" : "tsplib-unreadable",
               SourceLocation{path, 0, 0}, f.error);
    return std::nullopt;
  }
  return std::move(f.text);
}
}  // namespace

std::optional<TsplibInstance> ReadTsplib(const std::string& path, DiagnosticSink& sink) {
  const std::optional<std::string> text = ReadTspFile(path, sink);
  if (!text) return std::nullopt;
  return ParseTsplib(*text, path, sink);
}

std::optional<std::vector<int>> ParseTsplibTour(std::string_view text, const std::string& file,
                                                int dimension, DiagnosticSink& sink) {
  TspText t{SplitTspLines(text), 0, file, sink};
  for (; t.at < t.lines.size(); ++t.at) {
    const TspLine& line = t.lines[t.at];
    if (line.tokens.empty() || line.tokens[0] != "TOUR_SECTION") continue;
    std::vector<int> tour;
    std::vector<bool> seen(static_cast<std::size_t>(dimension), false);
    for (++t.at; t.at < t.lines.size() && !IsKeywordLine(t.lines[t.at]); ++t.at) {
      for (std::string_view token : t.lines[t.at].tokens) {
        const std::optional<double> v = ParseTspNumber(token);
        if (v && *v == -1 && static_cast<int>(tour.size()) == dimension) return tour;
        if (!v || *v < 1 || *v > dimension || *v != std::floor(*v) ||
            seen[static_cast<std::size_t>(*v) - 1]) {
          t.Fail("bad-node", t.lines[t.at].number,
                 "'" + std::string(token) + "' is not a new city in 1.." +
                     std::to_string(dimension) + " (or -1 after all of them)");
          return std::nullopt;
        }
        seen[static_cast<std::size_t>(*v) - 1] = true;
        tour.push_back(static_cast<int>(*v) - 1);
      }
    }
    t.Fail("count", t.LastLine(),
           "TOUR_SECTION ends after " + std::to_string(tour.size()) + " of " +
               std::to_string(dimension) + " cities without -1");
    return std::nullopt;
  }
  t.Fail("missing", t.LastLine(), "no TOUR_SECTION");
  return std::nullopt;
}

std::optional<std::vector<int>> ReadTsplibTour(const std::string& path, int dimension,
                                               DiagnosticSink& sink) {
  const std::optional<std::string> text = ReadTspFile(path, sink);
  if (!text) return std::nullopt;
  return ParseTsplibTour(*text, path, dimension, sink);
}

double TourLength(const TsplibInstance& instance, const std::vector<int>& cities) {
  double length = 0.0;
  for (std::size_t k = 0; k < cities.size(); ++k)
    length += instance.Distance(cities[k], cities[(k + 1) % cities.size()]);
  return length;
}

SequenceProblem TsplibProblem(const TsplibInstance& instance, bool bidirectional) {
  const int courses = instance.dimension - 1;
  const auto nodes = 2u * static_cast<std::size_t>(courses);
  auto table = std::make_shared<MoveTable>();
  table->move.resize(nodes * nodes);
  table->from_start.resize(nodes);
  table->to_finish.resize(nodes);
  for (std::size_t u = 0; u < nodes; ++u) {
    const int city_u = static_cast<int>(u / 2) + 1;
    table->from_start[u] = instance.Distance(0, city_u);
    table->to_finish[u] = instance.Distance(city_u, 0);
    for (std::size_t v = 0; v < nodes; ++v)
      table->move[u * nodes + v] = instance.Distance(city_u, static_cast<int>(v / 2) + 1);
  }
  SequenceProblem p;
  p.courses = courses;
  p.bidirectional = bidirectional;
  p.finish = std::vector<double>{};
  p.table = std::move(table);
  return p;
}

std::vector<int> TsplibTour(const std::vector<Visit>& order) {
  std::vector<int> cities{0};
  for (const Visit& v : order) cities.push_back(v.course + 1);
  return cities;
}

std::optional<std::vector<TsplibOptimum>> ReadTsplibOptima(const std::string& path,
                                                           DiagnosticSink& sink) {
  const std::optional<std::string> text = ReadTspFile(path, sink);
  if (!text) return std::nullopt;
  std::vector<TsplibOptimum> out;
  for (const TspLine& line : SplitTspLines(*text)) {
    if (line.tokens.empty() || line.tokens[0].front() == '#') continue;
    const std::optional<double> optimum =
        line.tokens.size() == 3 ? ParseTspNumber(line.tokens[2]) : std::nullopt;
    const bool type_ok =
        line.tokens.size() == 3 && (line.tokens[1] == "TSP" || line.tokens[1] == "ATSP");
    if (!optimum || !type_ok || *optimum <= 0) {
      sink.Error("tsplib-bad-optimum", SourceLocation{path, line.number, 0},
                 "expected 'name TSP|ATSP length' with a positive length");
      return std::nullopt;
    }
    out.push_back({std::string(line.tokens[0]), line.tokens[1] == "TSP", *optimum});
  }
  return out;
}

}  // namespace stitchsim::planner
