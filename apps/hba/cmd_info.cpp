// `hba info DIR`: what discovery found in a dataset folder and a summary of
// its scans and trajectory, without reading whole scans where avoidable
// (PCD headers and .bin file sizes give the point counts).
#include <tbb/parallel_for.h>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <iostream>

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "dataset_args.hpp"
#include "hba/core/error.hpp"
#include "hba/io/scan_file_summary.hpp"
#include "io/file_warnings.hpp"
#include "json_text.hpp"
#include "number_checks.hpp"

namespace hba::cli {
namespace {

struct InfoOptions {
  DatasetArgs dataset;
  std::size_t sample = 0;  // 0: every scan
  bool json = false;
};

struct PointStats {
  std::uint64_t min = 0, median = 0, max = 0;
  std::size_t scans_looked_at = 0;
};

struct Summary {
  PointStats points;
  std::vector<std::string> fields;  // of the first scan
  std::string scan_encoding;        // e.g. "PCD binary", "KITTI float32"
  double length_m = 0.0;
  Vec3 extent_min = Vec3::Zero(), extent_max = Vec3::Zero();
  bool has_duration = false;
  double duration_s = 0.0;
};

// `count` indices spread evenly over [0, n), first and last included.
std::vector<std::size_t> evenlySpaced(std::size_t n, std::size_t count) {
  std::vector<std::size_t> indices;
  if (count == 0 || count >= n) count = n;
  for (std::size_t k = 0; k < count; ++k) {
    indices.push_back(count == 1 ? 0 : (k * (n - 1) + (count - 1) / 2) / (count - 1));
  }
  return indices;
}

// Scans that store no points are read as empty: name a few, count them all.
void warnAboutEmptyScans(const io::Dataset& dataset, const std::vector<std::size_t>& indices,
                         const std::vector<std::uint64_t>& counts) {
  std::size_t empty = 0;
  for (std::size_t k = 0; k < counts.size(); ++k) {
    if (counts[k] != 0) continue;
    ++empty;
    io::warnAboutFile(
        dataset.scanPath(indices[k]), "scans with no points",
        "the scan stores no points: it adds nothing to the map or to the optimization of its pose");
  }
  if (empty > io::kNamedFilesPerProblem) {
    spdlog::warn("{} of the {} scans looked at store no points", empty, counts.size());
  }
}

PointStats pointStats(const io::Dataset& dataset, std::size_t sample) {
  const std::vector<std::size_t> indices = evenlySpaced(dataset.size(), sample);
  std::vector<std::uint64_t> counts(indices.size());
  std::vector<std::exception_ptr> failures(indices.size());
  // Reading thousands of headers is I/O latency bound: overlap the reads.
  tbb::parallel_for(std::size_t(0), indices.size(), [&](std::size_t k) {
    try {
      counts[k] = dataset.recording() ? dataset.loadScan(indices[k]).size()
                                      : io::storedPointCount(dataset.scanPath(indices[k]));
    } catch (...) {
      failures[k] = std::current_exception();
    }
  });
  // Report the first bad scan in file order, whichever thread met it first.
  for (const std::exception_ptr& failure : failures) {
    if (failure) std::rethrow_exception(failure);
  }
  warnAboutEmptyScans(dataset, indices, counts);
  std::sort(counts.begin(), counts.end());
  return {counts.front(), counts[counts.size() / 2], counts.back(), counts.size()};
}

Summary summarize(const io::Dataset& dataset, std::size_t sample) {
  Summary summary;
  summary.points = pointStats(dataset, sample);
  if (const rec::Recording* recording = dataset.recording()) {
    summary.fields = recording->cloudFields();
    summary.scan_encoding = recording->cloudType() + " on " + recording->cloudTopic();
  } else {
    io::ScanFileFields first = io::describeScanFields(dataset.scanPath(0));
    summary.fields = std::move(first.fields);
    summary.scan_encoding = std::move(first.encoding);
  }
  const Trajectory& trajectory = dataset.trajectory();
  summary.length_m = pathLength(trajectory.poses);
  summary.extent_min = summary.extent_max = trajectory.poses.front().t;
  for (const Pose& pose : trajectory.poses) {
    summary.extent_min = summary.extent_min.cwiseMin(pose.t);
    summary.extent_max = summary.extent_max.cwiseMax(pose.t);
  }
  if (trajectory.hasStamps()) {
    summary.has_duration = true;
    summary.duration_s = trajectory.stamps.back() - trajectory.stamps.front();
  }
  return summary;
}

// Rounding noise like -1e-17 would print as "-0.00".
double printable(double metres) { return std::abs(metres) < 5e-3 ? 0.0 : metres; }

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& word : words) out += (out.empty() ? "" : " ") + word;
  return out;
}

void printRecording(const rec::Recording& recording) {
  std::cout << "recording:   " << recording.path().string() << " (" << recording.format() << ")\n"
            << "topics:\n"
            << rec::describeTopics(recording.topics()) << "\n"
            << "scans:       " << recording.size() << " of the " << recording.cloudMessages()
            << " messages on " << recording.cloudTopic() << " (frame '" << recording.cloudFrame() << "')\n"
            << "poses:       " << recording.poseTopic() << ", interpolated at each scan's stamp\n";
  for (const std::string& warning : recording.warnings()) std::cout << "warning:     " << warning << "\n";
}

