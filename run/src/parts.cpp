// Part files of a sharded verify run: written by a shard (PartJson), read and merged by
// `report merge` (part_merge.cpp).
#include "stitchsim/run/parts.h"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "stitchsim/common/exact_sum.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/version.h"
#include "stitchsim/run/reports.h"

namespace stitchsim::run {
namespace {

constexpr const char* kPartFormat = "stitchsim-verify-part";
constexpr int kPartVersion = 1;

std::string Hex64(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// The keys every part of one run shares (the programme, the scene, the options, the cut).
constexpr const char* kSameKeys[] = {
    "program",          "program_bytes",     "program_fnv1a",  "scene",  "dialect",
    "scene_files",      "no_collision",      "allow_mismatch", "shards", "chunks_total",
    "chunk_lines",      "warm_lines",        "lines",          "moves",  "cycle_time_s",
    "stitch_length_mm", "declared_stitches", "tool_version"};

// The scene's files are the ones the shards ran on.
bool SceneFilesUnchanged(const nlohmann::json& head, const scene::Scene& scene,
                         DiagnosticSink& sink) {
  std::size_t k = 0;
  for (const auto& f : SceneFingerprints(scene)) {
    if (k >= head["scene_files"].size() || head["scene_files"][k]["fnv1a"] != Hex64(f.fnv1a)) {
      ToolError(sink, "part-stale",
                "the " + f.role + " (" + f.path + ") changed since the shards ran: run them again");
      return false;
    }
    ++k;
  }
  return true;
}

// A programme run in one chunk: its one part holds the finished reports.
std::optional<CompleteReports> CompleteOf(const Part& part, DiagnosticSink& sink) {
  const nlohmann::json& c = part.j["complete"];
  if (!c.is_object() || !c.contains("text") || !c.contains("json") || !c.contains("junit")) {
    ToolError(sink, "part-bad", part.file + ": bad 'complete'");
    return std::nullopt;
  }
  return CompleteReports{c["text"].get<std::string>(), c["json"].get<std::string>(),
                         c["junit"].get<std::string>(), c.value("errors", 0L)};
}

// The model the shards ran on, rebuilt from the first part (the rules finish as one run's).
std::unique_ptr<RunModel> ModelOf(const nlohmann::json& head, LoadedScene loaded,
                                  DiagnosticSink& sink) {
  const std::string dialect_file = head["dialect"].get<std::string>();
  std::optional<program::Dialect> dialect = program::Dialect::Default();
  if (!dialect_file.empty()) {
    DiagnosticSink dialect_sink;
    dialect = program::LoadDialect(dialect_file, dialect_sink);
    if (Forward(dialect_sink, sink) || !dialect) return nullptr;
  }
  RunOptions options;
  options.no_collision = head["no_collision"].get<bool>();
  options.allow_mismatch = head["allow_mismatch"].get<bool>();
  std::optional<long> declared;
  if (!head["declared_stitches"].is_null()) declared = head["declared_stitches"].get<long>();
  return MakeRunModel(std::move(loaded), *dialect, head["stitch_length_mm"].get<double>(), declared,
                      options, sink);
}

// The parts' verifiers absorbed in chunk order into one, and their timed sums added.
bool AbsorbParts(const std::vector<Part>& parts, const RunModel& model, verify::Verifier& merged,
                 ExactSum& timed, DiagnosticSink& sink) {
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const nlohmann::json& j = parts[i].j;
    if (i > 0 && j["start"] != parts[i - 1].j["end"]) {
      ToolError(sink, "part-boundary",
                parts[i].file + " started from a state that differs from where " +
                    parts[i - 1].file +
                    " ended (the arm's branch or the controller's speed at the cut): verify "
                    "with fewer shards, or in one process with --jobs");
      return false;
    }
    ExactSum part_timed;
    if (!ExactSum::FromHex(j.value("timed_sum", std::string()), part_timed)) {
      ToolError(sink, "part-bad", parts[i].file + ": bad timed_sum");
      return false;
    }
    timed.Add(part_timed);
    std::string error;
    verify::Verifier v(model.Rules(), false);
    if (!v.LoadPartial(j["verifier"], error)) {
      ToolError(sink, "part-bad", parts[i].file + ": " + error);
      return false;
    }
    merged.Absorb(v);
  }
  return true;
}

}  // namespace

std::uint64_t FileFnv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return 0;
  // One digit short of FNV-1a's offset basis (14695981039346656037, trace::Fnv1a64's); kept:
  // shards compare it only with each other, and part files stay as they were.
  std::uint64_t h = 1469598103934665603ULL;
  std::vector<char> buf(1 << 20);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= static_cast<unsigned char>(buf[static_cast<std::size_t>(i)]);
      h *= 1099511628211ULL;
    }
  }
  return h;
}

