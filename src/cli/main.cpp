// The skybake executable: parses the command line with CLI11 (only here) and
// dispatches to the subcommands of commands.hpp. Errors are caught once:
// `skybake: error: <message>` on stderr and the exit code of core/error.hpp.
#include <cctype>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "core/error.hpp"
#include "core/fresh_pages.hpp"
#include "io/atomic_file.hpp"
#include "io/texture_file.hpp"
#include "pipeline/output_writer.hpp"
#include "pipeline/product.hpp"

namespace {

using namespace skybake::cli;

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

// "EXR, DDS, KTX2 or VDB": format names in upper case, the last joined by `last`.
std::string formats_help(const std::vector<std::string>& formats, const std::string& last) {
  std::string s;
  for (size_t i = 0; i < formats.size(); ++i) {
    if (i > 0) s += i + 1 == formats.size() ? " " + last + " " : ", ";
    for (char c : formats[i]) s += char(std::toupper((unsigned char)c));
  }
  return s;
}

// The names --only takes, every registered product, wrapped at 90 columns.
std::string only_products_help() {
  std::string s = "\nProducts (--only):\n", line = " ";
  for (const skybake::ProductInfo& p : skybake::product_registry()) {
    if (line.size() + p.name.size() > 88) {
      s += line + "\n";
      line = " ";
    }
    line += " " + p.name;
  }
  return s + line + "\n";
}

const char* kFooter = R"(
Examples:
  skybake bake presets/earth.json                 bake what the scene asks for into out/earth/
  skybake bake presets/*.json --threads 2 --json  farm mode: machine-readable summary on stdout
  skybake plan presets/earth.json                 show products, dependencies and what is stale
  skybake info out/earth/transmittance.dds        read a baked file back
  skybake check-tiling out/clouds_hzd/noise_shape.dds   verify a noise volume tiles
  skybake report presets/earth.json --quick      error vs bake time -> out/earth/report/report.html

Errors are one line on stderr: "skybake: error: <message>".
Exit codes: 0 ok, 1 check failed, 2 usage, 3 invalid preset, 4 file error, 5 internal error.
Docs: README.md, docs/presets.md.)";

// Options that mean the same in every command that has them.

void add_presets_option(CLI::App* cmd, std::vector<std::string>& presets) {
  cmd->add_option("presets", presets,
                  "Scene presets: files, folders (their scene presets, recursively) or globs")
      ->required();
}

void add_out_option(CLI::App* cmd, std::string& out_dir, const std::string& help) {
  cmd->add_option("-o,--out", out_dir, "Output folder" + help)->capture_default_str();
}

void add_only_option(CLI::App* cmd, std::vector<std::string>& only, const std::string& help) {
  cmd->add_option("--only", only, help)->delimiter(',');
}

void add_threads_option(CLI::App* cmd, int& threads) {
  cmd->add_option("-j,--threads", threads, "Worker threads; 0 = all cores")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
}

void add_json_flag(CLI::App* cmd, bool& json, const std::string& help) {
  cmd->add_flag("--json", json, help);
}

CLI::App* add_bake_command(CLI::App& app, BakeArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "bake", "Bake the outputs each scene preset asks for (only what is stale).");
  add_presets_option(cmd, args.presets);
  add_out_option(cmd, args.out_dir, "; files go to DIR/<scene>/");
  add_only_option(cmd, args.only,
                  "Bake only these products (comma separated); their dependencies are read back "
                  "when current on disk, else computed in memory");
  add_threads_option(cmd, args.threads);
  cmd->add_flag("-f,--force", args.force, "Bake even outputs that are up to date");
  cmd->add_flag("--verify", args.verify,
                "Hash every recorded file instead of trusting a matching size and time");
  cmd->add_flag("--strict", args.strict,
                "Exit 1 when any output has a warning (after writing and recording everything)");
  cmd->add_flag("--emit-shader-constants", args.emit_shader_constants,
                "Write <output>.glsl and <output>.hlsl beside each output (baked or current) with "
                "the constants its manifest entry records, and list them in the manifest");
  cmd->add_flag("-q,--quiet", args.quiet,
                "No progress, no line per output, no summary line (warnings still on stderr)");
  cmd->add_flag("-v,--verbose", args.verbose,
                "Log on stderr why each output is (not) baked, what was read back or computed "
                "in memory, threads and timings");
  add_json_flag(cmd, args.json, "Print a machine-readable summary on stdout");
  cmd->footer(
      only_products_help() +
      "\nOutputs are written to a temporary name and renamed when complete; "
      "DIR/<scene>/manifest.json records every output (files, shape, channels, "
      "parameterization, input hash, bake time). Re-running an unchanged bake does no work. "
      "The last line counts the outputs baked and up to date, the warnings and the seconds.");
  return cmd;
}

CLI::App* add_validate_command(CLI::App& app, ValidateArgs& args) {
  CLI::App* cmd =
      app.add_subcommand("validate", "Check presets against schemas/ and the semantic rules.");
  cmd->add_option("presets", args.presets,
                  "Preset files (JSON) of any kind: scene, planet, atmosphere or clouds, by "
                  "their $schema; folders (their scene presets, recursively) or globs")
      ->required();
  cmd->add_flag("--strict", args.strict, "Keys that have no effect are errors, not warnings");
  cmd->add_flag("-q,--quiet", args.quiet, "Print only errors and warnings");
  add_json_flag(cmd, args.json, "Print results as JSON on stdout");
  cmd->footer("\nEvery problem of a file is listed (the first 20). Exit 0 when every preset is "
              "valid (warnings on stderr: keys that have no effect), 1 otherwise or with a "
              "warning under --strict; 4 when a file does not exist.");
  return cmd;
}

void add_plan_emit_options(CLI::App* cmd, PlanArgs& args) {
  CLI::Option* emit = cmd->add_option("--emit", args.emit, "Emit a build file: ninja or slurm")
                          ->check(CLI::IsMember({"ninja", "slurm"}));
  cmd->add_option("--emit-file", args.emit_file, "Write the emitted file here (default: stdout)")
      ->needs(emit);
  cmd->add_option("--launcher", args.launcher,
                  "ninja: prefix of every edge, e.g. \"srun -N1 -n1 -c1 --exact --quiet\"")
      ->needs(emit);
  cmd->add_option("--task-threads", args.threads, "--threads of each emitted task")
      ->capture_default_str()
      ->check(CLI::Range(1, 1024))
      ->needs(emit);
  cmd->add_flag("--strict", args.strict,
               "Every emitted task runs `bake --strict`: a warning fails its task")
      ->needs(emit);
  cmd->add_option("--edges", args.edges,
                  "ninja: one edge (one process) per scene, baking all its products, or per "
                  "product")
      ->capture_default_str()
      ->check(CLI::IsMember({"scene", "product"}))
      ->needs(emit);
  cmd->add_option("--chunk", args.chunk,
                  "Presets per task: per slurm array task, or per ninja edge of --edges scene")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000))
      ->needs(emit);
  cmd->add_option("--max-parallel", args.max_parallel,
                  "At most this many bakes at once: slurm array tasks, or ninja edges (a pool, "
                  "whatever -j) (0 = no limit)")
      ->capture_default_str()
      ->needs(emit);
  cmd->get_option("--json")->excludes(emit);
}

CLI::App* add_plan_command(CLI::App& app, PlanArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "plan", "Show the product graph of scenes or a catalog; emit it for ninja or Slurm.");
  add_presets_option(cmd, args.catalog);
  add_out_option(cmd, args.out_dir, " the bakes write to (read for the state, not written)");
  add_only_option(cmd, args.only, "Plan only these products (comma separated)");
  add_json_flag(cmd, args.json,
                "JSON on stdout: per-scene graphs plus the farm graph of stale nodes and edges");
  add_plan_emit_options(cmd, args);
  cmd->footer(
      only_products_help() +
      "\nExamples:\n"
      "  skybake plan presets/earth.json                       graph and state of one scene\n"
      "  skybake plan presets/ --json                          farm graph of a catalog\n"
      "  skybake plan presets/ -o out --emit ninja --emit-file build.ninja && ninja -f "
      "build.ninja -j 8\n"
      "  skybake plan presets/ --emit ninja --launcher \"srun -N1 -n1 -c1 --exact --quiet\" "
      "--emit-file build.ninja\n"
      "  skybake plan 'catalog/*.json' --emit slurm --chunk 10 --emit-file bake.sbatch && sbatch "
      "bake.sbatch");
  return cmd;
}

// --max-memory of info and check-tiling: a size such as 1G, 512M or bytes.
void add_max_memory_option(CLI::App* cmd, uint64_t& bytes) {
  cmd->add_option("--max-memory", bytes,
                  "Refuse a file whose header announces more than this much decoded data "
                  "(e.g. 512M, 4G; default 1G), before anything is allocated")
      ->transform(CLI::AsSizeValue(false))
      ->check(CLI::Range(uint64_t(1) << 20, skybake::kNoReadBudget));
}

CLI::App* add_info_command(CLI::App& app, InfoArgs& args) {
  CLI::App* cmd =
      app.add_subcommand("info", "Read back " + formats_help(skybake::texture_file_formats(), "or") +
                                     " files and print shape and metadata.");
  cmd->add_option("files", args.files, "Files written by skybake, folders of them or quoted glob patterns")->required();
  add_max_memory_option(cmd, args.max_memory);
  add_json_flag(cmd, args.json, "Print as JSON on stdout");
  return cmd;
}

CLI::App* add_check_tiling_command(CLI::App& app, CheckTilingArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "check-tiling", "Check that baked 2D/3D textures tile (" +
                          formats_help(skybake::texture_file_formats(), "or") +
                          " files); exit 1 if not.");
  cmd->add_option("files", args.files, "Texture files written by skybake, folders of them or quoted glob patterns")->required();
  cmd->add_option("-t,--tolerance", args.tolerance,
                  "The seam's jump score may exceed the median interior face's by this "
                  "fraction, or by 4 spreads of the interior faces if more")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1000.0));
  cmd->add_flag("-q,--quiet", args.quiet, "One line per file");
  add_max_memory_option(cmd, args.max_memory);
  add_json_flag(cmd, args.json, "Print the scores as JSON on stdout");
  cmd->footer(
      "\nEvery mip level, array layer, axis and channel: the jump and the turn of slope across "
      "the wrapped face, each against the faces beside it, compared with the same scores of the "
      "interior faces. Exit 1 when a seam stands out, or when level 0 is too small or too rough "
      "(white noise) for a seam to show. See docs/clouds.md \"Checking that a texture tiles\".");
  return cmd;
}

CLI::App* add_report_command(CLI::App& app, ReportArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "report", "Measure each product's error against run time; write report.json and HTML.");
  add_presets_option(cmd, args.presets);
  add_out_option(cmd, args.out_dir, "; writes DIR/<scene>/report/");
  add_only_option(cmd, args.only, "Measure only these products (comma separated)");
  add_threads_option(cmd, args.threads);
  cmd->add_flag("--quick", args.quick, "Few ladder points, queries and paths (seconds, for tests)");
  cmd->add_option("--paths", args.paths,
                  "Path tracer paths per view for the sky radiance (0 = the level's: "
                  "65536, --quick 256)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1 << 24));
  cmd->add_flag("-q,--quiet", args.quiet, "No progress lines on stderr");
  add_json_flag(cmd, args.json, "Print the summary as JSON on stdout");
  cmd->footer(
      only_products_help() +
      "\nLadders of sample counts and sizes per table against independent references (adaptive "
      "quadrature, finer integration), sky radiance against the path tracer, float32/half "
      "findings, sky previews. Exit 0 whatever the accuracy; see docs/report.md.");
  return cmd;
}

// The arguments of every command, filled by the parse.
struct Arguments {
  BakeArgs bake;
  ValidateArgs validate;
  PlanArgs plan;
  InfoArgs info;
  CheckTilingArgs tiling;
  ReportArgs report;
};

struct Command {
  CLI::App* app;
  std::function<int()> run;
};

std::vector<Command> add_commands(CLI::App& app, Arguments& a) {
  return {{add_bake_command(app, a.bake), [&a] { return run_bake(a.bake); }},
          {add_validate_command(app, a.validate), [&a] { return run_validate(a.validate); }},
          {add_plan_command(app, a.plan), [&a] { return run_plan(a.plan); }},
          {add_info_command(app, a.info), [&a] { return run_info(a.info); }},
          {add_check_tiling_command(app, a.tiling), [&a] { return run_check_tiling(a.tiling); }},
          {add_report_command(app, a.report), [&a] { return run_report(a.report); }}};
}

void configure_app(CLI::App& app) {
  app.set_version_flag("--version", "skybake " SKYBAKE_VERSION);
  app.require_subcommand(1);
  app.footer(products_help() + kFooter);
  app.get_formatter()->column_width(34);
}

std::vector<std::string> command_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* cmd : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(cmd->get_name());
  return names;
}

std::vector<std::string> option_names(const CLI::App& cmd) {
  std::vector<std::string> names;
  for (const CLI::Option* opt : cmd.get_options()) {
    for (const std::string& n : opt->get_lnames()) names.push_back("--" + n);
    for (const std::string& n : opt->get_snames()) names.push_back("-" + n);
  }
  return names;
}

bool is_option(const std::string& arg) { return arg.size() > 1 && arg[0] == '-'; }

// The one line for a command line CLI11 refused: an unknown option or command
// is named (with a suggestion), before CLI11's complaint about what it then
// misses ("presets is required"); otherwise CLI11's own message.
std::string parse_error_message(const CLI::App& app, const CLI::ParseError& e) {
  const std::vector<CLI::App*> parsed = app.get_subcommands();
  for (const CLI::App* cmd : parsed)
    for (const std::string& arg : cmd->remaining())
      if (is_option(arg)) return unknown_option_message(cmd->get_name(), arg, option_names(*cmd));
  for (const std::string& arg : app.remaining()) {
    if (is_option(arg)) return unknown_option_message("", arg, option_names(app));
    if (parsed.empty()) return unknown_command_message(arg, command_names(app));
  }
  if (parsed.empty()) return no_command_message(command_names(app));
  return e.what();
}

// --json anywhere on the command line: errors go to stdout as JSON too,
// also when the command line itself is refused.
bool wants_json(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--json") return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  skybake::keep_freed_memory();  // fresh pages are dear (core/fresh_pages.hpp)
  skybake::install_temporary_cleanup();  // SIGINT, SIGTERM: no temporaries left behind
  CLI::App app{"skybake " SKYBAKE_VERSION
               " - bakes real-time sky assets (atmosphere LUTs, cloud noise, weather textures)\n"
               "from JSON scene presets into " +
               formats_help(skybake::output_formats(), "and") + " files."};
  configure_app(app);
  Arguments args;
  args.plan.self = self_path(argv[0]);
  const std::vector<Command> commands = add_commands(app, args);
  const bool json = wants_json(argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    return print_error(parse_error_message(app, e), skybake::kExitUsage, json);
  }
  for (const Command& c : commands)
    if (c.app->parsed()) return run_reporting_errors(c.run, json);
  return print_error(no_command_message(command_names(app)), skybake::kExitUsage, json);
}
