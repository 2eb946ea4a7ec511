// `hba optimize DATA -o OUT`: the whole method on a dataset.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "dataset_args.hpp"
#include "hba/closure/frame_priors.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "hba/core/staging_folder.hpp"
#include "hba/io/loop_file.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/position_prior_file.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pyramid/convention_check.hpp"
#include "hba/pyramid/hierarchical_ba.hpp"
#include "hba/pyramid/report_json.hpp"
#include "hba/pyramid/settings_file.hpp"
#include "hba/render/map_picture.hpp"
#include "hba/voxel/downsampled_scan_source.hpp"
#include "output_dir.hpp"
#include "setting_flags.hpp"
#include "version_text.hpp"

namespace hba::cli {
namespace {
namespace fs = std::filesystem;

struct OptimizeArgs {
  DatasetArgs data;
  std::string output;
  std::string config;
  SettingFlags settings;
  std::string ground_truth;
  std::string loops;
  std::string priors;
  double prior_max_gap_s = 0.5;
  bool no_render = false;
  bool no_convention_check = false;
  bool force = false;
  bool print_config = false;
};

double peakMemoryMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

// Ground truth to draw: --gt, or the simulator's gt.txt beside the data.
std::optional<Trajectory> groundTruth(const OptimizeArgs& args, const io::Dataset& dataset) {
  fs::path path = args.ground_truth;
  if (path.empty() && fs::exists(dataset.root() / "gt.txt")) path = dataset.root() / "gt.txt";
  if (path.empty()) return std::nullopt;
  Trajectory gt = io::readPoses(path);
  if (gt.size() != dataset.size()) {
    spdlog::warn("{}: {} poses for {} scans; not drawn", path.string(), gt.size(), dataset.size());
    return std::nullopt;
  }
  return gt;
}

void writePicture(const OptimizeArgs& args, const io::Dataset& dataset, const io::ScanSource& scans,
                  const std::vector<Pose>& optimized, const fs::path& out) {
#ifdef __GLIBC__
  // The optimization's freed heap stays resident while the picture's large
  // buffers come as fresh pages: handing it back first keeps the run's peak
  // memory that of the optimization.
  malloc_trim(0);
#endif
  const std::optional<Trajectory> gt = groundTruth(args, dataset);
  const fs::path png = out / "before_after.png";
  spdlog::info("drawing before_after.png");
  render::writeBeforeAfter(scans, dataset.trajectory().poses, optimized, gt ? &gt->poses : nullptr, png);
}

// The sensor poses in three formats, and the poses of the frame the input
// trajectory described (KITTI's camera 0, an --extrinsic body) beside them.
std::vector<std::string> writeOptimizedPoses(const fs::path& out, const io::Dataset& dataset,
                                             const std::vector<Pose>& poses) {
  if (!dataset.trajectory().hasStamps()) {
    spdlog::info(
        "no timestamps (none in the trajectory, no times.txt, scans not named by time): "
        "poses_tum.txt carries the scan index as time; give --times FILE for real stamps");
  }
  Trajectory optimized;
  optimized.poses = poses;
  optimized.stamps = dataset.trajectory().stamps;
  io::writePoses(out / "pose.json", optimized, io::PoseFormat::Hba);
  io::writePoses(out / "poses_kitti.txt", optimized, io::PoseFormat::Kitti);
  io::writePoses(out / "poses_tum.txt", optimized, io::PoseFormat::Tum);
  std::vector<std::string> written = {"pose.json (HBA)", "poses_kitti.txt", "poses_tum.txt"};
  if (!dataset.inputFrame().empty()) {
    const std::string prefix = dataset.inputFrame() + "_poses";
    optimized.poses = dataset.toInputFrame(poses);
    io::writePoses(out / (prefix + "_kitti.txt"), optimized, io::PoseFormat::Kitti);
    io::writePoses(out / (prefix + "_tum.txt"), optimized, io::PoseFormat::Tum);
    written.push_back(prefix + "_kitti.txt, " + prefix + "_tum.txt (" + dataset.inputFrame() + " frame)");
  }
  return written;
}

// The loop pairs and position priors of --loops and --priors, read before
// any work so that a bad file fails at once.
pyramid::ClosureInputs readClosureInputs(const OptimizeArgs& args, const io::Dataset& dataset) {
  pyramid::ClosureInputs inputs;
  if (!args.loops.empty()) {
    for (const io::LoopRecord& record : io::readLoopFile(args.loops, dataset.size())) {
      inputs.loops.push_back({record.from, record.to, record.relative});
    }
    spdlog::info("{}: {} loop closure pairs", args.loops, inputs.loops.size());
  }
  if (!args.priors.empty()) {
    const std::vector<io::TimedPosition> timed = io::readPositionPriorFile(args.priors);
    closure::FramePriors attached;
    try {
      attached = closure::attachPriors(timed, dataset.trajectory(), args.prior_max_gap_s);
    } catch (const Error& e) {
      throw Error(args.priors + ": " + e.what());
    }
    inputs.priors = attached.factors;
    spdlog::info("{}: {} position priors, {} attached to frames", args.priors, timed.size(),
                 attached.factors.size());
    if (attached.outside > 0) {
      spdlog::warn("{}: {} priors lie more than {:g} s from every scan and are not used", args.priors,
                   attached.outside, args.prior_max_gap_s);
    }
    if (inputs.priors.empty()) throw Error(args.priors + ": no prior falls within the scans' time span");
  }
  return inputs;
}

// Defaults, then the YAML file, then the flags given on the command line.
pyramid::HbaSettings mergeSettings(const OptimizeArgs& args) {
  pyramid::HbaSettings settings;
  if (!args.config.empty()) pyramid::applySettingsFile(args.config, settings);
  args.settings.applyTo(settings);
  pyramid::checkSettings(settings);
  return settings;
}

// Refuses input in another convention (inverted poses, world-frame scans)
// before hours of work on it, naming the flag that fixes it.
nlohmann::json checkConventions(const OptimizeArgs& args, const io::ScanSource& source,
                                const io::Dataset& dataset) {
  if (args.no_convention_check) return "skipped (--no-convention-check)";
  pyramid::GivenConventions given;
  given.invert_poses = args.data.invert_poses;
  given.scans_in_world = dataset.scansInWorld();
  given.extrinsic = !dataset.inputFrame().empty();
  const pyramid::ConventionCheck check = pyramid::checkConventions(source, dataset.trajectory().poses, given);
  if (check.verdict != pyramid::ConventionVerdict::AsGiven)
    throw Error(dataset.root().string() + ": " + check.message);
  if (check.stretches == 0) {
    spdlog::info("convention check: the path has no stretch long enough to tell");
    return "not enough motion to tell";
  }
  spdlog::info(
      "convention check: the poses as given make the crispest map ({:.2f}; inverted {:.2f}, "
      "no poses {:.2f}, of a turned body {:.2f})",
      check.as_given, check.inverted, check.in_world, check.turned);
  return {{"stretches", check.stretches},
          {"as_given", check.as_given},
          {"inverted", check.inverted},
          {"no_poses", check.in_world},
          {"turned_body", check.turned}};
}

void writeReport(const fs::path& out, const pyramid::HbaResult& result, const io::Dataset& dataset,
                 const pyramid::HbaSettings& settings, const nlohmann::json& conventions) {
  nlohmann::json report = pyramid::reportToJson(result.report);
  report["convention_check"] = conventions;
  report["hba"] = {{"version", HBA_VERSION}, {"revision", HBA_REVISION}};
  report["input"] = {
      {"dataset", fs::absolute(dataset.root()).string()},
      {"layout", dataset.layout()},
      {"poses", fs::absolute(dataset.posesFile()).string()},
      {"pose_format", hba::toString(dataset.poseFormat())},
      {"scans", dataset.size()},
      {"stamps", dataset.stampsSource().empty() ? "none (scan index)" : dataset.stampsSource()},
      {"pose_frame", dataset.inputFrame().empty() ? "sensor" : dataset.inputFrame()},
      {"scans_in_world", dataset.scansInWorld()}};
  report["settings"] = pyramid::settingsToJson(settings);
  report["peak_memory_mib"] = peakMemoryMiB();
  writeFileAtomically(
      out / "report.json", [&](std::ostream& os) { os << report.dump(2) << '\n'; }, false);
}

void run(const OptimizeArgs& args) {
  pyramid::HbaSettings settings = mergeSettings(args);
  if (args.print_config) {
    std::cout << pyramid::settingsToYaml(settings);
    return;
  }
  // Required unless --print-config (CLI11 cannot say "unless").
  if (args.data.dir.empty()) throw CLI::RequiredError("DIR");
  if (args.output.empty()) throw CLI::RequiredError("--output");
  // -j (a tbb::global_control in main), passed down explicitly: the pose
  // graph's Ceres solve runs on it too.
  settings.threads = pyramid::resolvedThreadCount(settings);

  const io::Dataset dataset = args.data.open();
  refuseOutputInsideInput(args.output, dataset);
  const pyramid::ClosureInputs closures = readClosureInputs(args, dataset);
  // Everything is written beside OUT and moved into place at the end: no
  // half-written folder, no earlier run's files beside this run's.
  StagingFolder staging(args.output, args.force);
  const fs::path& out = staging.path();
  // One source of the scans for the convention check, the optimization and the picture.
  const io::DatasetScanSource scans(dataset);
  const nlohmann::json conventions =
      checkConventions(args, voxel::DownsampledScanSource(scans, settings.scan_voxel), dataset);
  spdlog::info("dataset: {} ({} layout), {} scans, poses from {}", dataset.root().string(), dataset.layout(),
               dataset.size(), dataset.posesFile().string());
  spdlog::debug("settings: {}", pyramid::settingsToJson(settings).dump());  // also in report.json
  spdlog::info("threads: {}", settings.threads);

  const pyramid::HbaResult result =
      pyramid::runHierarchicalBa(scans, dataset.trajectory().poses, settings, closures);

  const std::vector<std::string> written = writeOptimizedPoses(out, dataset, result.poses);
  writeReport(out, result, dataset, settings, conventions);

  if (!args.no_render) writePicture(args, dataset, scans, result.poses, out);
  staging.commit();
  spdlog::info("done in {:.1f} s (peak memory {:.0f} MiB): {}", result.report.seconds_total, peakMemoryMiB(),
               staging.destination().string());
  spdlog::info("wrote {}, report.json{}", fmt::format("{}", fmt::join(written, ", ")),
               args.no_render ? "" : ", before_after.png");
}

}  // namespace

void registerOptimizeCommand(CLI::App& app) {
  auto args = std::make_shared<OptimizeArgs>();
  auto* command =
      app.add_subcommand("optimize", "Optimize the poses of a sequence (hierarchical BA + pose graph)");
  args->data.addTo(command);
  command->get_option("DIR")->required(false);
  command->add_option("-o,--output", args->output,
                      "Output folder (created; never inside the input; a non-empty one needs --force)");
  command->add_flag("--print-config", args->print_config,
                    "Print every setting (defaults, --config, flags) as a commented YAML file for "
                    "--config, and stop");
  command->add_flag("--force", args->force, "Replace a non-empty output folder (as a whole, at the end)");
  command
      ->add_option("--gt", args->ground_truth,
                   "Ground-truth trajectory to draw in the picture (default: DIR/gt.txt if present)")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--loops", args->loops,
                   "Loop-closure pairs to verify and close: lines 'i j' or 'i j tx ty tz qx qy qz qw' "
                   "(docs/closure.md)")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--priors", args->priors,
                   "Position priors (GNSS in a local metric frame): lines 't x y z sigma' or "
                   "'t x y z sx sy sz' (docs/closure.md)")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--prior-max-gap", args->prior_max_gap_s,
                   "A prior further than this (s) from every scan's stamp is not used")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_flag("--no-render", args->no_render, "Do not write before_after.png");
  command->add_flag("--no-convention-check", args->no_convention_check,
                    "Do not check that the map is crispest with the poses as given (vs inverted, vs none)");
  command->add_option("--config", args->config, "YAML settings file (flags override it)")
      ->check(CLI::ExistingFile);
  args->settings.addTo(command);
  command->callback([args] { run(*args); });
}

}  // namespace hba::cli