int ShardOf(const sim::Chunk& c, std::uint64_t file_bytes, int shards) {
  if (c.warm.programme_start || file_bytes == 0) return 1;
  const long double at = static_cast<long double>(c.warm.reader.bytes) * shards / file_bytes;
  return 1 + std::min(static_cast<int>(at), shards - 1);
}

nlohmann::json PartJson(const ChunkedOptions& inv, const RunModel& model,
                        const sim::ScanResult& scan, const std::vector<int>& indices,
                        const ChunkedRun* run, std::uint64_t program_fnv) {
  nlohmann::json j;
  j["format"] = kPartFormat;
  j["version"] = kPartVersion;
  j["tool_version"] = std::string(ToolVersion());
  j["program"] = inv.program;
  j["program_bytes"] = scan.bytes;
  j["program_fnv1a"] = Hex64(program_fnv);
  j["scene"] = inv.scene;
  j["dialect"] = inv.dialect;
  nlohmann::json fp = nlohmann::json::array();
  for (const auto& f : SceneFingerprints(*model.loaded.scene)) {
    fp.push_back({{"role", f.role}, {"fnv1a", Hex64(f.fnv1a)}});
  }
  j["scene_files"] = fp;
  j["no_collision"] = inv.no_collision;
  j["allow_mismatch"] = inv.allow_mismatch;
  j["shard"] = inv.plan.shard;
  j["shards"] = inv.plan.shards;
  j["chunks_total"] = scan.chunks;
  j["chunk_lines"] = inv.plan.chunk_lines;
  j["warm_lines"] = inv.plan.warm_lines;
  j["lines"] = scan.summary.lines;
  j["moves"] = scan.summary.moves;
  j["cycle_time_s"] = scan.summary.time_s;
  j["stitch_length_mm"] = model.stitch_length_mm;
  j["declared_stitches"] =
      model.declared_stitches ? nlohmann::json(*model.declared_stitches) : nlohmann::json(nullptr);
  if (indices.empty() || run == nullptr) {
    j["chunks"] = nullptr;
    return j;
  }
  j["chunks"] = {indices.front(), indices.back()};
  if (scan.chunks == 1) {
    // Not cut (fibre placement, or a programme with no safe point): this part is the whole
    // run; its reports are finished here (the afp.* rules cannot be carried in a part).
    const trace::TraceFileSummary summary{scan.summary.lines, scan.summary.moves,
                                          scan.summary.time_s, run->timed.Value()};
    verify::Report report =
        RunReport(inv.program, inv.scene, *model.loaded.scene, model.stitch_length_mm, summary);
    run->verifier->Finish(report);
    j["complete"] = {{"text", verify::ReportToText(report)},
                     {"json", verify::ReportToJson(report)},
                     {"junit", verify::ReportToJunit(report)},
                     {"errors", report.errors}};
    return j;
  }
  j["timed_sum"] = run->timed.Hex();
  j["start"] = run->start.Hex();
  j["end"] = run->end.Hex();
  run->verifier->CloseNeedleWindow();
  j["verifier"] = run->verifier->SavePartial();
  return j;
}

