// `hba extract REC -o DIR`: a recording's scans and interpolated poses as a
// folder other tools (and hba) read: DIR/pcd/NNNNNN.pcd, pose.json (sensor
// poses), times.txt. Any dataset hba reads can be extracted the same way.
#include <spdlog/spdlog.h>

#include <memory>

#include "commands.hpp"
#include "core/progress.hpp"
#include "core/remove_on_interrupt.hpp"
#include "core/staging_folder.hpp"
#include "dataset_args.hpp"
#include "hba/core/error.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "output_dir.hpp"

namespace hba::cli {
namespace {
namespace fs = std::filesystem;

struct ExtractArgs {
  DatasetArgs data;
  std::string output;
  bool force = false;
};

std::string scanName(std::size_t i) {
  std::string digits = std::to_string(i);
  return std::string(digits.size() < 6 ? 6 - digits.size() : 0, '0') + digits + ".pcd";
}

void runExtract(const ExtractArgs& args) {
  const io::Dataset dataset = args.data.open();
  refuseOutputInsideInput(args.output, dataset);
  refuseReplacingInputs(args.output);
  StagingFolder staging(args.output, args.force, "hba extract");
  const fs::path pcd = staging.path() / "pcd";
  fs::create_directory(pcd);
  Progress progress("extracting", dataset.size(), "scans");
  // In order: each chunk of a recording is decompressed once.
  for (std::size_t i = 0; i < dataset.size(); ++i) {
    io::writePcd(pcd / scanName(i), dataset.loadScan(i), io::PcdEncoding::Binary);
    interruptPointForTests("scan-written");
    progress.advance();
  }
  io::writePoses(staging.path() / "pose.json", dataset.trajectory(), io::PoseFormat::Hba);
  if (dataset.trajectory().hasStamps())
    io::writeTimes(staging.path() / "times.txt", dataset.trajectory().stamps);
  staging.commit();
  spdlog::info("wrote {} scans with their poses to {} (pcd/, pose.json{})", dataset.size(),
               staging.destination().string(), dataset.trajectory().hasStamps() ? ", times.txt" : "");
}

}  // namespace

void registerExtractCommand(CLI::App& app) {
  auto args = std::make_shared<ExtractArgs>();
  auto* command = app.add_subcommand(
      "extract",
      "Write a recording's (or any dataset's) scans and sensor poses as a folder: pcd/NNNNNN.pcd, "
      "pose.json, times.txt (a bag's poses interpolated at each scan's stamp)");
  args->data.addTo(command);
  command->add_option("-o,--output", args->output, "Output folder (created; a non-empty one needs --force)")
      ->required();
  command->add_flag("--force", args->force, "Replace a non-empty output folder (as a whole, at the end)");
  command->callback([args] { runExtract(*args); });
}

}  // namespace hba::cli
