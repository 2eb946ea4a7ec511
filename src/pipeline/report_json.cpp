#include "pipeline/report_json.hpp"

namespace hba::pipeline {
namespace {

nlohmann::json layersJson(const HbaReport& r) {
  nlohmann::json layers = nlohmann::json::array();
  for (const auto& l : r.layer_reports) {
    layers.push_back({{"iteration", l.iteration},
                      {"layer", l.layer},
                      {"global", l.global},
                      {"frames", l.frames},
                      {"windows", l.windows},
                      {"windows_without_planes", l.windows_without_planes},
                      {"windows_untrusted", l.windows_untrusted},
                      {"windows_settled", l.windows_settled},
                      {"windows_solved_again", l.windows_solved_again},
                      {"planes", l.planes},
                      {"plane_points", l.plane_points},
                      {"cloud_points", l.cloud_points},
                      {"exchange_bytes", l.exchange_bytes},
                      {"exchange_bytes_largest", l.exchange_bytes_largest},
                      {"lm_iterations", l.lm_iterations},
                      {"association_rounds", l.association_rounds},
                      {"cost_before", l.cost_before},
                      {"cost_after", l.cost_after},
                      {"plane_rms_before_m", l.rms_before},
                      {"plane_rms_after_m", l.rms_after},
                      {"seconds", l.seconds}});
  }
  return layers;
}

nlohmann::json relativeErrorJson(const RelativeErrorRms& e) {
  return {{"rotation_rms_deg", e.rotation_rms_deg},
          {"translation_rms_m", e.translation_rms_m},
          {"rotation_xyz_deg", e.rotation_deg},
          {"translation_xyz_m", e.translation_m}};
}

nlohmann::json iterationsJson(const HbaReport& r) {
  nlohmann::json iterations = nlohmann::json::array();
  for (const auto& it : r.iterations) {
    iterations.push_back({{"iteration", it.iteration},
                          {"factors", it.factors},
                          {"pose_graph_cost_before", it.graph_cost_before},
                          {"pose_graph_cost_after", it.graph_cost_after},
                          {"max_translation_update_m", it.max_translation_update},
                          {"max_rotation_update_deg", it.max_rotation_update},
                          {"seconds_pose_graph", it.seconds_graph}});
  }
  return iterations;
}

nlohmann::json closureJson(const ClosureReport& cl) {
  nlohmann::json loops = nlohmann::json::array();
  for (const LoopReport& l : cl.loops) {
    loops.push_back({{"from", l.from},
                     {"to", l.to},
                     {"source", l.source},
                     {"verified", l.verified},
                     {"used", l.used},
                     {"reason", l.reason},
                     {"shared_planes", l.shared_planes},
                     {"overlap", l.overlap},
                     {"plane_rms_m", l.rms_m},
                     {"correction_m", l.correction_m},
                     {"correction_deg", l.correction_deg}});
  }
  return {{"ran", cl.ran},
          {"revisits_searched", cl.revisits_searched},
          {"loops_given", cl.loops_given},
          {"revisit_candidates", cl.revisit_candidates},
          {"verified", cl.verified},
          {"rejected_by_planes", cl.rejected_by_planes},
          {"dropped_as_inconsistent", cl.dropped_as_inconsistent},
          {"loops_used", cl.loops_used},
          {"priors_given", cl.priors_given},
          {"priors_dropped", cl.priors_dropped},
          {"priors_used", cl.priors_used},
          {"largest_move_m", cl.largest_move_m},
          {"held_at_input", cl.held_at_input},
          {"anchoring_move_m", cl.anchoring_move_m},
          {"anchoring_priors_dropped", cl.anchoring_priors_dropped},
          {"loops", loops},
          {"seconds", cl.seconds}};
}

nlohmann::json refinementJson(const RefinementReport& f) {
  return {{"ran", f.ran},
          {"blocks", f.blocks},
          {"scan_points", f.scan_points},
          {"planes", f.planes},
          {"observations", f.observations},
          {"plane_points", f.plane_points},
          {"plane_rms_before_m", f.rms_before},
          {"plane_rms_after_m", f.rms_after},
          {"lm_iterations", f.iterations},
          {"cg_products", f.cg_products},
          {"associations", f.rounds},
          {"held_pairs", f.held_pairs},
          {"still_sliding", f.still_sliding},
          {"position_priors", f.position_priors},
          {"converged", f.converged},
          {"converged_at_start", f.converged_at_start},
          {"gain_over_noise", f.gain_over_noise},
          {"groups",
           {{"ran", f.groups.ran},
            {"groups", f.groups.groups},
            {"frames_per_group", f.groups.frames_per_group},
            {"points", f.groups.points},
            {"planes", f.groups.planes},
            {"plane_rms_before_m", f.groups.rms_before},
            {"plane_rms_after_m", f.groups.rms_after},
            {"rejected", f.groups.rejected},
            {"largest_move_m", f.groups.largest_move_m},
            {"seconds", f.groups.seconds}}},
          {"seconds", f.seconds}};
}

nlohmann::json consistencyJson(const ConsistencyReport& c) {
  nlohmann::json regions = nlohmann::json::array();
  for (std::size_t k = 0; k < c.region_first_frame.size(); ++k) {
    regions.push_back({{"first_frame", c.region_first_frame[k]},
                       {"input_rms_m", c.region_input_rms[k]},
                       {"final_rms_m", c.region_final_rms[k]}});
  }
  return {{"planes", c.planes},
          {"input_rms_m", c.input_rms},
          {"hierarchy_rms_m", c.hierarchy_rms},
          {"final_rms_m", c.final_rms},
          {"hierarchy_rejected", c.hierarchy_rejected},
          {"hierarchy_insignificant", c.hierarchy_insignificant},
          {"final_rejected", c.final_rejected},
          {"regions", regions}};
}

}  // namespace

nlohmann::json windowSizeJson(const WindowSize& w) {
  return {{"window", w.window},
          {"stride", w.stride},
          {"automatic", w.automatic},
          {"points_per_scan", w.points_per_scan}};
}

nlohmann::json finalVoxelJson(const FinalVoxel& v) {
  return {{"setting_m", v.setting},
          {"chosen_m", v.chosen},
          {"coarsened", v.coarsened},
          {"scan_points_at_setting", v.scan_points_at_setting},
          {"scan_points_at_chosen", v.scan_points_at_chosen}};
}

nlohmann::json memoryEstimateJson(const MemoryEstimate& estimate, const ScanDensity& density) {
  constexpr double kMiB = 1024.0 * 1024.0;
  nlohmann::json stages = nlohmann::json::array();
  for (const StageMemory& s : estimate.stages)
    stages.push_back({{"stage", stageName(s.stage)}, {"mib", s.bytes / kMiB}, {"detail", s.detail}});
  return {{"peak_mib", estimate.peakBytes() / kMiB},
          {"peak_stage", stageName(estimate.largest().stage)},
          {"stages", stages},
          {"scans_sampled", density.sampled},
          {"points_per_scan", density.points}};
}

nlohmann::json reportToJson(const HbaReport& r) {
  return {{"frames", r.frames},
          {"largest_update",
           {{"translation_m", r.largest_translation_update}, {"rotation_deg", r.largest_rotation_update}}},
          {"closure", closureJson(r.closure)},
          {"refinement", refinementJson(r.refinement)},
          {"consistency", consistencyJson(r.consistency)},
          {"layers", r.layers},
          {"windows", windowSizeJson(r.windows)},
          {"final_voxel", finalVoxelJson(r.final_voxel)},
          {"threads", r.threads},
          {"processes", r.processes},
          // "converged: false" read as a failure after the default single pass.
          {"outer_iterations",
           {{"run", r.iterations.size()}, {"stopped", r.rounds_stopped}, {"reason", r.rounds_reason}}},
          {"layer_reports", layersJson(r)},
          {"iterations", iterationsJson(r)},
          {"seconds",
           {{"read", r.seconds_read},
            {"downsample", r.seconds_downsample},
            {"voxelize", r.seconds_voxelize},
            {"solve", r.seconds_solve},
            {"keyframes", r.seconds_keyframes},
            {"pose_graph", r.seconds_graph},
            {"total", r.seconds_total}}},
          {"warnings", r.warnings}};
}

nlohmann::json windowErrorsToJson(const std::vector<LayerWindowErrors>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const LayerWindowErrors& row : rows) {
    out.push_back({{"iteration", row.iteration},
                   {"layer", row.layer},
                   {"global", row.global},
                   {"windows", row.windows},
                   {"pairs", row.pairs},
                   {"input", relativeErrorJson(row.input)},
                   {"start", relativeErrorJson(row.start)},
                   {"window", relativeErrorJson(row.window)},
                   {"hierarchy", relativeErrorJson(row.hierarchy)},
                   {"final", relativeErrorJson(row.final)}});
  }
  return out;
}

}  // namespace hba::pipeline