bool ReadPart(const std::string& file, Part& part, DiagnosticSink& sink) {
  const std::optional<std::string> text = ReadFile(file);
  if (!text) {
    ToolError(sink, "io-missing-file", "cannot read part " + file);
    return false;
  }
  part.file = file;
  part.j = nlohmann::json::parse(*text, nullptr, /*allow_exceptions=*/false);
  if (part.j.is_discarded() || !part.j.is_object() ||
      part.j.value("format", std::string()) != kPartFormat) {
    ToolError(sink, "part-bad",
              file +
                  ": not a whole verify part file (cut short by a killed shard, or another "
                  "file); run its shard again");
    return false;
  }
  if (part.j.value("version", 0) != kPartVersion) {
    ToolError(sink, "part-bad",
              file + ": part format version " + std::to_string(part.j.value("version", 0)) +
                  ", expected 1");
    return false;
  }
  for (const char* key : kSameKeys) {
    if (!part.j.contains(key)) {
      ToolError(sink, "part-bad", file + ": no '" + key + "'");
      return false;
    }
  }
  if (part.j.contains("chunks") && part.j["chunks"].is_array() && part.j["chunks"].size() == 2) {
    part.lo = part.j["chunks"][0].get<int>();
    part.hi = part.j["chunks"][1].get<int>();
  }
  return true;
}

bool PartsFit(std::vector<Part>& parts, DiagnosticSink& sink) {
  const Part& first = parts.front();
  for (const Part& p : parts) {
    for (const char* key : kSameKeys) {
      if (p.j[key] != first.j[key]) {
        ToolError(sink, "part-mismatch",
                  p.file + " and " + first.file + " differ in '" + key +
                      "': parts of different programmes, scenes or runs");
        return false;
      }
    }
  }
  std::vector<Part*> with;
  for (Part& p : parts) {
    if (p.lo >= 0) with.push_back(&p);
  }
  std::sort(with.begin(), with.end(), [](const Part* a, const Part* b) { return a->lo < b->lo; });
  const int total = first.j["chunks_total"].get<int>();
  const long lines = first.j["lines"].get<long>();
  int expect = 0;
  const auto missing = [&](int from, int to) {
    ToolError(sink, "part-missing",
              "chunks " + std::to_string(from) + ".." + std::to_string(to) + " of " +
                  std::to_string(total) + " (of the programme's " + std::to_string(lines) +
                  " lines) are in no part: a shard was killed or its part is missing; run it "
                  "again (" +
                  std::to_string(first.j["shards"].get<int>()) + " shards)");
  };
  for (const Part* p : with) {
    if (p->lo > expect) {
      missing(expect, p->lo - 1);
      return false;
    }
    if (p->lo < expect) {
      ToolError(sink, "part-duplicate", p->file + " repeats chunks another part holds");
      return false;
    }
    expect = p->hi + 1;
  }
  if (expect < total) {
    missing(expect, total - 1);
    return false;
  }
  std::vector<Part> ordered;
  for (Part* p : with) ordered.push_back(std::move(*p));
  parts = std::move(ordered);
  return true;
}

MergedReport MergeParts(const std::vector<std::string>& files, const scene::LoadOptions& load,
                        DiagnosticSink& sink) {
  MergedReport out;
  std::vector<Part> parts(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (!ReadPart(files[i], parts[i], sink)) return out;
  }
  if (!PartsFit(parts, sink)) return out;
  const nlohmann::json& head = parts.front().j;
  const std::string scene_file = head["scene"].get<std::string>();
  std::optional<LoadedScene> loaded = LoadScene(scene_file, load, sink);
  if (!loaded || !SceneFilesUnchanged(head, *loaded->scene, sink)) return out;
  if (parts.size() == 1 && parts.front().j.contains("complete")) {
    out.complete = CompleteOf(parts.front(), sink);
    if (!out.complete) return out;
    out.status = out.complete->errors == 0 ? RunStatus::kOk : RunStatus::kFindings;
    return out;
  }
  const std::unique_ptr<RunModel> model = ModelOf(head, std::move(*loaded), sink);
  if (!model) return out;
  verify::Verifier merged(model->Rules(), false);
  ExactSum timed;
  if (!AbsorbParts(parts, *model, merged, timed, sink)) return out;
  const trace::TraceFileSummary summary{head["lines"].get<long>(), head["moves"].get<long>(),
                                        head["cycle_time_s"].get<double>(), timed.Value()};
  out.report = RunReport(head["program"].get<std::string>(), scene_file, *model->loaded.scene,
                         model->stitch_length_mm, summary);
  merged.Finish(out.report);
  out.status = out.report.errors == 0 ? RunStatus::kOk : RunStatus::kFindings;
  return out;
}

}  // namespace stitchsim::run
