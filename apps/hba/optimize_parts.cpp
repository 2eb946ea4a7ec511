// The parts of `hba optimize` shared by one sequence and several sessions.
#include "optimize_parts.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>

#include <chrono>
#include <optional>

#include "core/input_file.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "hba/core/memory_budget.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/render/map_picture.hpp"
#include "hba/render/report_page.hpp"
#include "hba/settings/settings_file.hpp"
#include "json_text.hpp"
#include "pipeline/convention_check.hpp"
#include "pipeline/report_json.hpp"
#include "recording_entry.hpp"
#include "version_text.hpp"

namespace hba::cli::optimize {
namespace fs = std::filesystem;

double peakMemoryMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

std::optional<Trajectory> readGroundTruth(const Args& args, const io::Dataset& dataset, std::size_t frames) {
  fs::path path = args.ground_truth;
  if (path.empty() && regularFileIsPresent(dataset.root() / "gt.txt")) path = dataset.root() / "gt.txt";
  if (path.empty()) return std::nullopt;
  Trajectory gt = io::readPoses(path);
  if (gt.size() != frames) {
    spdlog::warn("{}: {} poses for {} scans; not drawn nor compared", path.string(), gt.size(), frames);
    return std::nullopt;
  }
  return gt;
}

nlohmann::json windowErrorsReport(const pipeline::HbaResult& result, const std::vector<Pose>& input,
                                  const Trajectory& gt) {
  const std::vector<pipeline::LayerWindowErrors> rows = pipeline::windowErrors(
      result.report.window_records, input, result.hierarchy_poses, result.poses, gt.poses);
  spdlog::info(
      "windows against the ground truth (RMS of each window's frames from its first: deg, m; "
      "report.json's window_errors):");
  spdlog::info("  {:>5} {:>6} {:>17} {:>17} {:>17} {:>17} {:>17}", "layer", "pairs", "input", "window start",
               "window result", "hierarchy", "final");
  auto cell = [](const pipeline::RelativeErrorRms& e) {
    return fmt::format("{:.4f} {:.4f}", e.rotation_rms_deg, e.translation_rms_m);
  };
  for (const pipeline::LayerWindowErrors& row : rows) {
    spdlog::info("  {:>5} {:>6} {:>17} {:>17} {:>17} {:>17} {:>17}",
                 fmt::format("{}{}", row.layer, row.global ? "g" : ""), row.pairs, cell(row.input),
                 cell(row.start), cell(row.window), cell(row.hierarchy), cell(row.final));
  }
  return pipeline::windowErrorsToJson(rows);
}

void announceReplacement(const StagingFolder& staging) {
  if (staging.replaces().empty()) return;
  spdlog::info("--force: {} holds {}; it will be replaced by this run's output when it is complete",
               staging.destination().string(), staging.replaces());
}

namespace {

// The scans as the optimization kept them (parsed and downsampled once, at
// `scan_voxel`) when that is at least as fine as `voxel`, with
// `scans_voxel` set to it; `scans` otherwise.
const io::ScanSource& scansFor(double voxel, const io::ScanSource& scans, const pipeline::HbaResult& result,
                               double scan_voxel, double& scans_voxel) {
  if (!result.scans || result.scans->size() != scans.size() || scan_voxel > voxel) return scans;
  scans_voxel = scan_voxel;
  return *result.scans;
}

}  // namespace

bool writePicture(const io::ScanSource& scans, const pipeline::HbaResult& result, double scan_voxel,
                  const std::vector<Pose>& before, const std::optional<Trajectory>& gt, const fs::path& out) {
  const std::vector<Pose>& optimized = result.poses;
  const fs::path png = out / "before_after.png";
  spdlog::info("drawing before_after.png");
  render::RenderSettings settings;
  const io::ScanSource& source = scansFor(settings.voxel, scans, result, scan_voxel, settings.scans_voxel);
  // The picture is the last step: one that cannot fit is left out, and
  // the poses and report are kept.
  settings.budget = MemoryBudget::ofAvailableMemory();
  try {
    render::writeBeforeAfter(source, before, optimized, gt ? &gt->poses : nullptr, png, settings);
  } catch (const MemoryExceeded& e) {
    spdlog::warn("before_after.png not drawn: {}; `hba render --compare` draws it from the outputs",
                 e.what());
    return false;
  }
  return true;
}

bool writeReportPage(const io::ScanSource& scans, const pipeline::HbaResult& result, double scan_voxel,
                     const std::vector<Pose>& before, const std::optional<Trajectory>& gt,
                     const nlohmann::json& report, const std::string& title, const fs::path& out) {
  spdlog::info("writing report.html");
  const auto start = std::chrono::steady_clock::now();
  render::ReportPageSettings settings;
  const io::ScanSource& source = scansFor(settings.voxel, scans, result, scan_voxel, settings.scans_voxel);
  settings.memory = MemoryBudget::ofAvailableMemoryAsHeld();
  render::ReportPageInput input;
  input.title = title;
  input.before = before;
  input.after = result.poses;
  if (gt) input.ground_truth = gt->poses;
  input.report = report;
  if (regularFileIsPresent(out / "before_after.png")) input.picture = out / "before_after.png";
  try {
    const render::ReportPageFigures page =
        render::writeReportPage(source, input, out / "report.html", settings);
    spdlog::info("report.html: {} points (voxel {:.2f} m), {:.1f} MB, in {:.2f} s", page.points, page.voxel,
                 static_cast<double>(page.bytes) / 1e6,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  } catch (const MemoryExceeded& e) {
    spdlog::warn("report.html not written: {}; `hba view` writes it from the outputs", e.what());
    return false;
  }
  return true;
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

std::vector<std::string> writeEveryScanPoses(const fs::path& out, const io::Dataset& dataset,
                                             const std::vector<Pose>& poses) {
  Trajectory every = dataset.everyScan(poses);
  io::writePoses(out / "every_scan_poses_tum.txt", every, io::PoseFormat::Tum);
  std::vector<std::string> written = {fmt::format("every_scan_poses_tum.txt ({} scans)", every.size())};
  if (!dataset.inputFrame().empty()) {
    const std::string name = "every_scan_" + dataset.inputFrame() + "_poses_tum.txt";
    every.poses = dataset.toInputFrame(every.poses);
    io::writePoses(out / name, every, io::PoseFormat::Tum);
    written.push_back(name + " (" + dataset.inputFrame() + " frame)");
  }
  return written;
}

pipeline::ClosureInputs readClosureInputs(const Args& args, const std::vector<const io::Dataset*>& datasets,
                                          const std::vector<std::size_t>& starts, std::size_t frames) {
  std::vector<const Trajectory*> sessions;
  for (const io::Dataset* dataset : datasets) sessions.push_back(&dataset->trajectory());
  return pipeline::readClosureFiles(args.closure_files, sessions, starts, frames);
}

// Defaults, then the YAML file, then the flags given on the command line.
HbaSettings mergeSettings(const Args& args) {
  HbaSettings settings;
  if (!args.config.empty()) settings::applySettingsFile(args.config, settings);
  args.settings.applyTo(settings);
  settings::checkSettings(settings);
  return settings;
}

// Refuses input in another convention (inverted poses, world-frame scans)
// before hours of work on it, naming the flag that fixes it.
nlohmann::json checkConventions(const Args& args, const io::ScanSource& source, const io::Dataset& dataset) {
  if (args.no_convention_check) return "skipped (--no-convention-check)";
  pipeline::GivenConventions given;
  given.invert_poses = args.data.invert_poses;
  given.scans_in_world = dataset.scansInWorld();
  given.extrinsic = !dataset.inputFrame().empty();
  const pipeline::ConventionCheck check =
      pipeline::checkConventions(source, dataset.trajectory().poses, given);
  if (check.verdict != pipeline::ConventionVerdict::AsGiven)
    throw Error(dataset.root().string() + ": " + check.message);
  if (check.stretches == 0) {
    spdlog::info("convention check: the path has no stretch long enough to tell");
    return "not enough motion to tell";
  }
  if (!check.cannot_tell.empty()) {
    spdlog::warn(
        "convention check: {}; the poses and scans are taken as given (sensor-to-world poses, "
        "sensor-frame scans)",
        check.cannot_tell);
    return check.cannot_tell;
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

nlohmann::json reportJson(const pipeline::HbaResult& result, const io::Dataset& dataset,
                          const DatasetArgs& data, const HbaSettings& settings,
                          const nlohmann::json& conventions) {
  nlohmann::json report = pipeline::reportToJson(result.report);
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
  if (const rec::Recording* recording = dataset.recording())
    report["input"]["recording"] = recordingEntry(*recording, data);
  report["settings"] = settings::settingsToJson(settings);
  return report;
}

nlohmann::json writeReport(const fs::path& out, const nlohmann::json& report) {
  nlohmann::json with_memory = report;
  with_memory["peak_memory_mib"] = peakMemoryMiB();
  writeFileAtomically(
      out / "report.json", [&](std::ostream& os) { os << jsonText(with_memory, 2) << '\n'; }, false);
  return with_memory;
}

}  // namespace hba::cli::optimize
