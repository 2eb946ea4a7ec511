// `hba view OUT`: writes OUT/report.html again for an existing output folder;
// `hba view DATA --compare POSES -o page.html`: a page for a dataset and
// any pose files.
#include <spdlog/spdlog.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "core/input_file.hpp"
#include "dataset_args.hpp"
#include "earlier_output.hpp"
#include "file_checks.hpp"
#include "hba/core/error.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/render/report_page.hpp"
#include "number_checks.hpp"
#include "output_dir.hpp"

namespace hba::cli {
namespace {
namespace fs = std::filesystem;

struct ViewArgs {
  DatasetArgs data;
  std::string output, compare, gt;
  bool force = false;
  render::ReportPageSettings settings;
};

// The dataset an output folder was made from, as its report names it; the
// dataset flags given (topics, --extrinsic) apply to it.
DatasetArgs datasetOf(const ViewArgs& args, const fs::path& out, const nlohmann::json& report) {
  if (report.contains("sessions") || report.contains("map")) {
    throw Error(out.string() +
                ": a run of several sessions or against a map; its report.html is written by hba optimize "
                "(hba view reads single runs)");
  }
  DatasetArgs data = args.data;
  data.dir = outputInput(report, out, "dataset");
  data.poses = outputInput(report, out, "poses");
  if (data.format.empty()) data.format = outputInput(report, out, "pose_format");
  const std::string frame = outputInput(report, out, "pose_frame");
  if (frame != "sensor" && data.extrinsic.empty() && data.calibration.empty()) {
    failAt(out / "report.json",
           "the run's poses were of the " + frame + " frame: give the --extrinsic or --calib it had");
  }
  if (outputInputFlag(report, out, "scans_in_world")) data.scans_in_world = true;
  return data;
}

void run(ViewArgs& args) {
  const fs::path given = args.data.dir;
  const bool from_output = isOptimizeOutput(given);
  render::ReportPageInput input;
  io::Dataset dataset = [&] {
    if (!from_output) return args.data.open();
    input.report = readOutputReport(given);
    return datasetOf(args, given, input.report).open();
  }();
  input.before = dataset.trajectory().poses;
  if (from_output) {
    if (!args.compare.empty())
      throw Error("--compare is for a dataset; " + given.string() + " is an output folder");
    input.after = readPosesFor(dataset, given / "pose.json");
    if (regularFileIsPresent(given / "before_after.png")) input.picture = given / "before_after.png";
  } else {
    input.after = args.compare.empty() ? input.before : readPosesFor(dataset, args.compare);
  }
  fs::path output = args.output;
  if (output.empty()) {
    if (!from_output)
      throw Error("-o page.html is needed for a dataset (hba view OUT writes OUT/report.html)");
    output = given / "report.html";
  }
  if (output.extension() != ".html") throw Error(output.string() + ": the page (-o) must be an .html file");
  refuseOutputInsideInput(output, dataset);
  // A page hba wrote is written again; any other file only with --force.
  const auto claim = claimOutputFile(output, args.force || render::isReportPage(output));
  if (!args.gt.empty()) {
    input.ground_truth = readPosesFor(dataset, args.gt);  // asked for: a wrong length is an error
  } else if (regularFileIsPresent(dataset.root() / "gt.txt")) {
    // As hba optimize: a gt.txt beside the data that does not pair up is not drawn, with a word.
    std::vector<Pose> gt = io::readPoses(dataset.root() / "gt.txt").poses;
    if (gt.size() == dataset.size()) {
      input.ground_truth = std::move(gt);
    } else {
      spdlog::warn("{}: {} poses for {} scans; not drawn", (dataset.root() / "gt.txt").string(), gt.size(),
                   dataset.size());
    }
  }
  input.title = folderName(dataset.root());

  const auto start = std::chrono::steady_clock::now();
  const io::DatasetScanSource scans(dataset);
  args.settings.memory = MemoryBudget::ofAvailableMemoryAsHeld();
  const render::ReportPageFigures page = render::writeReportPage(scans, input, output, args.settings);
  spdlog::info("wrote {}: {} points (voxel {:.2f} m), {:.1f} MB, in {:.2f} s", output.string(), page.points,
               page.voxel, static_cast<double>(page.bytes) / 1e6,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace

void registerViewCommand(CLI::App& app) {
  auto args = std::make_shared<ViewArgs>();
  auto* command = app.add_subcommand(
      "view",
      "Write the report page (the map in 3D in a browser, input and optimized poses): OUT/report.html for an "
      "output folder of hba optimize, or -o FILE for a dataset and --compare POSES");
  args->data.addTo(command);
  command->add_option("-o,--output", args->output,
                      "The page (.html); default OUT/report.html for an output folder");
  command->add_flag("--force", args->force, "Replace an existing file that is not an hba report page");
  command
      ->add_option("--compare", args->compare, "With a dataset: the optimized poses to show beside its own")
      ->check(inputFile());
  command->add_option("--gt", args->gt, "Ground-truth trajectory to draw (default: the dataset's gt.txt)")
      ->check(inputFile());
  command
      ->add_option("--points", args->settings.point_budget,
                   "At most this many map points on the page (the map is thinned to fit)")
      ->check(countIn(1000, 8e6))
      ->capture_default_str();
  command->add_option("--voxel", args->settings.voxel, "The finest voxel the map is thinned at (m)")
      ->check(realIn(0.01, 10.0, "m"))
      ->capture_default_str();
  command->callback([args] { run(*args); });
}

}  // namespace hba::cli
