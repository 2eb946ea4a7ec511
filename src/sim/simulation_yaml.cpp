// sim.yaml: a record of every parameter of a simulated sequence, so that it
// can be reproduced and its ground truth understood without the command line.
#include <yaml-cpp/yaml.h>

#include "hba/core/atomic_file.hpp"
#include "hba/sim/simulation.hpp"
#include "simulation_yaml.hpp"

namespace hba::sim {
namespace {

void emitTrajectory(YAML::Emitter& out, const TrajectoryConfig& t, const std::vector<Pose>& truth) {
  out << YAML::Key << "trajectory" << YAML::Value << YAML::BeginMap;
  if (t.file.empty()) {
    out << YAML::Key << "shape" << YAML::Value << hba::toString(t.shape);
    out << YAML::Key << "speed_mps" << YAML::Value << t.speed;
  } else {
    out << YAML::Key << "file" << YAML::Value << t.file.string();
  }
  out << YAML::Key << "frames" << YAML::Value << truth.size();
  out << YAML::Key << "frame_rate_hz" << YAML::Value << t.frame_rate_hz;
  out << YAML::Key << "sensor_height_m" << YAML::Value << t.sensor_height;
  out << YAML::Key << "length_m" << YAML::Value << pathLength(truth);
  out << YAML::EndMap;
}

void emitSensor(YAML::Emitter& out, const SensorConfig& c) {
  out << YAML::Key << "sensor" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "model" << YAML::Value << hba::toString(c.model);
  if (c.model == SensorModel::Livox) {
    out << YAML::Key << "points_per_frame" << YAML::Value << c.points_per_frame;
    out << YAML::Key << "field_of_view_deg" << YAML::Value << c.field_of_view_deg;
  } else {
    out << YAML::Key << "channels" << YAML::Value << c.channels;
    out << YAML::Key << "min_elevation_deg" << YAML::Value << c.min_elevation_deg;
    out << YAML::Key << "max_elevation_deg" << YAML::Value << c.max_elevation_deg;
    out << YAML::Key << "columns" << YAML::Value << c.columns;
  }
  out << YAML::Key << "min_range_m" << YAML::Value << c.min_range;
  out << YAML::Key << "max_range_m" << YAML::Value << c.max_range;
  out << YAML::Key << "range_noise_m" << YAML::Value << c.range_noise;
  out << YAML::Key << "dropout" << YAML::Value << c.dropout;
  out << YAML::Key << "motion_distortion" << YAML::Value << false;
  out << YAML::EndMap;
}

void emitWorld(YAML::Emitter& out, const SimulationConfig& config, const World& world) {
  const WorldConfig& w = config.world;
  out << YAML::Key << "world" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "scene" << YAML::Value << hba::toString(config.scene);
  out << YAML::Key << "max_slope" << YAML::Value << w.max_slope;
  out << YAML::Key << "ground_cell_m" << YAML::Value << w.ground_cell;
  out << YAML::Key << "margin_m" << YAML::Value << w.margin;
  out << YAML::Key << "road_half_width_m" << YAML::Value << w.road_half_width;
  out << YAML::Key << "corridor_m" << YAML::Value << w.corridor;
  out << YAML::Key << "populated_distance_m" << YAML::Value << w.populated_distance;
  out << YAML::Key << "density_per_hectare" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "buildings" << YAML::Value << w.buildings;
  out << YAML::Key << "walls" << YAML::Value << w.walls;
  out << YAML::Key << "poles" << YAML::Value << w.poles;
  out << YAML::Key << "trees" << YAML::Value << w.trees;
  out << YAML::Key << "bushes" << YAML::Value << w.bushes;
  out << YAML::EndMap;
  out << YAML::Key << "triangles" << YAML::Value << world.triangles().size();
  out << YAML::Key << "spheres" << YAML::Value << world.spheres().size();
  out << YAML::EndMap;
}

void emitDrift(YAML::Emitter& out, const DriftConfig& d) {
  out << YAML::Key << "initial_poses" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "model" << YAML::Value << (d.loop_closed ? "loop_closed" : "drift");
  if (d.loop_closed) {
    out << YAML::Key << "translation_sigma_m" << YAML::Value << d.closed_translation_sigma;
    out << YAML::Key << "rotation_sigma_deg" << YAML::Value << d.closed_rotation_sigma_deg;
  } else {
    out << YAML::Key << "translation_per_m" << YAML::Value << d.translation;
    out << YAML::Key << "rotation_deg_per_m" << YAML::Value << d.rotation_deg_per_m;
    out << YAML::Key << "vertical_per_m" << YAML::Value << d.vertical;
    out << YAML::Key << "wander_length_m" << YAML::Value << d.wander_length;
  }
  out << YAML::Key << "jitter_translation_m" << YAML::Value << d.jitter_translation;
  out << YAML::Key << "jitter_rotation_deg" << YAML::Value << d.jitter_rotation_deg;
  out << YAML::EndMap;
}

}  // namespace

void emitYamlHeader(YAML::Emitter& out, std::uint64_t seed) {
  out << YAML::Key << "generator" << YAML::Value << "hba simulate";
  out << YAML::Key << "version" << YAML::Value << HBA_SIM_VERSION;
  out << YAML::Key << "seed" << YAML::Value << seed;
}

void emitDatasetFiles(YAML::Emitter& out) {
  out << YAML::Key << "scans" << YAML::Value << "pcd/ (binary PCD x y z intensity, sensor frame)";
  out << YAML::Key << "initial_poses" << YAML::Value << "pose.json (hba: tx ty tz qw qx qy qz)";
  out << YAML::Key << "ground_truth" << YAML::Value << "gt.txt (tum: t tx ty tz qx qy qz qw)";
  out << YAML::Key << "times" << YAML::Value << "times.txt (one stamp a line, s)";
}

void emitYamlBody(YAML::Emitter& out, const SimulationConfig& config, const std::vector<Pose>& truth,
                  const World& world) {
  out << YAML::Key << "sensor_frame" << YAML::Value << "x forward, y left, z up";
  emitTrajectory(out, config.trajectory, truth);
  emitSensor(out, config.sensor);
  out << YAML::Key << "downsample_voxel_m" << YAML::Value << config.downsample_voxel;
  out << YAML::Key << "raw_sweeps" << YAML::Value << config.sweep;
  emitWorld(out, config, world);
  emitDrift(out, config.drift);
}

void writeYamlFile(const std::filesystem::path& path, const YAML::Emitter& out) {
  const auto write = [&](std::ostream& stream) { stream << out.c_str() << '\n'; };
  writeFileAtomically(path, write, false);
}

void writeSimulationYaml(const Simulation& s, const std::filesystem::path& path) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  emitYamlHeader(out, s.config.seed);
  out << YAML::Key << "files" << YAML::Value << YAML::BeginMap;
  emitDatasetFiles(out);
  out << YAML::EndMap;
  emitYamlBody(out, s.config, s.truth.poses, s.world);
  out << YAML::EndMap;
  writeYamlFile(path, out);
}

}  // namespace hba::sim
