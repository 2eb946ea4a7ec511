// `hba simulate`: writes a synthetic LiDAR sequence with ground truth.
#include <spdlog/spdlog.h>

#include <cmath>
#include <memory>

#include "commands.hpp"
#include "core/input_file.hpp"
#include "core/stopwatch.hpp"
#include "enum_choice.hpp"
#include "hba/core/error.hpp"
#include "hba/sim/sessions.hpp"
#include "hba/sim/simulation.hpp"
#include "number_checks.hpp"
#include "output_dir.hpp"

namespace hba::cli {
namespace {

struct SimulateArgs {
  std::string output;
  std::size_t frames = 300;
  std::uint64_t seed = 1;
  std::string trajectory = "block";
  double speed = 5.0;
  std::string sensor = "vlp16";
  // Unset optionals keep the sensor preset's value.
  std::optional<double> noise, dropout, max_range;
  double drift_translation = sim::DriftConfig{}.translation;
  double drift_rotation = sim::DriftConfig{}.rotation_deg_per_m;
  double drift_z = sim::DriftConfig{}.vertical;
  double jitter_translation = 0.0;
  double jitter_rotation = 0.0;
  std::string scene = "mixed";
  bool loop_closed = false;
  bool poses_only = false;
  double downsample = 0.0;
  bool sweep = false;
  bool force = false;
  std::size_t progress_every = 100;
  // Several sessions in one world (sim/sessions.hpp); 1 writes one dataset as always.
  std::size_t sessions = 1;
  double session_shift = sim::SessionsConfig{}.shift;
  bool session_reverse = false;
  std::optional<std::size_t> session_frames;
};

sim::SimulationConfig configFrom(const SimulateArgs& args) {
  sim::SimulationConfig config;
  config.seed = args.seed;
  config.trajectory.frames = args.frames;
  config.trajectory.speed = args.speed;
  if (auto shape = findEnum<sim::PathShape>(args.trajectory)) {
    config.trajectory.shape = *shape;
  } else {
    config.trajectory.file = args.trajectory;
    // A FIFO or a link loop there is named as such (input_file.hpp).
    if (!regularFileIsPresent(config.trajectory.file)) {
      failAt(args.trajectory, "not block, figure8, street, nor a trajectory file");
    }
  }
  const auto model = findEnum<sim::SensorModel>(args.sensor);
  if (!model) throw Error("simulate: unknown sensor '" + args.sensor + "'");
  config.sensor = sim::sensorPreset(*model);
  if (args.noise) config.sensor.range_noise = *args.noise;
  if (args.dropout) config.sensor.dropout = *args.dropout;
  if (args.max_range) config.sensor.max_range = *args.max_range;
  config.drift.translation = args.drift_translation;
  config.drift.rotation_deg_per_m = args.drift_rotation;
  config.drift.vertical = args.drift_z;
  config.drift.loop_closed = args.loop_closed;
  config.drift.jitter_translation = args.jitter_translation;
  config.drift.jitter_rotation_deg = args.jitter_rotation;
  config.scene = *findEnum<sim::Scene>(args.scene);  // CLI11 checked the name
  config.world = sim::scenePreset(config.scene);
  config.downsample_voxel = args.downsample;
  config.sweep = args.sweep;
  return config;
}

sim::WriteOptions writeOptionsFrom(const SimulateArgs& args, Clock::time_point start) {
  sim::WriteOptions options;
  options.force = args.force;
  options.poses_only = args.poses_only;
  options.progress_every = args.progress_every;
  options.progress = [start](std::size_t done, std::size_t total) {
    const double seconds = secondsSince(start);
    spdlog::info("simulated {}/{} frames ({:.1f} s)", done, total, seconds);
  };
  return options;
}

sim::SessionsConfig sessionsFrom(const SimulateArgs& args) {
  sim::SessionsConfig sessions;
  sessions.count = args.sessions;
  sessions.shift = args.session_shift;
  sessions.reverse = args.session_reverse;
  // --frames sizes the path (the loop is the one a single run of --frames
  // drives); --session-frames, if given, is every session's own length.
  if (args.session_frames) sessions.frames.assign(args.sessions, *args.session_frames);
  sim::validate(sessions);
  return sessions;
}

void runSessions(const SimulateArgs& args, const sim::SessionsConfig& sessions) {
  const auto start = Clock::now();
  const sim::SessionSet set = sim::prepareSessions(configFrom(args), sessions);
  spdlog::info("world: {} triangles, {} spheres; {} sessions {} m apart along the path{}",
               set.world.triangles().size(), set.world.spheres().size(), set.list.size(), sessions.shift,
               sessions.reverse ? ", odd sessions reversed" : "");
  std::size_t frames = 0;
  for (const sim::Session& session : set.list) {
    const Pose& frame = session.common_from_session;
    const double heading = std::atan2(frame.R()(1, 0), frame.R()(0, 0)) * 180.0 / M_PI;
    spdlog::info("{}: {} frames, path {:.0f} m, starts {:.1f} m from session 0's start, heading {:+.1f} deg",
                 sim::sessionFolderName(session.index), session.truth.size(), pathLength(session.truth.poses),
                 frame.t.norm(), heading);
    frames += session.truth.size();
  }
  sim::writeSessions(set, args.output, writeOptionsFrom(args, start));
  const double seconds = secondsSince(start);
  spdlog::info("wrote {} ({} sessions, {} frames in {:.1f} s)", args.output, set.list.size(), frames,
               seconds);
}

void run(const SimulateArgs& args) {
  refuseReplacingInputs(args.output);  // e.g. the --trajectory file inside the output folder
  const sim::SessionsConfig sessions = sessionsFrom(args);
  if (sessions.count > 1) {
    runSessions(args, sessions);
    return;
  }
  const auto start = Clock::now();
  const sim::Simulation simulation = sim::prepareSimulation(configFrom(args));
  spdlog::info(
      "world: {} triangles, {} spheres; path {:.0f} m over {} frames; sensor {} "
      "({} rays/frame)",
      simulation.world.triangles().size(), simulation.world.spheres().size(),
      pathLength(simulation.truth.poses), simulation.truth.size(),
      hba::toString(simulation.config.sensor.model), simulation.config.sensor.raysPerFrame());
  sim::writeSimulation(simulation, args.output, writeOptionsFrom(args, start));
  const double seconds = secondsSince(start);
  spdlog::info("wrote {} ({} frames in {:.1f} s, {:.1f} frames/s)", args.output, simulation.truth.size(),
               seconds, simulation.truth.size() / seconds);
}

}  // namespace

void registerSimulateCommand(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  auto* command = app.add_subcommand(
      "simulate",
      "Write a synthetic LiDAR sequence (HBA layout: pcd/, pose.json with drifting initial "
      "poses, gt.txt ground truth in TUM format, times.txt, sim.yaml)");
  command->add_option("-o,--output", args->output, "Output folder (must be empty or absent)")->required();
  // The ranges are the simulator's own (sim::validate); 10^6 frames is a
  // day of driving.
  command->add_option("--frames", args->frames, "Number of frames (10 Hz)")
      ->check(countIn(1, 1e6))
      ->capture_default_str();
  command->add_option("--seed", args->seed, "Random seed (same seed, same files)")
      ->check(seedNumber())
      ->capture_default_str();
  command
      ->add_option("--trajectory", args->trajectory,
                   "block | figure8 | street | a KITTI/TUM/HBA trajectory file")
      ->check(nameOrFile(enumNames<sim::PathShape>(), "a trajectory file"))
      ->capture_default_str();
  command->add_option("--speed", args->speed, "Vehicle speed in m/s (procedural paths)")
      ->check(positiveUpTo(100.0, "m/s"))
      ->capture_default_str();
  command->add_option("--sensor", args->sensor, "vlp16 | hdl32 | hdl64 | os128 | livox")
      ->check(oneOf<sim::SensorModel>())
      ->capture_default_str();
  command->add_option("--noise", args->noise, "Range noise sigma in m (default: 0.02)")
      ->check(realIn(0, 1, "m"));
  command->add_option("--dropout", args->dropout, "Probability a return is lost (default: 0.02)")
      ->check(numberIn({0, 1, false, true, ""}));
  command->add_option("--max-range", args->max_range, "Maximum range in m (default: preset)")
      ->check(realIn(1, 1000, "m"));
  command
      ->add_option("--drift-translation", args->drift_translation,
                   "Odometry translation drift, fraction of distance (0.01 = 1 %)")
      ->check(realIn(0, 1))
      ->capture_default_str();
  command->add_option("--drift-rotation", args->drift_rotation, "Odometry heading drift in deg per metre")
      ->check(realIn(0, 10, "deg per m"))
      ->capture_default_str();
  command
      ->add_option("--jitter-translation", args->jitter_translation,
                   "Per-frame odometry noise on top of the drift, sigma per axis (m)")
      ->check(realIn(0, 1, "m"))
      ->default_val(args->jitter_translation);
  command
      ->add_option("--jitter-rotation", args->jitter_rotation,
                   "Per-frame odometry noise on top of the drift, sigma per axis (deg)")
      ->check(realIn(0, 10, "deg"))
      ->default_val(args->jitter_rotation);
  command
      ->add_option("--scene", args->scene,
                   "mixed | city (dense buildings) | open (sparse structure, vegetation) | indoor "
                   "(corridors and halls under a ceiling)")
      ->check(oneOf<sim::Scene>())
      ->default_val(args->scene);
  command->add_option("--drift-z", args->drift_z, "Odometry height drift, m per m")
      ->check(realIn(0, 1))
      ->capture_default_str();
  command->add_flag("--loop-closed", args->loop_closed,
                    "Initial poses = truth + small independent noise (no drift)");
  command->add_flag("--poses-only", args->poses_only,
                    "Write pose.json, gt.txt, times.txt and sim.yaml but no scans (same bytes as a full "
                    "run; pair with optimize --poses to reuse another run's scans)");
  command
      ->add_option("--downsample", args->downsample,
                   "Voxel size in m to thin each scan (0 = keep every return)")
      ->check(numberIn({1e-3, 100, false, false, "keep every return"}, NumberKind::Real, "m"))
      ->capture_default_str();
  command->add_flag("--sweep", args->sweep,
                    "Raw sweeps: each ray measured from the moving sensor, each point with its time "
                    "(PCD field 'time', s since the scan's stamp); hba deskews them");
  command->add_flag("--force", args->force, "Replace a non-empty output folder");
  command->add_option("--progress-every", args->progress_every, "Log progress every N frames")
      ->check(numberIn({1, 1e6, false, false, "at the end only"}, NumberKind::Count))
      ->capture_default_str();
  command
      ->add_option("--sessions", args->sessions,
                   "Sessions in one world, written to DIR/session-0 ... (1: one dataset in DIR)")
      ->check(countIn(1, 1000))
      ->capture_default_str();
  command
      ->add_option("--session-shift", args->session_shift,
                   "Metres along the path between one session's start and the next's")
      ->check(realIn(0, 1e5, "m"))
      ->capture_default_str();
  command->add_flag("--session-reverse", args->session_reverse,
                    "Sessions 1, 3, 5 ... drive the path in the other direction");
  command
      ->add_option("--session-frames", args->session_frames,
                   "Frames of every session (default: --frames, which also sizes the procedural loop)")
      ->check(countIn(1, 1e6));
  command->callback([args] { run(*args); });
}

}  // namespace hba::cli
