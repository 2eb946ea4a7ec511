// `hba optimize DATA -o OUT`: the whole method on a dataset.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <tbb/global_control.h>

#include <filesystem>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "dataset_args.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "hba/core/staging_folder.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pyramid/convention_check.hpp"
#include "hba/pyramid/hierarchical_ba.hpp"
#include "hba/pyramid/report_json.hpp"
#include "hba/pyramid/settings_file.hpp"
#include "hba/render/map_picture.hpp"
#include "hba/voxel/downsampled_scan_source.hpp"
#include "output_dir.hpp"

namespace hba::cli {
namespace {
namespace fs = std::filesystem;

struct OptimizeArgs {
  DatasetArgs data;
  std::string output;
  std::string config;
  pyramid::HbaSettings settings;
  std::string top_down;
  std::string pairs;
  double voxel = 0.0;  // sets both local and global voxel sizes
  std::string ground_truth;
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
  render::writeBeforeAfter(scans, dataset.trajectory().poses, optimized,
                           gt ? &gt->poses : nullptr, png);
}

// The sensor poses in three formats, and the poses of the frame the input
// trajectory described (KITTI's camera 0, an --extrinsic body) beside them.
std::vector<std::string> writeOptimizedPoses(const fs::path& out, const io::Dataset& dataset,
                                             const std::vector<Pose>& poses) {
  if (!dataset.trajectory().hasStamps()) {
    spdlog::info("no timestamps (none in the trajectory, no times.txt, scans not named by time): "
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

// Defaults, then the YAML file, then the flags given on the command line.
pyramid::HbaSettings mergeSettings(const OptimizeArgs& args, const CLI::App& command) {
  pyramid::HbaSettings settings;
  if (!args.config.empty()) pyramid::applySettingsFile(args.config, settings);
  auto given = [&](const char* flag) { return command.count(flag) > 0; };
  const pyramid::HbaSettings& flags = args.settings;
  if (given("--window")) settings.window = flags.window;
  if (given("--stride")) settings.stride = flags.stride;
  if (given("--layers")) settings.layers = flags.layers;
  if (given("--iterations")) settings.outer_iterations = flags.outer_iterations;
  if (given("--scan-voxel")) settings.scan_voxel = flags.scan_voxel;
  if (given("--keyframe-voxel")) settings.keyframe_voxel = flags.keyframe_voxel;
  if (given("--voxel")) {
    settings.scan_window_voxel = settings.local.planes.voxel_size = settings.global.planes.voxel_size = args.voxel;
  }
  if (given("--voxel-scans")) settings.scan_window_voxel = flags.scan_window_voxel;
  if (given("--voxel-local")) settings.local.planes.voxel_size = flags.local.planes.voxel_size;
  if (given("--voxel-global")) settings.global.planes.voxel_size = flags.global.planes.voxel_size;
  if (given("--final-voxel")) settings.local.final_voxel_size = settings.global.final_voxel_size = flags.local.final_voxel_size;
  if (given("--theta-local")) settings.local.planes.eigen_ratio = flags.local.planes.eigen_ratio;
  if (given("--theta-global")) settings.global.planes.eigen_ratio = flags.global.planes.eigen_ratio;
  if (given("--reject")) settings.local.reject_ratio = settings.global.reject_ratio = flags.local.reject_ratio;
  if (given("--ba-iterations")) settings.local.max_iterations = settings.global.max_iterations = flags.local.max_iterations;
  if (given("--point-sigma")) settings.information.point_sigma = flags.information.point_sigma;
  if (given("--no-refine")) settings.refine = false;
  if (given("--refine-voxel")) settings.refinement.planes.voxel_size = flags.refinement.planes.voxel_size;
  if (given("--no-motion-prior")) settings.setMotionPrior(false);
  // CLI11 has checked the names already.
  if (given("--top-down")) settings.top_down = *pyramid::topDownModeFromString(args.top_down);
  if (given("--pairs")) settings.factor_pairs = *pyramid::factorPairsFromString(args.pairs);
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
  if (check.verdict != pyramid::ConventionVerdict::AsGiven) throw Error(dataset.root().string() + ": " + check.message);
  if (check.stretches == 0) {
    spdlog::info("convention check: the path has no stretch long enough to tell");
    return "not enough motion to tell";
  }
  spdlog::info("convention check: the poses as given make the crispest map ({:.2f}; inverted {:.2f}, "
               "no poses {:.2f}, of a turned body {:.2f})",
               check.as_given, check.inverted, check.in_world, check.turned);
  return {{"stretches", check.stretches}, {"as_given", check.as_given}, {"inverted", check.inverted},
          {"no_poses", check.in_world}, {"turned_body", check.turned}};
}

void writeReport(const fs::path& out, const pyramid::HbaResult& result, const io::Dataset& dataset,
                 const pyramid::HbaSettings& settings, std::size_t threads, const nlohmann::json& conventions) {
  nlohmann::json report = pyramid::reportToJson(result.report);
  report["convention_check"] = conventions;
  report["input"] = {{"dataset", fs::absolute(dataset.root()).string()},
                     {"layout", dataset.layout()},
                     {"poses", fs::absolute(dataset.posesFile()).string()},
                     {"pose_format", io::toString(dataset.poseFormat())},
                     {"scans", dataset.size()},
                     {"stamps", dataset.stampsSource().empty() ? "none (scan index)" : dataset.stampsSource()},
                     {"pose_frame", dataset.inputFrame().empty() ? "sensor" : dataset.inputFrame()},
                     {"scans_in_world", dataset.scansInWorld()}};
  report["settings"] = pyramid::settingsToJson(settings);
  report["threads"] = threads;
  report["peak_memory_mib"] = peakMemoryMiB();
  writeFileAtomically(out / "report.json", [&](std::ostream& os) { os << report.dump(2) << '\n'; },
                      false);
}

void run(const OptimizeArgs& args, const CLI::App& command) {
  const pyramid::HbaSettings settings = mergeSettings(args, command);
  if (args.print_config) {
    std::cout << pyramid::settingsToYaml(settings);
    return;
  }
  // Required unless --print-config (CLI11 cannot say "unless").
  if (args.data.dir.empty()) throw CLI::RequiredError("DIR");
  if (args.output.empty()) throw CLI::RequiredError("--output");
  // The -j limit (a tbb::global_control), not the machine's core count.
  const std::size_t threads =
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);

  const io::Dataset dataset = args.data.open();
  refuseOutputInsideInput(args.output, dataset);
  // Everything is written beside OUT and moved into place at the end: no
  // half-written folder, no earlier run's files beside this run's.
  StagingFolder staging(args.output, args.force);
  const fs::path& out = staging.path();
  // One source of the scans for the convention check, the optimization and the picture.
  const io::DatasetScanSource scans(dataset);
  const nlohmann::json conventions =
      checkConventions(args, voxel::DownsampledScanSource(scans, settings.scan_voxel), dataset);
  spdlog::info("dataset: {} ({} layout), {} scans, poses from {}", dataset.root().string(),
               dataset.layout(), dataset.size(), dataset.posesFile().string());
  spdlog::debug("settings: {}", pyramid::settingsToJson(settings).dump());  // also in report.json
  spdlog::info("threads: {}", threads);

  const pyramid::HbaResult result =
      pyramid::runHierarchicalBa(scans, dataset.trajectory().poses, settings);

  const std::vector<std::string> written = writeOptimizedPoses(out, dataset, result.poses);
  writeReport(out, result, dataset, settings, threads, conventions);

  if (!args.no_render) writePicture(args, dataset, scans, result.poses, out);
  staging.commit();
  spdlog::info("done in {:.1f} s (peak memory {:.0f} MiB): {}", result.report.seconds_total,
               peakMemoryMiB(), staging.destination().string());
  spdlog::info("wrote {}, report.json{}", fmt::format("{}", fmt::join(written, ", ")),
               args.no_render ? "" : ", before_after.png");
}

}  // namespace

void registerOptimizeCommand(CLI::App& app) {
  auto args = std::make_shared<OptimizeArgs>();
  pyramid::HbaSettings& s = args->settings;
  auto* command = app.add_subcommand(
      "optimize", "Optimize the poses of a sequence (hierarchical BA + pose graph)");
  args->data.addTo(command);
  command->get_option("DIR")->required(false);
  command->add_option("-o,--output", args->output,
                      "Output folder (created; never inside the input; a non-empty one needs --force)");
  command->add_flag("--print-config", args->print_config,
                    "Print every setting (defaults, --config, flags) as a commented YAML file for "
                    "--config, and stop");
  command->add_flag("--force", args->force, "Replace a non-empty output folder (as a whole, at the end)");
  command->add_option("--gt", args->ground_truth,
                      "Ground-truth trajectory to draw in the picture (default: DIR/gt.txt if present)")
      ->check(CLI::ExistingFile);
  command->add_flag("--no-render", args->no_render, "Do not write before_after.png");
  command->add_flag("--no-convention-check", args->no_convention_check,
                    "Do not check that the map is crispest with the poses as given (vs inverted, vs none)");
  command->add_option("--config", args->config, "YAML settings file (flags override it)")
      ->check(CLI::ExistingFile);
  command->add_option("--window", s.window, "Frames per local window (w)")->default_val(s.window);
  command->add_option("--stride", s.stride, "Stride between windows (s < w)")->default_val(s.stride);
  command->add_option("--layers", s.layers, "Pyramid layers incl. layer 1 (0 = automatic)")
      ->default_val(s.layers);
  command->add_option("--iterations", s.outer_iterations, "Outer iterations (bottom-up + top-down)")
      ->default_val(s.outer_iterations);
  command->add_option("--scan-voxel", s.scan_voxel, "Downsample scans to this voxel (m)")
      ->default_val(s.scan_voxel);
  command->add_option("--keyframe-voxel", s.keyframe_voxel, "Downsample keyframes to this voxel (m)")
      ->default_val(s.keyframe_voxel);
  command->add_option("--voxel", args->voxel, "Root voxel size V of every BA (m)");
  command->add_option("--voxel-scans", s.scan_window_voxel,
                      "Root voxel size of the layer-1 (scan) windows (m; 0 = --voxel-local)")
      ->default_val(s.scan_window_voxel);
  command->add_option("--voxel-local", s.local.planes.voxel_size,
                      "Root voxel size of the keyframe windows, layers 2 and up (m)")
      ->default_val(s.local.planes.voxel_size);
  command->add_option("--voxel-global", s.global.planes.voxel_size, "Root voxel size of global BA (m)")
      ->default_val(s.global.planes.voxel_size);
  command->add_option("--final-voxel", s.local.final_voxel_size,
                      "Coarse to fine: voxel size of the last associations (m; 0 = off)")
      ->default_val(s.local.final_voxel_size);
  command->add_option("--theta-local", s.local.planes.eigen_ratio, "Plane test threshold, local BA")
      ->default_val(s.local.planes.eigen_ratio);
  command->add_option("--theta-global", s.global.planes.eigen_ratio, "Plane test threshold, global BA")
      ->default_val(s.global.planes.eigen_ratio);
  command->add_option("--reject", s.local.reject_ratio, "Fraction of worst planes rejected")
      ->default_val(s.local.reject_ratio);
  command->add_option("--ba-iterations", s.local.max_iterations, "LM iterations per BA round")
      ->default_val(s.local.max_iterations);
  command->add_option("--point-sigma", s.information.point_sigma,
                      "Point-to-plane noise for the pose-graph weights (m)")
      ->default_val(s.information.point_sigma);
  command->add_flag("--no-refine", "Skip the final sparse BA over every scan (the hierarchy alone)");
  command->add_option("--refine-voxel", s.refinement.planes.voxel_size,
                      "Root voxel of the final sparse BA over every scan (m)")
      ->default_val(s.refinement.planes.voxel_size);
  command->add_flag("--no-motion-prior",
                    "No weak prior holding neighbouring frames at their input relative pose");
  command->add_option("--top-down", args->top_down, "pose-graph (the paper) or direct-assign (ablation)")
      ->check(CLI::IsMember({"pose-graph", "direct-assign"}));
  command->add_option("--pairs", args->pairs, "Window frame pairs that become factors")
      ->check(CLI::IsMember({"adjacent", "all", "from-first"}));
  command->callback([args, command] { run(*args, *command); });
}

}  // namespace hba::cli
