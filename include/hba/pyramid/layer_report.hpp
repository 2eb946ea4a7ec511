#pragma once
// What the pyramid reports of its layers, windows and top-down passes
// (report.json's "layer_reports", "iterations"; docs/cli.md lists the keys).
#include <cstddef>
#include <vector>

#include "hba/core/pose.hpp"

namespace hba::pyramid {

// What one layer's BAs did in one outer iteration.
struct LayerReport {
  int iteration = 0;    // outer iteration, from 1
  int layer = 0;        // pyramid layer, from 1 (layer 1 = input scans)
  bool global = false;  // the top layer's single global BA
  std::size_t frames = 0;
  std::size_t windows = 0;
  std::size_t windows_without_planes = 0;
  // Windows whose BA made the planes found at their input poses blurrier:
  // they keep their input poses (trust check, docs/pyramid.md).
  std::size_t windows_untrusted = 0;
  // Windows whose BA gained no more than fitting noise would: they keep
  // their start poses (settle check, docs/pyramid.md).
  std::size_t windows_settled = 0;
  // Windows whose coarse-to-fine result failed the trust check, solved
  // again on their input's finest planes from their input (counted with
  // whichever verdict that then got: settled, moved or untrusted).
  std::size_t windows_solved_again = 0;
  std::size_t planes = 0;        // summed over windows
  std::size_t plane_points = 0;  // summed over windows
  std::size_t cloud_points = 0;  // points in this layer's clouds (after downsampling)
  // Bytes the processes sent each other after this layer (every member's
  // message once; 0 in one process), and the largest one member sent.
  std::size_t exchange_bytes = 0;
  std::size_t exchange_bytes_largest = 0;
  std::size_t lm_iterations = 0;       // summed over windows
  std::size_t association_rounds = 0;  // summed over windows
  double cost_before = 0.0;            // summed BA cost over windows
  double cost_after = 0.0;
  double rms_before = 0.0;  // point-to-plane RMS over all plane points (m)
  double rms_after = 0.0;
  double seconds = 0.0;
};

// One window of the pyramid as it ran: the layer-1 scans its frames start
// at, their poses as the window began (the layer's, chained from the
// windows below) and as its BA left them (frame 0 held). Kept for a
// diagnosis against a reference (window_errors.hpp): where error enters.
struct WindowRecord {
  int iteration = 0;
  int layer = 0;
  bool global = false;
  std::vector<std::size_t> nodes;
  std::vector<Pose> start;
  std::vector<Pose> optimized;
};

struct IterationReport {
  int iteration = 0;
  std::size_t factors = 0;
  double graph_cost_before = 0.0;
  double graph_cost_after = 0.0;
  double max_translation_update = 0.0;  // m, over all layer-1 poses
  double max_rotation_update = 0.0;     // degrees
  double seconds_graph = 0.0;
};

}  // namespace hba::pyramid
