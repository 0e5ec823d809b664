// skybake check-tiling: reads a 2D or 3D texture skybake wrote (DDS, EXR,
// VDB) and checks it tiles (core/tiling.hpp); exit 0 when every axis and
// channel tiles, 1 otherwise (idiff-style), with the ratio per face.
#include <cmath>
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "core/error.hpp"
#include "core/tiling.hpp"
#include "io/texture_file.hpp"

namespace skybake::cli {

int run_check_tiling(const CheckTilingArgs& args) {
  require_files(args.files);
  bool all_tile = true;
  nlohmann::json files = nlohmann::json::array();
  for (const std::string& file : args.files) {
    const LoadedTexture loaded = read_texture_file(file);
    const TilingReport report = measure_tiling(loaded.texture, args.tolerance);
    all_tile = all_tile && report.tiles;
    nlohmann::json axes = nlohmann::json::array();
    for (const AxisTiling& a : report.axes)
      axes.push_back({{"axis", std::string(1, a.axis)},
                      {"channel", a.channel},
                      {"seam_jump", a.seam_jump},
                      {"interior_jump", a.interior_jump},
                      {"ratio", std::isfinite(a.ratio) ? nlohmann::json(a.ratio) : "inf"},
                      {"tiles", a.tiles}});
    files.push_back({{"file", file}, {"tiles", report.tiles}, {"axes", axes}});
    if (args.json) continue;
    std::printf("%s  %s (%s, tolerance %.3g)\n", report.tiles ? "TILES  " : "NO TILE", file.c_str(),
                loaded.texture.shape_string().c_str(), args.tolerance);
    if (args.quiet) continue;
    for (const AxisTiling& a : report.axes)
      std::printf("  axis %c  channel %-4s seam %-10.4g interior %-10.4g ratio %-8.4g %s\n",
                  a.axis, a.channel.c_str(), a.seam_jump, a.interior_jump, a.ratio,
                  a.tiles ? "ok" : "FAIL");
  }
  if (args.json)
    std::cout << nlohmann::json{{"tiles", all_tile}, {"tolerance", args.tolerance},
                                {"files", files}}
                     .dump(2)
              << "\n";
  return all_tile ? kExitOk : kExitFailure;
}

}  // namespace skybake::cli
