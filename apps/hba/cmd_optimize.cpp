// `hba optimize DATA [MORE...] -o OUT`: the whole method on a dataset (or
// on several sessions of one place, optimize_sessions.cpp).
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "core/staging_folder.hpp"
#include "core/temporary_folder.hpp"
#include "enum_choice.hpp"
#include "file_checks.hpp"
#include "hba/core/error.hpp"
#include "hba/io/scan_formats.hpp"
#include "hba/pipeline/deskew_passes.hpp"
#include "hba/settings/settings_file.hpp"
#include "hba/voxel/downsampled_scan_source.hpp"
#include "json_text.hpp"
#include "memory_check.hpp"
#include "number_checks.hpp"
#include "optimize_parts.hpp"
#include "output_dir.hpp"
#include "process_group.hpp"

namespace hba::cli {
namespace {
namespace fs = std::filesystem;
using namespace optimize;

void run(const Args& args) {
  const HbaSettings settings = mergeSettings(args);
  if (args.print_config) {
    std::cout << settings::settingsToYaml(settings);
    return;
  }
  // Required unless --print-config (CLI11 cannot say "unless").
  if (args.data.dir.empty()) throw CLI::RequiredError("DIR");
  if (args.output.empty() && !args.print_plan) throw CLI::RequiredError("--output");
  // Kept clouds and maps go to the temporary folder: a wrong TMPDIR is
  // refused before any work, naming it.
  temporaryFolder();
  // Under mpirun every process runs the method, sharing its work (which
  // stage runs where: runStages, src/pipeline/hierarchical_ba.cpp); the first
  // alone checks the conventions and writes the outputs.
  const dist::Group& group = processGroup();
  if (args.print_plan && (!args.map.empty() || !args.fixed.empty() || !args.more_sessions.empty()))
    throw CLI::ValidationError("--print-plan", "plans one dataset: not with --map, --fixed or more sessions");
  if (!args.map.empty() || !args.fixed.empty()) {
    if (group.size() > 1)
      throw Error("--map and --fixed do not run under mpirun yet: run them in one process");
    return runWithMap(args, settings);
  }
  if (!args.more_sessions.empty()) {
    if (group.size() > 1)
      throw Error("several sessions do not run under mpirun yet: run them in one process");
    return runSessions(args, settings);
  }

  if (!args.print_plan) refuseProtectedFolder(args.output);
  io::Dataset dataset = args.data.open();
  if (!args.print_plan) refuseOutputInsideInput(args.output, dataset);
  const pipeline::ClosureInputs closures = readClosureInputs(args, {&dataset}, {0}, dataset.size());
  const std::optional<Trajectory> gt = readGroundTruth(args, dataset, dataset.size());
  // One source of the scans for the memory estimate, the convention check,
  // the optimization and the picture.
  const io::DatasetScanSource scans(dataset);
  // The run worked out once, from the settings and a few scans; one that
  // cannot fit is refused before any output or heavy work.
  const pipeline::Plan plan = pipeline::planRun(scans, settings);
  if (args.print_plan) {
    std::cout << pipeline::planToJson(plan).dump(2) << "\n";
    return;
  }
  const nlohmann::json memory = checkMemory(plan, args.no_memory_check);
  // Everything is written beside OUT and moved into place at the end: no
  // half-written folder, no earlier run's files beside this run's.
  std::optional<StagingFolder> staging;
  if (group.root()) {
    staging.emplace(args.output, args.force, "hba optimize");
    announceReplacement(*staging);
  }
  const nlohmann::json conventions =
      group.root() ? checkConventions(args, voxel::DownsampledScanSource(scans, settings.scan_voxel), dataset)
                   : nlohmann::json();
  spdlog::info("dataset: {} ({} layout), {} scans, poses from {}", dataset.root().string(), dataset.layout(),
               dataset.size(), dataset.posesFile().string());
  spdlog::debug("settings: {}", jsonText(settings::settingsToJson(settings)));  // also in report.json
  // -j (a tbb::global_control in main), resolved once by the plan: the pose
  // graph's Ceres solve runs on it too.
  spdlog::info("threads: {}{}", plan.settings.threads,
               group.size() > 1 ? fmt::format(" in each of {} processes", group.size()) : "");

  pipeline::DatasetRun run = pipeline::runWithDeskewPasses(dataset, scans, dataset.trajectory().poses, plan,
                                                           closures, args.deskew_passes, group);
  const pipeline::HbaResult& result = run.result;
  if (!group.root()) return;
  const fs::path& out = staging->path();

  std::vector<std::string> written = writeOptimizedPoses(out, dataset, result.poses);
  if (args.every_scan) {
    for (std::string& name : writeEveryScanPoses(out, dataset, result.poses))
      written.push_back(std::move(name));
  }
  nlohmann::json report = reportJson(result, dataset, args.data, settings, conventions);
  report["memory_estimate"] = memory;
  if (gt) report["window_errors"] = windowErrorsReport(result, dataset.trajectory().poses, *gt);
  if (dataset.pointTimes()) report["deskew"] = pipeline::deskewReport(dataset, run);
  report = writeReport(out, report);

  const bool drawn = !args.no_render &&
                     writePicture(scans, result, settings.scan_voxel, dataset.trajectory().poses, gt, out);
  const bool paged =
      !args.no_report_page && writeReportPage(scans, result, settings.scan_voxel, dataset.trajectory().poses,
                                              gt, report, folderName(dataset.root()), out);
  staging->commit();
  spdlog::info("done in {:.1f} s (peak memory {:.0f} MiB): {}", result.report.seconds_total, peakMemoryMiB(),
               staging->destination().string());
  spdlog::info("wrote {}, report.json{}{}", fmt::format("{}", fmt::join(written, ", ")),
               drawn ? ", before_after.png" : "", paged ? ", report.html" : "");
}

}  // namespace

void registerOptimizeCommand(CLI::App& app) {
  auto args = std::make_shared<Args>();
  auto* command =
      app.add_subcommand("optimize", "Optimize the poses of a sequence (hierarchical BA + pose graph)");
  args->data.addTo(command);
  command->get_option("DIR")->required(false);
  command->add_option("MORE", args->more_sessions,
                      "More sessions of the same place, optimized with DIR into one map in DIR's frame "
                      "(docs/closure.md)");
  command
      ->add_option("--align", args->align,
                   "With several sessions, how each later one is placed in the first one's frame at the "
                   "start: register (found from their overlap), identity (already in one frame), or a "
                   "file with one 'tx ty tz qx qy qz qw' line per later session")
      ->check(nameOrFile({"register", "identity"}, "a file of transforms"))
      ->capture_default_str();
  command
      ->add_option("--map", args->map,
                   "A map that stays put (a " + io::scanFormatList(true) +
                       " cloud, e.g. from hba map, or an earlier "
                       "output folder): DIR is placed in it, optimized and refined against it; poses in the "
                       "map's frame (docs/closure.md)")
      ->check(CLI::ExistingPath);
  command
      ->add_option("--fixed", args->fixed,
                   "As --map, with the map given as a dataset (scans and poses) whose poses stay put")
      ->check(CLI::ExistingDirectory);
  command->add_option("-o,--output", args->output,
                      "Output folder (created; never inside the input; a non-empty one needs --force)");
  command->add_flag("--print-config", args->print_config,
                    "Print every setting (defaults, --config, flags) as a commented YAML file for "
                    "--config, and stop");
  command->add_flag("--print-plan", args->print_plan,
                    "Print what the run would do, as JSON (windows, final voxel, layers, threads, the "
                    "memory it needs; from the settings and a few scans read), and stop: nothing is "
                    "optimized or written");
  command->add_flag("--force", args->force, "Replace a non-empty output folder (as a whole, at the end)");
  command
      ->add_option("--gt", args->ground_truth,
                   "Ground-truth trajectory: drawn in the picture and the page, and every window of the "
                   "pyramid measured against it (report.json's window_errors; default: DIR/gt.txt if "
                   "present)")
      ->check(inputFile());
  command
      ->add_option("--loops", args->closure_files.loops,
                   "Loop-closure pairs to verify and close: lines 'i j' or 'i j tx ty tz qx qy qz qw' "
                   "(docs/closure.md)")
      ->check(inputFile());
  command
      ->add_option("--priors", args->closure_files.priors,
                   "Position priors (GNSS in a local metric frame): lines 't x y z sigma' or "
                   "'t x y z sx sy sz' (docs/closure.md)")
      ->check(inputFile());
  command
      ->add_option("--prior-max-gap", args->closure_files.prior_max_gap_s,
                   "A prior further than this (s) from every scan's stamp is not used")
      ->check(positiveUpTo(3600.0, "s"))
      ->capture_default_str();
  command
      ->add_option("--deskew-passes", args->deskew_passes,
                   "Raw sweeps (--deskew): runs, each after deskewing the sweeps by the poses the last "
                   "one found (the first by the input's)")
      ->check(CLI::Range(1, 5))
      ->capture_default_str();
  command->add_flag("--every-scan", args->every_scan,
                    "Also write every_scan_poses_tum.txt: every scan of a recording, keyframe or not, its "
                    "pose corrected as the keyframes around it were");
  command->add_flag("--no-render", args->no_render, "Do not write before_after.png");
  command->add_flag("--no-report-page", args->no_report_page,
                    "Do not write report.html (the map in 3D in a browser; `hba view` writes it later)");
  command->add_flag("--no-memory-check", args->no_memory_check,
                    "Run even when the estimated peak memory exceeds what the machine has available "
                    "(docs/pyramid.md, \"Memory\")");
  command->add_flag("--no-convention-check", args->no_convention_check,
                    "Do not check that the map is crispest with the poses as given (vs inverted, vs none)");
  command->add_option("--config", args->config, "YAML settings file (flags override it)")->check(inputFile());
  args->settings.addTo(command);
  command->callback([args] { run(*args); });
}

}  // namespace hba::cli
