// skybake check-tiling: reads a 2D or 3D texture skybake wrote (DDS, EXR,
// VDB) and checks that every mip level and array layer tiles
// (core/tiling.hpp); exit 0 when every file tiles, 1 when a seam shows or a
// file is too small or too rough for a seam to show, 4 only for a file that
// cannot be read. One line per file, then one per level, layer, axis and
// channel with its scores and limits.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/texture_args.hpp"
#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "core/error.hpp"
#include "core/tiling.hpp"
#include "io/exr.hpp"
#include "io/texture_file.hpp"

namespace skybake::cli {

namespace {

nlohmann::json number(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json("inf");
}

nlohmann::json score_json(const SeamScore& s) {
  return {{"seam", number(s.seam)},
          {"median", number(s.median)},
          {"q90", number(s.q90)},
          {"limit", number(s.limit)}};
}

const char* headline(TilingVerdict v) {
  switch (v) {
    case TilingVerdict::tiles:
      return "TILES      ";
    case TilingVerdict::seam:
      return "NO TILE    ";
    default:
      return "CANNOT TELL";
  }
}

// Reads `file`; an EXR whose pixels no longer match its skybake:shape or
// skybake:layout (cropped or resized by another tool) is a picture all the
// same, measured as stored, with the mismatch in `note`.
LoadedTexture read_for_tiling(const std::string& file, uint64_t budget, std::string& note) {
  try {
    return read_texture_file(file, budget);
  } catch (const IoError& e) {
    if (std::filesystem::path(file).extension() != ".exr") throw;
    LoadedTexture loaded;
    try {
      loaded.texture = read_exr(file, ExrShape::as_stored, budget);
    } catch (const IoError&) {
      throw e;
    }
    loaded.format = "exr";
    note = fmt::format("measured as stored: {}", e.what());
    return loaded;
  }
}

// The JSON record of one file's measure.
nlohmann::json tiling_json(const std::string& file, const LoadedTexture& loaded,
                           const TilingReport& report, const std::string& note) {
  nlohmann::json axes = nlohmann::json::array();
  for (const AxisTiling& a : report.axes)
    axes.push_back({{"level", a.level},
                    {"layer", a.layer},
                    {"axis", std::string(1, a.axis)},
                    {"channel", a.channel},
                    {"texels", a.texels},
                    {"verdict", tiling_verdict_name(a.verdict)},
                    {"reason", a.reason},
                    {"values", score_json(a.values)},
                    {"slopes", score_json(a.slopes)},
                    {"contrast", number(a.contrast)},
                    {"ratio", number(a.ratio)},
                    {"tiles", a.tiles}});
  nlohmann::json entry = {{"file", file},
                          {"tiles", report.tiles},
                          {"verdict", tiling_verdict_name(report.verdict)},
                          {"shape", loaded.texture.shape_string()},
                          {"mip_levels", 1 + loaded.lower_levels.size()},
                          {"worst_ratio", number(report.worst_ratio)},
                          {"axes", axes}};
  if (!note.empty()) entry["note"] = note;
  return entry;
}

// One line per judged axis (a mip level none of whose axes is judged takes one line).
void print_axes(const Texture& tex, const TilingReport& report) {
  for (size_t i = 0; i < report.axes.size(); ++i) {
    const AxisTiling& a = report.axes[i];
    size_t end = i;
    while (end < report.axes.size() && report.axes[end].level == a.level &&
           report.axes[end].verdict == TilingVerdict::not_judged)
      ++end;
    if (end > i && (end == report.axes.size() || report.axes[end].level != a.level) &&
        (i == 0 || report.axes[i - 1].level != a.level)) {
      std::printf("  level %d  not judged: %s\n", a.level, a.reason.c_str());
      i = end - 1;
      continue;
    }
    const std::string where =
        fmt::format("level {}{}  axis {}  {:<4} {:>5} texels", a.level,
                    tex.layers > 1 ? fmt::format("  layer {}", a.layer) : "", a.axis, a.channel,
                    a.texels);
    if (a.verdict == TilingVerdict::tiles && a.reason == "constant") {
      std::printf("  %s  constant  ok\n", where.c_str());
    } else if (a.verdict == TilingVerdict::tiles || a.verdict == TilingVerdict::seam) {
      std::printf("  %s  values %.3g (limit %.3g)  slopes %.3g (limit %.3g)  contrast %.3g  %s\n",
                  where.c_str(), a.values.seam, a.values.limit, a.slopes.seam, a.slopes.limit,
                  a.contrast, a.verdict == TilingVerdict::seam ? "SEAM" : "ok");
    } else {
      std::printf("  %s  %s: %s\n", where.c_str(),
                  a.verdict == TilingVerdict::cannot_tell ? "CANNOT TELL" : "not judged",
                  a.reason.c_str());
    }
  }
}

}  // namespace

int run_check_tiling(const CheckTilingArgs& args) {
  const std::vector<std::string> inputs = expand_texture_files(args.files);
  TilingVerdict overall = TilingVerdict::tiles;
  nlohmann::json files = nlohmann::json::array();
  for (const std::string& file : inputs) {
    std::string note;
    const LoadedTexture loaded = read_for_tiling(file, args.max_memory, note);
    const Texture& tex = loaded.texture;
    const TilingReport report = measure_tiling(tex, loaded.lower_levels, args.tolerance);
    if (report.verdict == TilingVerdict::seam ||
        (report.verdict == TilingVerdict::cannot_tell && overall == TilingVerdict::tiles))
      overall = report.verdict;
    files.push_back(tiling_json(file, loaded, report, note));
    if (args.json) continue;
    const size_t levels = 1 + loaded.lower_levels.size();
    std::printf("%s  %s (%s%s, tolerance %.3g)\n", headline(report.verdict), file.c_str(),
                tex.shape_string().c_str(),
                levels > 1 ? fmt::format(", {} mip levels", levels).c_str() : "", args.tolerance);
    if (!note.empty()) std::printf("  note: %s\n", note.c_str());
    if (!args.quiet) print_axes(tex, report);
  }
  if (args.json)
    std::cout << nlohmann::json{{"tiles", overall == TilingVerdict::tiles},
                                {"verdict", tiling_verdict_name(overall)},
                                {"tolerance", args.tolerance},
                                {"files", files}}
                     .dump(2)
              << "\n";
  return overall == TilingVerdict::tiles ? kExitOk : kExitFailure;
}

}  // namespace skybake::cli
