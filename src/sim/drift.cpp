#include "hba/sim/drift.hpp"

#include <cmath>

#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "sim/random.hpp"

namespace hba::sim {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// Draws in a fixed order (the order of function arguments is unspecified).
Vec3 gaussianVector(std::mt19937_64& rng) {
  std::normal_distribution<double> gaussian(0.0, 1.0);
  const double x = gaussian(rng);
  const double y = gaussian(rng);
  return Vec3(x, y, gaussian(rng));
}

std::vector<Pose> accumulateDrift(const std::vector<Pose>& truth, const DriftConfig& c,
                                  std::mt19937_64& rng) {
  std::normal_distribution<double> gaussian(0.0, 1.0);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  // Directions of the biases, each a random walk in angle over distance.
  double translation_angle = angle(rng);           // in the body x-y plane
  double yaw_phase = rng() % 2 == 0 ? 0.0 : M_PI;  // yaw bias = rate * cos(phase)
  double tilt_angle = angle(rng);                  // roll/pitch bias direction
  const double vertical_sign = rng() % 2 == 0 ? 1.0 : -1.0;
  const double rotation_rate = c.rotation_deg_per_m * kDegToRad;

  std::vector<Pose> drifted{truth.front()};
  drifted.reserve(truth.size());
  for (std::size_t k = 1; k < truth.size(); ++k) {
    const Pose motion = relative(truth[k - 1], truth[k]);
    const double d = motion.t.norm();
    const double wander = std::sqrt(d / c.wander_length);
    translation_angle += wander * gaussian(rng);
    yaw_phase += wander * gaussian(rng);
    tilt_angle += wander * gaussian(rng);

    const Vec3 translation_error =
        d * c.translation * Vec3(std::cos(translation_angle), std::sin(translation_angle), 0.0);
    const Vec3 rotation_error =
        d * rotation_rate * Vec3(0.1 * std::cos(tilt_angle), 0.1 * std::sin(tilt_angle), std::cos(yaw_phase));
    const Pose noisy_motion(motion.q * Quat(so3Exp(rotation_error)), motion.t + translation_error);
    Pose next = drifted.back() * noisy_motion;
    next.q.normalize();
    next.t.z() += vertical_sign * c.vertical * d;
    drifted.push_back(next);
  }
  return drifted;
}

std::vector<Pose> perturbIndependently(const std::vector<Pose>& truth, const DriftConfig& c,
                                       std::mt19937_64& rng) {
  std::vector<Pose> noisy{truth.front()};
  for (std::size_t k = 1; k < truth.size(); ++k) {
    const Vec3 dt = c.closed_translation_sigma * gaussianVector(rng);
    const Vec3 dr = c.closed_rotation_sigma_deg * kDegToRad * gaussianVector(rng);
    noisy.emplace_back((truth[k].q * Quat(so3Exp(dr))).normalized(), truth[k].t + dt);
  }
  return noisy;
}

}  // namespace

void validate(const DriftConfig& c) {
  const bool ok = c.translation >= 0.0 && c.rotation_deg_per_m >= 0.0 && c.vertical >= 0.0 &&
                  c.jitter_translation >= 0.0 && c.jitter_rotation_deg >= 0.0 && c.wander_length > 0.0 &&
                  c.closed_translation_sigma >= 0.0 && c.closed_rotation_sigma_deg >= 0.0;
  if (!ok) throw Error("simulate: drift rates and noise levels must be non-negative");
  if (c.translation > 1.0 || c.rotation_deg_per_m > 10.0 || c.vertical > 1.0) {
    throw Error(
        "simulate: drift rates are implausibly large (translation and vertical are "
        "fractions of the distance, e.g. 0.01 for 1 %)");
  }
  if (c.jitter_translation > 1.0 || c.jitter_rotation_deg > 10.0) {
    throw Error("simulate: jitter is implausibly large (at most 1 m and 10 deg per frame)");
  }
}

std::vector<Pose> applyDrift(const std::vector<Pose>& truth, const DriftConfig& config, std::uint64_t seed) {
  validate(config);
  if (truth.empty()) return {};
  auto rng = makeRng(seed, Stream::Drift);
  std::vector<Pose> poses =
      config.loop_closed ? perturbIndependently(truth, config, rng) : accumulateDrift(truth, config, rng);
  if (config.jitter_translation > 0.0 || config.jitter_rotation_deg > 0.0) {
    // Its own stream: runs without jitter keep their exact bytes.
    auto jitter = makeRng(seed, Stream::Jitter);
    for (std::size_t k = 1; k < poses.size(); ++k) {  // the first pose fixes the frame
      const Vec3 dt = config.jitter_translation * gaussianVector(jitter);
      const Vec3 dr = config.jitter_rotation_deg * kDegToRad * gaussianVector(jitter);
      poses[k] = Pose((poses[k].q * Quat(so3Exp(dr))).normalized(), Vec3(poses[k].t + dt));
    }
  }
  return poses;
}

}  // namespace hba::sim