void printText(const io::Dataset& dataset, const Summary& s) {
  if (dataset.recording()) {
    printRecording(*dataset.recording());
  } else {
    const std::string extension = dataset.scanPath(0).extension().string();
    std::cout << "dataset:     " << dataset.root().string() << "\n"
              << "layout:      " << dataset.layout() << "\n"
              << "scans:       " << dataset.size() << " (" << extension << ") in "
              << dataset.scansDir().string() << "\n"
              << "poses:       " << dataset.trajectory().size() << " (" << hba::toString(dataset.poseFormat())
              << ") from " << dataset.posesFile().string() << "\n";
  }
  if (!dataset.calibrationFile().empty()) {
    std::cout << "calibration: camera poses turned into LiDAR poses with Tr of "
              << dataset.calibrationFile().string() << "\n";
  }
  std::cout << fmt::format("points/scan: min {}, median {}, max {} ({} of {} scans looked at)\n",
                           s.points.min, s.points.median, s.points.max, s.points.scans_looked_at,
                           dataset.size())
            << "fields:      " << joined(s.fields) << " (" << s.scan_encoding << ")\n"
            << fmt::format("trajectory:  {:.2f} m long\n", s.length_m)
            << fmt::format("extent:      x [{:.2f}, {:.2f}]  y [{:.2f}, {:.2f}]  z [{:.2f}, {:.2f}] m\n",
                           printable(s.extent_min.x()), printable(s.extent_max.x()),
                           printable(s.extent_min.y()), printable(s.extent_max.y()),
                           printable(s.extent_min.z()), printable(s.extent_max.z()));
  if (s.has_duration) {
    const std::string source = dataset.stampsSource() == "times file"
                                   ? dataset.timesFile().filename().string()
                               : dataset.stampsSource() == "scan names" ? "the scan names"
                               : dataset.recording()                    ? "the clouds' headers"
                                                     : dataset.posesFile().filename().string();
    std::cout << fmt::format("duration:    {:.2f} s (timestamps from {})\n", s.duration_s, source);
  } else {
    std::cout << "duration:    unknown (no timestamps: give --times FILE)\n";
  }
  if (!dataset.inputFrame().empty() && dataset.calibrationFile().empty()) {
    std::cout << "pose frame:  " << dataset.inputFrame() << " poses turned into sensor poses (--extrinsic)\n";
  }
  if (dataset.scansInWorld()) std::cout << "scans:       saved in the world frame (--scans-in-world)\n";
  const double far = std::max(s.extent_min.cwiseAbs().maxCoeff(), s.extent_max.cwiseAbs().maxCoeff());
  if (far > 1e4) {
    std::cout << fmt::format(
        "coordinates: {:.0f} km from the origin; hba works relative to the first "
        "pose (no precision lost)\n",
        far / 1000.0);
  }
}

void printJson(const io::Dataset& dataset, const Summary& s) {
  nlohmann::json out = {
      {"dataset", dataset.root().string()},
      {"layout", dataset.layout()},
      {"scans_dir", dataset.scansDir().string()},
      {"scan_count", dataset.size()},
      {"scan_extension", dataset.recording() ? "" : dataset.scanPath(0).extension().string()},
      {"poses_file", dataset.posesFile().string()},
      {"pose_format", hba::toString(dataset.poseFormat())},
      {"pose_count", dataset.trajectory().size()},
      {"calibration_file", dataset.calibrationFile().string()},
      {"times_file", dataset.timesFile().string()},
      {"stamps", dataset.stampsSource()},
      {"pose_frame", dataset.inputFrame().empty() ? "sensor" : dataset.inputFrame()},
      {"scans_in_world", dataset.scansInWorld()},
      {"points_per_scan",
       {{"min", s.points.min},
        {"median", s.points.median},
        {"max", s.points.max},
        {"scans_looked_at", s.points.scans_looked_at}}},
      {"fields", s.fields},
      {"scan_encoding", s.scan_encoding},
      {"trajectory_length_m", s.length_m},
      {"extent_min", {s.extent_min.x(), s.extent_min.y(), s.extent_min.z()}},
      {"extent_max", {s.extent_max.x(), s.extent_max.y(), s.extent_max.z()}},
      {"duration_s", s.has_duration ? nlohmann::json(s.duration_s) : nlohmann::json(nullptr)},
  };
  if (const rec::Recording* recording = dataset.recording()) {
    nlohmann::json topics = nlohmann::json::array();
    for (const rec::RecordingTopic& topic : recording->topics()) {
      topics.push_back({{"topic", topic.topic}, {"type", topic.type}, {"messages", topic.messages}});
    }
    out["recording"] = {{"format", recording->format()},
                        {"topics", topics},
                        {"cloud_topic", recording->cloudTopic()},
                        {"cloud_frame", recording->cloudFrame()},
                        {"cloud_messages", recording->cloudMessages()},
                        {"pose_topic", recording->poseTopic()}};
  }
  std::cout << jsonText(out, 2) << "\n";
}

void runInfo(const InfoOptions& options) {
  const io::Dataset dataset = options.dataset.open();
  const Summary summary = summarize(dataset, options.sample);
  if (options.json) {
    printJson(dataset, summary);
  } else {
    printText(dataset, summary);
  }
}

}  // namespace

void registerInfoCommand(CLI::App& app) {
  auto options = std::make_shared<InfoOptions>();
  auto* command = app.add_subcommand(
      "info",
      "Show what a dataset folder or recording holds: layout (topics), scans, poses, points, trajectory");
  options->dataset.addTo(command);
  command
      ->add_option("--sample", options->sample,
                   "Look at N evenly spaced scans for the point statistics (0 = all)")
      ->check(numberIn({1, 1e9, false, false, "all"}, NumberKind::Count));
  command->add_flag("--json", options->json, "Print a JSON document instead of text");
  command->callback([options] { runInfo(*options); });
}

}  // namespace hba::cli
