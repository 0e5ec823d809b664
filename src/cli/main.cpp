// The skybake executable: parses the command line with CLI11 (only here) and
// dispatches to the subcommands of commands.hpp. Errors are caught once:
// `skybake: error: <message>` on stderr and the exit code of core/error.hpp.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "core/error.hpp"
#include "pipeline/product.hpp"

namespace {

// The absolute path of this executable, for emitted build files.
std::string self_path(const char* argv0) {
  std::error_code ec;
  const auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::absolute(argv0).string() : p.string();
}

std::string products_help() {
  std::string s = "\nProducts:\n";
  for (const skybake::ProductInfo& p : skybake::product_registry()) {
    std::string size;
    for (size_t i = 0; i < p.default_size.size(); ++i)
      size += (i ? "x" : "") + std::to_string(p.default_size[i]);
    s += "  " + p.name + std::string(p.name.size() < 20 ? 20 - p.name.size() : 1, ' ') + size +
         "  " + p.summary + "\n";
  }
  return s;
}

const char* kFooter = R"(
Examples:
  skybake bake presets/earth.json                 bake what the scene asks for into out/earth/
  skybake bake presets/*.json --threads 2 --json  farm mode: machine-readable summary on stdout
  skybake plan presets/earth.json                 show products, dependencies and what is stale
  skybake info out/earth/transmittance.dds        read a baked file back
  skybake check-tiling out/clouds_hzd/noise_shape.dds   verify a noise volume tiles
  skybake report presets/earth.json --quick      error vs bake time -> out/earth/report/report.html

Exit codes: 0 ok, 1 check failed, 2 usage, 3 invalid preset, 4 file error, 5 internal error.
Docs: README.md, docs/presets.md.)";

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"skybake " SKYBAKE_VERSION
               " - bakes real-time sky assets (atmosphere LUTs, cloud noise, weather textures)\n"
               "from JSON scene presets into EXR, DDS, VDB and PNG files."};
  app.set_version_flag("--version", "skybake " SKYBAKE_VERSION);
  app.require_subcommand(1);
  app.footer(products_help() + kFooter);
  app.get_formatter()->column_width(34);

  bool json_errors = false;

  skybake::cli::BakeArgs bake;
  CLI::App* bake_cmd = app.add_subcommand(
      "bake", "Bake the outputs each scene preset asks for (only what is stale).");
  bake_cmd->add_option("presets", bake.presets,
                       "Scene presets: files, folders (their scene presets, recursively) or globs")
      ->required();
  bake_cmd->add_option("-o,--out", bake.out_dir, "Output folder; files go to DIR/<scene>/")
      ->capture_default_str();
  bake_cmd->add_option("--only", bake.only,
                       "Bake only these products (comma separated); their dependencies are "
                       "computed in memory")
      ->delimiter(',');
  bake_cmd->add_option("-j,--threads", bake.threads, "Worker threads; 0 = all cores")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  bake_cmd->add_flag("-f,--force", bake.force, "Bake even outputs that are up to date");
  bake_cmd->add_flag("-q,--quiet", bake.quiet, "No progress and no summary lines");
  bake_cmd->add_flag("--json", bake.json, "Print a machine-readable summary on stdout");
  bake_cmd->footer(
      "\nOutputs are written to a temporary name and renamed when complete; "
      "DIR/<scene>/manifest.json records every output (files, shape, channels, "
      "parameterization, input hash, bake time). Re-running an unchanged bake does no work.");

  skybake::cli::ValidateArgs validate;
  CLI::App* validate_cmd =
      app.add_subcommand("validate", "Check presets against schemas/ and the semantic rules.");
  validate_cmd->add_option("presets", validate.presets, "Preset files (JSON)")->required();
  validate_cmd->add_flag("-q,--quiet", validate.quiet, "Print only errors");
  validate_cmd->add_flag("--json", validate.json, "Print results as JSON on stdout");
  validate_cmd->footer("\nExit 0 when every preset is valid, 1 otherwise.");

  skybake::cli::PlanArgs plan;
  plan.self = self_path(argv[0]);
  CLI::App* plan_cmd = app.add_subcommand(
      "plan", "Show the product graph of scenes or a catalog; emit it for ninja or Slurm.");
  plan_cmd->add_option("catalog", plan.catalog,
                       "Scene presets: files, folders (searched recursively) or glob patterns")
      ->required();
  plan_cmd->add_option("-d,--out-dir", plan.out_dir, "Output folder the bakes write to")
      ->capture_default_str();
  plan_cmd->add_option("--only", plan.only, "Restrict to these products")->delimiter(',');
  plan_cmd->add_flag("--json", plan.json,
                     "JSON: per-scene graphs plus the farm graph of stale nodes and edges");
  plan_cmd->add_option("--emit", plan.emit, "Emit a build file instead: ninja or slurm")
      ->check(CLI::IsMember({"ninja", "slurm"}));
  plan_cmd->add_option("-o,--output", plan.output, "Write the plan or emitted file here");
  plan_cmd->add_option("--launcher", plan.launcher,
                       "ninja: prefix of every edge, e.g. \"srun -N1 -n1 -c1 --exact --quiet\"");
  plan_cmd->add_option("--task-threads", plan.threads, "--threads of each emitted task")
      ->capture_default_str()
      ->check(CLI::Range(1, 1024));
  plan_cmd->add_option("--chunk", plan.chunk, "slurm: presets per array task")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  plan_cmd->add_option("--max-parallel", plan.max_parallel,
                       "slurm: at most this many array tasks at once (0 = no limit)")
      ->capture_default_str();
  plan_cmd->footer(
      "\nExamples:\n"
      "  skybake plan presets/earth.json                       graph and state of one scene\n"
      "  skybake plan presets/ --json                          farm graph of a catalog\n"
      "  skybake plan presets/ --emit ninja -o build.ninja && ninja -f build.ninja -j 8\n"
      "  skybake plan presets/ --emit ninja --launcher \"srun -N1 -n1 -c1 --exact --quiet\" -o "
      "build.ninja\n"
      "  skybake plan 'catalog/*.json' --emit slurm --chunk 10 -o bake.sbatch && sbatch "
      "bake.sbatch");

  skybake::cli::InfoArgs info;
  CLI::App* info_cmd =
      app.add_subcommand("info", "Read back EXR, DDS or VDB files and print shape and metadata.");
  info_cmd->add_option("files", info.files, "Files written by skybake")
      ->required()
      ->check(CLI::ExistingFile);
  info_cmd->add_flag("--json", info.json, "Print as JSON on stdout");

  skybake::cli::CheckTilingArgs tiling;
  CLI::App* tiling_cmd = app.add_subcommand(
      "check-tiling", "Check that baked 2D/3D textures tile (DDS, EXR, VDB); exit 1 if not.");
  tiling_cmd->add_option("files", tiling.files, "Texture files written by skybake")
      ->required()
      ->check(CLI::ExistingFile);
  tiling_cmd->add_option("-t,--tolerance", tiling.tolerance,
                         "A face passes when its seam jump <= (1 + T) x the largest interior "
                         "jump along that axis")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1000.0));
  tiling_cmd->add_flag("-q,--quiet", tiling.quiet, "One line per file");
  tiling_cmd->add_flag("--json", tiling.json, "Print the ratios as JSON on stdout");
  tiling_cmd->footer(
      "\nFor each axis and channel: the largest jump between neighbours across the wrapped "
      "face against the largest jump between interior neighbours (the ratio). A tileable "
      "texture's seam is just another neighbour face (ratio near or below 1).");

  skybake::cli::ReportArgs report;
  CLI::App* report_cmd = app.add_subcommand(
      "report", "Measure each product's error against run time; write report.json and HTML.");
  report_cmd->add_option("presets", report.presets, "Scene preset files (JSON)")->required();
  report_cmd->add_option("-o,--out", report.out_dir, "Output folder; writes DIR/<scene>/report/")
      ->capture_default_str();
  report_cmd->add_option("--products", report.products,
                         "Measure only these products (comma separated)")
      ->delimiter(',');
  report_cmd->add_option("-j,--threads", report.threads, "Worker threads; 0 = all cores")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  report_cmd->add_flag("--quick", report.quick,
                       "Few ladder points, queries and paths (seconds, for tests)");
  report_cmd->add_option("--paths", report.paths,
                         "Path tracer paths per view for the sky radiance (0 = the level's: "
                         "65536, --quick 256)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1 << 24));
  report_cmd->add_flag("-q,--quiet", report.quiet, "No progress lines on stderr");
  report_cmd->add_flag("--json", report.json, "Print the summary as JSON on stdout");
  report_cmd->footer(
      "\nLadders of sample counts and sizes per table against independent references (adaptive "
      "quadrature, finer integration), sky radiance against the path tracer, float32/half "
      "findings, sky previews. Exit 0 whatever the accuracy; see docs/report.md.");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : skybake::kExitUsage;
  }

  json_errors = (bake_cmd->parsed() && bake.json) || (plan_cmd->parsed() && plan.json) ||
                (info_cmd->parsed() && info.json) || (tiling_cmd->parsed() && tiling.json) ||
                (report_cmd->parsed() && report.json);
  try {
    if (bake_cmd->parsed()) return skybake::cli::run_bake(bake);
    if (validate_cmd->parsed()) return skybake::cli::run_validate(validate);
    if (plan_cmd->parsed()) return skybake::cli::run_plan(plan);
    if (info_cmd->parsed()) return skybake::cli::run_info(info);
    if (tiling_cmd->parsed()) return skybake::cli::run_check_tiling(tiling);
    if (report_cmd->parsed()) return skybake::cli::run_report(report);
  } catch (const skybake::Error& e) {
    std::fprintf(stderr, "skybake: error: %s\n", e.what());
    if (json_errors)
      std::cout << nlohmann::json{{"ok", false}, {"error", e.what()}, {"exit_code", e.exit_code()}}
                       .dump(2)
                << "\n";
    return e.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "skybake: internal error: %s\n", e.what());
    return skybake::kExitInternal;
  }
  return skybake::kExitUsage;
}
