// `hba render DATA -o map.png`: pictures of the merged map and trajectories.
#include <spdlog/spdlog.h>

#include <filesystem>
#include <string>

#include "commands.hpp"
#include "dataset_args.hpp"
#include "file_checks.hpp"
#include "hba/core/error.hpp"
#include "hba/core/memory_budget.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/render/map_picture.hpp"
#include "number_checks.hpp"
#include "output_dir.hpp"

namespace hba::cli {
namespace {

struct RenderArgs {
  DatasetArgs data;
  std::string output, compare, gt, crop;
  bool force = false;
  bool no_side = false;
  render::RenderSettings settings;
};

void run(RenderArgs& args) {
  if (std::filesystem::path(args.output).extension() != ".png")
    throw ValueError(args.output + ": the picture (-o) must be a .png file");
  if (!args.crop.empty()) args.settings.crop = render::parseBox(args.crop);  // checked by the flag
  args.settings.side_view = !args.no_side;

  const io::Dataset dataset = args.data.open();
  refuseOutputInsideInput(args.output, dataset);                // hba never writes into its input
  const auto claim = claimOutputFile(args.output, args.force);  // held until written
  std::vector<Pose> gt;
  if (!args.gt.empty()) gt = io::readPoses(args.gt).poses;
  const std::vector<Pose>* gt_ptr = args.gt.empty() ? nullptr : &gt;
  const io::DatasetScanSource scans(dataset);
  // Stops, with nothing written, before the kernel would kill it.
  args.settings.budget = MemoryBudget::ofAvailableMemory();
  render::PictureSize size;  // the size written, not the one asked: --compare may add a zoom row
  try {
    size =
        args.compare.empty()
            ? render::writeMapPicture(scans, dataset.trajectory().poses, gt_ptr, args.output, args.settings)
            : render::writeBeforeAfter(scans, dataset.trajectory().poses, readPosesFor(dataset, args.compare),
                                       gt_ptr, args.output, args.settings);
  } catch (const MemoryExceeded& e) {
    failAt(args.output, std::string("not written: ") + e.what() + "; a larger --voxel keeps fewer points");
  }
  spdlog::info("wrote {} ({}x{})", args.output, size.width, size.height);
}

}  // namespace

void registerRenderCommand(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  auto* command =
      app.add_subcommand("render",
                         "PNG of the merged map seen from above (and the side), with trajectories; "
                         "--compare draws before and after side by side");
  args->data.addTo(command);
  command->add_option("-o,--output", args->output, "Output picture (.png)")->required();
  command->add_flag("--force", args->force, "Replace an existing output file");
  command
      ->add_option("--compare", args->compare,
                   "A second trajectory (e.g. optimized): drawn right of the --poses/dataset one")
      ->check(inputFile());
  command->add_option("--gt", args->gt, "Ground-truth trajectory to overlay (aligned rigidly)")
      ->check(inputFile());
  command->add_option("--crop", args->crop, "Show only xmin,ymin,xmax,ymax (metres)")
      ->check(CLI::Validator(
          [](const std::string& text) -> std::string {
            try {
              render::parseBox(text);
              return "";
            } catch (const Error& e) {
              return e.what();
            }
          },
          "XMIN,YMIN,XMAX,YMAX"));
  command->add_option("--width", args->settings.width, "Picture width (px)")
      ->check(numberIn({200, 16384, false, false, ""}, NumberKind::Integer, "px"))
      ->capture_default_str();
  command
      ->add_option("--height", args->settings.height,
                   "Picture height (px); --compare adds a row 7/10 as tall below it where planes got thinner")
      ->check(numberIn({200, 16384, false, false, ""}, NumberKind::Integer, "px"))
      ->capture_default_str();
  command->add_option("--voxel", args->settings.voxel, "Voxel size of the merged maps (m; 0 = keep all)")
      ->check(mapVoxel())
      ->capture_default_str();
  command->add_flag("--no-side", args->no_side, "Leave out the side view (x vs z)");
  command->callback([args] { run(*args); });
}

}  // namespace hba::cli
