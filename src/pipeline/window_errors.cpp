#include "hba/pipeline/window_errors.hpp"

#include <cmath>
#include <string>

#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"

namespace hba::pipeline {
namespace {

constexpr double kDeg = 180.0 / M_PI;

// Sums of squared errors by axis, turned into RMS at the end.
struct ErrorSums {
  Vec3 rotation = Vec3::Zero();
  Vec3 translation = Vec3::Zero();

  void add(const Pose& estimate, const Pose& reference) {
    const Vec3 angle = so3Log(Mat3(estimate.R() * reference.R().transpose()));
    const Vec3 offset = estimate.t - reference.t;
    rotation += angle.cwiseAbs2();
    translation += offset.cwiseAbs2();
  }

  RelativeErrorRms rms(std::size_t pairs) const {
    RelativeErrorRms out;
    if (pairs == 0) return out;
    const double n = static_cast<double>(pairs);
    for (int a = 0; a < 3; ++a) {
      out.rotation_deg[static_cast<std::size_t>(a)] = std::sqrt(rotation[a] / n) * kDeg;
      out.translation_m[static_cast<std::size_t>(a)] = std::sqrt(translation[a] / n);
    }
    out.rotation_rms_deg = std::sqrt(rotation.sum() / n) * kDeg;
    out.translation_rms_m = std::sqrt(translation.sum() / n);
    return out;
  }
};

// The relative pose of scan `k` from scan `first` in `poses`.
Pose relativeOf(const std::vector<Pose>& poses, std::size_t first, std::size_t k) {
  return relative(poses[first], poses[k]);
}

struct RowSums {
  std::size_t windows = 0;
  std::size_t pairs = 0;
  ErrorSums input, start, window, hierarchy, final;
};

void checkCounts(const std::vector<Pose>& input, const std::vector<Pose>& hierarchy,
                 const std::vector<Pose>& final, const std::vector<Pose>& reference) {
  if (hierarchy.size() != input.size() || final.size() != input.size() || reference.size() != input.size()) {
    throw Error("window errors: " + std::to_string(input.size()) + " input poses, " +
                std::to_string(hierarchy.size()) + " of the hierarchy, " + std::to_string(final.size()) +
                " final and " + std::to_string(reference.size()) + " of the reference: they must be as many");
  }
}

}  // namespace

std::vector<LayerWindowErrors> windowErrors(const std::vector<WindowRecord>& records,
                                            const std::vector<Pose>& input,
                                            const std::vector<Pose>& hierarchy,
                                            const std::vector<Pose>& final,
                                            const std::vector<Pose>& reference) {
  checkCounts(input, hierarchy, final, reference);
  std::vector<LayerWindowErrors> rows;
  std::vector<RowSums> sums;
  for (const WindowRecord& record : records) {
    if (rows.empty() || rows.back().iteration != record.iteration || rows.back().layer != record.layer) {
      LayerWindowErrors row;
      row.iteration = record.iteration;
      row.layer = record.layer;
      row.global = record.global;
      rows.push_back(row);
      sums.emplace_back();
    }
    RowSums& sum = sums.back();
    ++sum.windows;
    if (record.start.size() != record.nodes.size() || record.optimized.size() != record.nodes.size())
      throw Error("window errors: a window record's poses and scans differ in number");
    for (std::size_t node : record.nodes) {
      if (node >= reference.size()) {
        throw Error("window errors: a window names scan " + std::to_string(node) + " of " +
                    std::to_string(reference.size()));
      }
    }
    const std::size_t first = record.nodes.front();
    for (std::size_t k = 1; k < record.nodes.size(); ++k) {
      const std::size_t node = record.nodes[k];
      const Pose truth = relativeOf(reference, first, node);
      sum.input.add(relativeOf(input, first, node), truth);
      sum.start.add(relative(record.start.front(), record.start[k]), truth);
      sum.window.add(relative(record.optimized.front(), record.optimized[k]), truth);
      sum.hierarchy.add(relativeOf(hierarchy, first, node), truth);
      sum.final.add(relativeOf(final, first, node), truth);
      ++sum.pairs;
    }
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const RowSums& sum = sums[i];
    LayerWindowErrors& row = rows[i];
    row.windows = sum.windows;
    row.pairs = sum.pairs;
    row.input = sum.input.rms(sum.pairs);
    row.start = sum.start.rms(sum.pairs);
    row.window = sum.window.rms(sum.pairs);
    row.hierarchy = sum.hierarchy.rms(sum.pairs);
    row.final = sum.final.rms(sum.pairs);
  }
  return rows;
}

}  // namespace hba::pipeline
