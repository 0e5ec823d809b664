// skybake info: reads back an EXR, DDS or VDB written by skybake and prints
// its shape, encoding, channels (with value ranges) and metadata.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "cli/texture_args.hpp"
#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "core/error.hpp"
#include "core/metadata_json.hpp"
#include "io/texture_file.hpp"

namespace skybake::cli {

namespace {

nlohmann::json channel_stats(const Texture& tex) {
  nlohmann::json stats = nlohmann::json::array();
  const int nc = tex.channel_count();
  for (int c = 0; c < nc; ++c) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0.0;
    for (size_t i = size_t(c); i < tex.data.size(); i += size_t(nc)) {
      lo = std::min(lo, double(tex.data[i]));
      hi = std::max(hi, double(tex.data[i]));
      sum += tex.data[i];
    }
    const double n = double(tex.texel_count());
    stats.push_back({{"name", tex.channels[c]}, {"min", lo}, {"max", hi}, {"mean", sum / n}});
  }
  return stats;
}

// The texel layout of a Hillaire-family table (atmosphere/table_convention.hpp):
// its "convention", skybake's when it records none; empty for other files.
std::string table_convention_text(const Texture& tex) {
  if (!tex.metadata.count("product")) return "";
  const std::string product = meta_string(tex.metadata, "product");
  for (const char* p : {"transmittance", "multiscattering", "skyview", "aerial_perspective"})
    if (product == p)
      return tex.metadata.count("convention") ? meta_string(tex.metadata, "convention")
                                              : std::string("skybake");
  return "";
}

}  // namespace

int run_info(const InfoArgs& args) {
  const std::vector<std::string> inputs = expand_texture_files(args.files);
  nlohmann::json all = nlohmann::json::array();
  for (const std::string& file : inputs) {
    const LoadedTexture loaded = read_texture_file(file, args.max_memory);
    const Texture& tex = loaded.texture;
    const nlohmann::json stats = channel_stats(tex);
    const nlohmann::json meta = metadata_to_json(tex.metadata);
    const std::string convention = table_convention_text(tex);
    all.push_back({{"file", file},
                   {"format", loaded.format},
                   {"encoding", loaded.encoding},
                   {"width", tex.width},
                   {"height", tex.height},
                   {"depth", tex.depth},
                   {"layers", tex.layers},
                   {"mip_levels", loaded.mip_levels},
                   {"channels", stats},
                   {"metadata", meta},
                   {"details", loaded.details}});
    if (!convention.empty()) all.back()["convention"] = convention;
    // A Psi_ms fitted to Hillaire's demo march (atmosphere/hillaire_demo_march_fit.hpp).
    const bool march_fit = tex.metadata.count("demo_march_fit") > 0;
    if (march_fit) all.back()["demo_march_fit"] = true;
    if (args.json) continue;
    std::printf("%s\n  format    %s (%s)\n  shape     %s (width x height%s%s), %d mip level%s\n",
                file.c_str(), loaded.format.c_str(), loaded.encoding.c_str(),
                tex.shape_string().c_str(), tex.depth > 1 ? " x depth" : "",
                tex.layers > 1 ? " [layers]" : "", loaded.mip_levels,
                loaded.mip_levels == 1 ? "" : "s");
    if (!convention.empty())
      std::printf("  convention %s%s\n", convention.c_str(),
                  march_fit ? ", Psi_ms fitted to his march (demo_march_fit)" : "");
    std::printf("  channels\n");
    for (const auto& s : stats)
      std::printf("    %-8s min %-12.6g max %-12.6g mean %.6g\n",
                  s["name"].get<std::string>().c_str(), s["min"].get<double>(),
                  s["max"].get<double>(), s["mean"].get<double>());
    if (!loaded.details.empty()) {
      std::printf("  header\n");
      for (const auto& [k, v] : loaded.details.items())
        std::printf("    %-22s %s\n", k.c_str(), v.is_string() ? v.get<std::string>().c_str()
                                                               : v.dump().c_str());
    }
    if (!tex.metadata.empty()) {
      std::printf("  metadata\n");
      for (const auto& [k, v] : tex.metadata)
        std::printf("    %-22s %s\n", k.c_str(), meta_text(v).c_str());
    }
  }
  if (args.json) std::cout << nlohmann::json{{"files", all}}.dump(2) << "\n";
  return kExitOk;
}

}  // namespace skybake::cli
