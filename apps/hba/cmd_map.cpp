// `hba map DATA -o map.pcd|map.ply|map.las`: the merged, voxel-downsampled map.
#include <spdlog/spdlog.h>

#include <filesystem>
#include <string>

#include "commands.hpp"
#include "dataset_args.hpp"
#include "enum_choice.hpp"
#include "hba/core/error.hpp"
#include "hba/core/memory_budget.hpp"
#include "hba/eval/merged_map.hpp"
#include "hba/io/las.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/ply.hpp"
#include "hba/io/scan_formats.hpp"
#include "hba/io/scan_source.hpp"
#include "number_checks.hpp"
#include "output_dir.hpp"

namespace hba::cli {
namespace {
namespace fs = std::filesystem;

struct MapArgs {
  DatasetArgs data;
  std::string output;
  std::string color = "none";
  bool force = false;
  eval::MapSettings settings;
};

void run(MapArgs& args) {
  const fs::path output = args.output;
  const io::ScanFormat* format = io::findScanFormat(output);
  if (!format || !format->keeps_doubles) {
    failAt(output, "the map must be a " + io::scanFormatList(true) + " file");
  }
  const bool las = std::string(format->extension) == ".las";
  args.settings.color = parseEnum<eval::MapColor>(args.color);

  const io::Dataset dataset = args.data.open();
  refuseOutputInsideInput(output, dataset);                // hba never writes into its input
  const auto claim = claimOutputFile(output, args.force);  // held until written
  spdlog::info("merging {} scans with poses from {}", dataset.size(), dataset.posesFile().string());
  const io::DatasetScanSource scans(dataset);
  // LAS has a field for the scan index (point source ID), so it gets one
  // beside the intensity whatever --color chose.
  io::LasPointExtras las_extras;
  // The map's size is known only once every scan is in: it stops, with
  // nothing written, before the kernel would kill it.
  args.settings.budget = MemoryBudget::ofAvailableMemory();
  PointCloud map;
  try {
    map = eval::buildMergedMap(scans, dataset.trajectory().poses, args.settings,
                               las ? &las_extras.scan_index : nullptr);
  } catch (const MemoryExceeded& e) {
    failAt(output, std::string("not written: ") + e.what() + "; a larger --voxel keeps fewer points");
  }
  if (las) {
    io::writeLas(output, map, las_extras);
  } else {
    format->write(output, map);
  }
  spdlog::info("wrote {} ({} points, voxel {} m, intensity = {})", output.string(), map.size(),
               args.settings.voxel, args.color == "none" ? "mean scan intensity" : args.color);
}

}  // namespace

void registerMapCommand(CLI::App& app) {
  auto args = std::make_shared<MapArgs>();
  auto* command = app.add_subcommand("map", "Write the merged, voxel-downsampled map of a dataset");
  args->data.addTo(command);
  command->add_option("-o,--output", args->output, "Output map file (" + io::scanFormatList(true) + ")")
      ->required();
  command->add_flag("--force", args->force, "Replace an existing output file");
  command->add_option("--voxel", args->settings.voxel, "Voxel size (m; 0 = keep every point)")
      ->check(mapVoxel())
      ->capture_default_str();
  command
      ->add_option("--color", args->color,
                   "What the intensity field carries: none (mean intensity), scan (scan index), "
                   "height (z)")
      ->check(oneOf<eval::MapColor>())
      ->capture_default_str();
  command->callback([args] { run(*args); });
}

}  // namespace hba::cli
