#pragma once
// The report page (`OUT/report.html`): one self-contained HTML file that
// shows the merged map in 3D (plain WebGL, no network), the input and the
// optimized map toggled or side by side, the trajectories, loop closures
// and revisits, the self-check's regions, and the run's figures as tables.
// The points are kept in their scans' frames with the scan's index, so the
// page places them with either pose set; docs/report_page.md says more.
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "hba/core/memory_budget.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"

namespace hba::render {

struct ReportPageInput {
  std::string title;               // the page's heading (a dataset's name)
  std::vector<Pose> before;        // the input poses, one per scan
  std::vector<Pose> after;         // the optimized poses, one per scan
  std::vector<Pose> ground_truth;  // empty, or one per scan (moved rigidly onto `after`)
  nlohmann::json report;           // report.json's content, or null
  std::filesystem::path picture;   // a PNG shown below the tables (before_after.png), or empty
};

struct ReportPageSettings {
  std::size_t point_budget = 2'000'000;  // at most this many points (the map is thinned to fit)
  double voxel = 0.1;                    // m: the finest world voxel the map is thinned at
  double scans_voxel = 0.0;              // the scans come downsampled at this voxel (m; 0: as recorded)
  MemoryBudget memory;                   // MemoryExceeded once the process outgrows it
};

// What was written.
struct ReportPageFigures {
  std::size_t points = 0;  // map points on the page
  double voxel = 0.0;      // m: the voxel they were thinned at
  std::size_t bytes = 0;   // the file's size
};

// Writes the page atomically. Throws hba::Error naming the file (a pose
// count that is not the scans', an unreadable picture, a full disk) and
// MemoryExceeded (see ReportPageSettings::memory).
ReportPageFigures writeReportPage(const io::ScanSource& scans, const ReportPageInput& input,
                                  const std::filesystem::path& html, const ReportPageSettings& settings = {});

// Whether `path` is a page written by writeReportPage (which `hba view` may
// replace without --force).
bool isReportPage(const std::filesystem::path& path);

}  // namespace hba::render
