// `hba eval --gt A --est B`: absolute and relative trajectory errors.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "enum_choice.hpp"
#include "file_checks.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "hba/eval/association.hpp"
#include "hba/eval/trajectory_error.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/render/error_plot.hpp"
#include "json_text.hpp"
#include "number_checks.hpp"
#include "output_dir.hpp"

namespace hba::cli {
namespace {

struct EvalArgs {
  std::string gt, est, gt_format, est_format, label, json, plot;
  std::string align = "se3", assoc = "auto", delta_unit = "frames";
  double delta = 1.0;
  double t_max_diff = 0.01;
  double min_matched = 0.5;
  bool force = false;
};

Trajectory readTrajectory(const std::string& path, const std::string& format) {
  Trajectory trajectory =
      format.empty() ? io::readPoses(path) : io::readPoses(path, parseEnum<io::PoseFormat>(format));
  const std::string unit = io::stampsToSeconds(trajectory.stamps);
  if (!unit.empty()) spdlog::info("{}: the stamps are in {}; read as seconds", path, unit);
  return trajectory;
}

// Too few estimated poses with a ground-truth stamp within the tolerance
// (none at all included): the files' clocks differ, as scan indices against
// seconds do. Says both files' stamps and the flag that would pair them.
void refuseTimesThatDisagree(const EvalArgs& args, const Trajectory& gt, const Trajectory& est,
                             std::size_t matched) {
  const double share = static_cast<double>(matched) / static_cast<double>(est.size());
  if (matched > 0 && share >= args.min_matched) return;
  const std::string other_pairing =
      gt.size() == est.size()
          ? fmt::format("pair poses by index (--assoc index: both files hold {} poses)", est.size())
          : fmt::format(
                "if the clocks agree but the stamps lie further apart, widen the tolerance (--t-max-diff; "
                "pairing by index, --assoc index, needs equal counts, not {} and {})",
                est.size(), gt.size());
  throw Error(fmt::format(
      "{}: only {} of {} estimated poses ({:.0f} %) have a ground-truth pose within {} s in {} "
      "(--min-matched {}). The two files' times do not agree: {} holds {}, {} holds {}. A TUM file written "
      "from data without timestamps carries scan indices (0, 1, 2, ...): give the stamps (hba optimize "
      "--times FILE), or {}.",
      args.est, matched, est.size(), 100.0 * share, args.t_max_diff, args.gt, args.min_matched, args.est,
      eval::describeStamps(est.stamps), args.gt, eval::describeStamps(gt.stamps), other_pairing));
}

std::string statsRow(const std::string& prefix, const char* name, const eval::ErrorStats& s) {
  // A space before every number: 123.456789 must not run into its neighbour.
  return fmt::format("{}{:<14} {:>11.6f} {:>11.6f} {:>11.6f} {:>11.6f} {:>11.6f} {:>11.6f}\n", prefix, name,
                     s.rmse, s.mean, s.median, s.std, s.min, s.max);
}

std::string table(const EvalArgs& args, const eval::TrajectoryEvaluation& r) {
  const std::string prefix = args.label.empty() ? "" : args.label + "  ";
  std::string out =
      fmt::format("{}{} of {} estimated poses matched by {}, alignment {}{}; RPE over {} {}\n", prefix,
                  r.matched, r.estimate_count, hba::toString(r.association_used), args.align,
                  args.align == "sim3" ? fmt::format(" (scale {:.6f})", r.alignment.scale) : "", args.delta,
                  args.delta_unit);
  out += fmt::format("{}{:<14} {:>11} {:>11} {:>11} {:>11} {:>11} {:>11}\n", prefix, "", "rmse", "mean",
                     "median", "std", "min", "max");
  out += statsRow(prefix, "ATE trans m", r.ate.translation_m);
  out += statsRow(prefix, "ATE rot deg", r.ate.rotation_deg);
  out += statsRow(prefix, "RPE trans m", r.rpe.translation_m);
  out += statsRow(prefix, "RPE rot deg", r.rpe.rotation_deg);
  return out;
}

nlohmann::json statsJson(const eval::ErrorStats& s) {
  return {{"count", s.count}, {"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median},
          {"std", s.std},     {"min", s.min},   {"max", s.max}};
}

nlohmann::json reportJson(const EvalArgs& args, const eval::TrajectoryEvaluation& r) {
  nlohmann::json rotation = nlohmann::json::array();
  for (int i = 0; i < 3; ++i)
    rotation.push_back({r.alignment.R(i, 0), r.alignment.R(i, 1), r.alignment.R(i, 2)});
  return {
      {"label", args.label},
      {"gt", args.gt},
      {"est", args.est},
      {"association", hba::toString(r.association_used)},
      {"matched", r.matched},
      {"gt_poses", r.reference_count},
      {"est_poses", r.estimate_count},
      {"alignment",
       {{"kind", args.align},
        {"rotation", rotation},
        {"translation", {r.alignment.t.x(), r.alignment.t.y(), r.alignment.t.z()}},
        {"scale", r.alignment.scale}}},
      {"ate",
       {{"translation_m", statsJson(r.ate.translation_m)}, {"rotation_deg", statsJson(r.ate.rotation_deg)}}},
      {"rpe",
       {{"delta", args.delta},
        {"delta_unit", args.delta_unit},
        {"translation_m", statsJson(r.rpe.translation_m)},
        {"rotation_deg", statsJson(r.rpe.rotation_deg)}}},
  };
}

void run(const EvalArgs& args) {
  eval::EvalOptions options;
  options.alignment = parseEnum<eval::Alignment>(args.align);
  options.association = parseEnum<eval::AssociationMode>(args.assoc);
  options.max_time_diff = args.t_max_diff;
  options.rpe_delta = args.delta;
  options.rpe_unit = parseEnum<eval::DeltaUnit>(args.delta_unit);
  if (options.rpe_unit == eval::DeltaUnit::Frames && args.delta != std::floor(args.delta))
    throw ValueError(
        fmt::format("--delta: in frames (--delta-unit) it must be a whole number, got {}", args.delta));

  if (!args.plot.empty() && std::filesystem::path(args.plot).extension() != ".png")
    throw ValueError(args.plot + ": --plot must name a .png file");
  std::unique_ptr<OutputLock> json_claim, plot_claim;  // held until written
  if (!args.json.empty()) json_claim = claimOutputFile(args.json, args.force);
  if (!args.plot.empty()) {
    if (std::filesystem::path(args.plot) == std::filesystem::path(args.json))
      failAt(args.plot, "is also the --json file; give them two names");
    plot_claim = claimOutputFile(args.plot, args.force);
  }
  const Trajectory gt = readTrajectory(args.gt, args.gt_format);
  const Trajectory est = readTrajectory(args.est, args.est_format);
  if (eval::pairsByTime(gt, est, options.association)) {
    refuseTimesThatDisagree(args, gt, est, eval::pairByTime(gt.stamps, est.stamps, args.t_max_diff).size());
  }
  const eval::TrajectoryEvaluation result = eval::evaluateTrajectory(gt, est, options);
  const double share = static_cast<double>(result.matched) / static_cast<double>(result.estimate_count);
  if (share < args.min_matched && result.association_used == eval::AssociationMode::Index) {
    throw Error(
        fmt::format("{}: only {} of {} estimated poses have a ground-truth pose at their index in {} "
                    "({} poses; --min-matched {}): are they the same sequence?",
                    args.est, result.matched, result.estimate_count, args.gt, gt.size(), args.min_matched));
  }
  if (result.matched < result.estimate_count) {
    spdlog::warn("{} estimated poses have no ground truth within {} s and are not evaluated",
                 result.estimate_count - result.matched, args.t_max_diff);
  }
  fmt::print("{}", table(args, result));
  if (!args.plot.empty()) {
    render::ErrorSeries series;
    series.x = result.pose_times;
    series.translation_m = result.ate_translation_m;
    series.rotation_deg = result.ate_rotation_deg;
    series.x_label = est.hasStamps() ? "time (s)" : "pose index";
    series.title = std::filesystem::path(args.est).filename().string();
    if (est.hasStamps()) {  // seconds from the start, not since 1970
      for (double& t : series.x) t -= est.stamps.front();
    }
    render::writeErrorPlot(series, args.plot);
    spdlog::info("wrote {}", args.plot);
  }
  if (!args.json.empty()) {
    writeFileAtomically(args.json,
                        [&](std::ostream& out) { out << jsonText(reportJson(args, result), 2) << '\n'; });
  }
}

}  // namespace

void registerEvalCommand(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  auto* command = app.add_subcommand(
      "eval", "Trajectory accuracy: ATE and RPE of an estimate against ground truth (evo's definitions)");
  command->add_option("--gt", args->gt, "Ground-truth trajectory file")->required()->check(inputFile());
  command->add_option("--est", args->est, "Estimated trajectory file")->required()->check(inputFile());
  const auto formats = oneOf<io::PoseFormat>();
  command->add_option("--gt-format", args->gt_format, "Format of --gt (default: detected)")->check(formats);
  command->add_option("--est-format", args->est_format, "Format of --est (default: detected)")
      ->check(formats);
  command->add_option("--align", args->align, "Alignment of the estimate onto the ground truth")
      ->check(oneOf<eval::Alignment>())
      ->capture_default_str();
  command
      ->add_option("--assoc", args->assoc,
                   "Pose pairing: auto = by time when both files have timestamps, else by index")
      ->check(oneOf<eval::AssociationMode>())
      ->capture_default_str();
  command->add_option("--t-max-diff", args->t_max_diff, "Time association tolerance (s)")
      ->check(realIn(0.0, 3600.0, "s"))
      ->capture_default_str();
  command
      ->add_option("--min-matched", args->min_matched,
                   "Fail when fewer than this share of estimated poses pair with ground truth")
      ->check(realIn(0.0, 1.0))
      ->capture_default_str();
  command->add_option("--delta", args->delta, "RPE distance between compared poses")
      ->check(positiveUpTo(1e6))
      ->capture_default_str();
  command->add_option("--delta-unit", args->delta_unit, "Unit of --delta")
      ->check(oneOf<eval::DeltaUnit>())
      ->capture_default_str();
  command->add_option("--label", args->label, "Text printed before every output line");
  command->add_option("--json", args->json, "Also write the results as JSON to this file");
  command->add_option("--plot", args->plot, "Also draw the ATE over time into this .png");
  command->add_flag("--force", args->force, "Replace an existing --json or --plot file");
  command->callback([args] { run(*args); });
}

}  // namespace hba::cli
