// Pose graph solve and window information at pyramid-like sizes.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "hba/core/lie.hpp"
#include "hba/graph/pose_graph.hpp"
#include "hba/graph/window_factors.hpp"

namespace {

using hba::Mat6;
using hba::Pose;
using hba::Vec3;
using hba::Vec6;

Vec6 randomTangent(std::mt19937& rng, double translation, double rotation) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Vec6 xi;
  for (int k = 0; k < 3; ++k) xi[k] = translation * normal(rng);
  for (int k = 3; k < 6; ++k) xi[k] = rotation * normal(rng);
  return xi;
}

// A drive around a loop with layered factors like a 3-layer pyramid with
// w = 10, s = 5: adjacent pairs at spacing 1, 5 and 25 frames, plus a closure.
// Start `Near`: every pose independently off by ~5 cm / 0.3 deg (what the
// pyramid's direct assignment hands over). Start `DeadReckoning`: chained
// noisy odometry, whose drift the closure must undo in one solve.
enum Start { Near = 0, DeadReckoning = 1 };
struct Problem {
  std::vector<Pose> initial;
  std::vector<hba::graph::RelativePoseFactor> factors;
};

Problem makeProblem(int n, Start start) {
  std::mt19937 rng(42);
  std::vector<Pose> truth;
  const double radius = n * 0.5 / (2 * M_PI);  // 0.5 m between frames
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * M_PI * i / n;
    truth.emplace_back(hba::so3Exp(Vec3(0, 0, angle + M_PI / 2)),
                       Vec3(radius * std::cos(angle), radius * std::sin(angle), 0));
  }
  Problem p;
  Mat6 information = Mat6::Identity();
  information.diagonal() << 1e4, 1e4, 1e4, 1e6, 1e6, 1e6;
  for (const int spacing : {1, 5, 25}) {
    for (int i = 0; i + spacing < n; i += spacing) {
      hba::graph::RelativePoseFactor f;
      f.from = static_cast<std::size_t>(i);
      f.to = static_cast<std::size_t>(i + spacing);
      f.measurement =
          hba::relative(truth[f.from], truth[f.to]) * hba::se3Exp(randomTangent(rng, 0.01, 0.001));
      f.information = information;
      p.factors.push_back(f);
    }
  }
  hba::graph::RelativePoseFactor closure;
  closure.from = static_cast<std::size_t>(n - 1);
  closure.to = 0;
  closure.measurement = hba::relative(truth.back(), truth.front());
  closure.information = information;
  p.factors.push_back(closure);
  p.initial = {truth.front()};
  for (int i = 1; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    p.initial.push_back(start == Near ? truth[k] * hba::se3Exp(randomTangent(rng, 0.05, 0.005))
                                      : p.initial.back() * p.factors[k - 1].measurement);
  }
  return p;
}

void BM_OptimizePoseGraph(benchmark::State& state) {
  const Problem p = makeProblem(static_cast<int>(state.range(0)), static_cast<Start>(state.range(2)));
  hba::graph::PoseGraphSettings settings;
  settings.threads = static_cast<int>(state.range(1));
  int iterations = 0;
  bool converged = false;
  for (auto _ : state) {
    const auto result = hba::graph::optimizePoseGraph(p.initial, p.factors, settings);
    iterations = result.iterations;
    converged = result.converged;
    // A copy: Google Benchmark 1.8 deprecates DoNotOptimize of a small const value.
    double final_cost = result.final_cost;
    benchmark::DoNotOptimize(final_cost);
  }
  state.counters["factors"] = static_cast<double>(p.factors.size());
  state.counters["lm_iterations"] = iterations;
  state.counters["converged"] = converged ? 1 : 0;
}
BENCHMARK(BM_OptimizePoseGraph)
    ->ArgNames({"nodes", "threads", "dead_reckoning"})
    ->Args({1000, 1, Near})
    ->Args({10000, 1, Near})
    ->Args({10000, 2, Near})
    ->Args({100000, 1, Near})
    ->Args({1000, 1, DeadReckoning})
    ->Args({10000, 1, DeadReckoning})
    ->Unit(benchmark::kMillisecond);

// One window's factors: K frames, a dense 6K x 6K Hessian.
void BM_WindowFactors(benchmark::State& state) {
  const auto count = static_cast<std::size_t>(state.range(0));
  const auto pairs = static_cast<hba::graph::FactorPairs>(state.range(1));
  std::mt19937 rng(7);
  std::vector<Pose> poses;
  std::vector<std::size_t> nodes;
  for (std::size_t k = 0; k < count; ++k) {
    poses.push_back(hba::se3Exp(randomTangent(rng, 3.0, 0.3)));
    nodes.push_back(k);
  }
  const auto n = static_cast<Eigen::Index>(6 * count);
  const Eigen::MatrixXd A = Eigen::MatrixXd::Random(2 * n, n);
  const Eigen::MatrixXd hessian = A.transpose() * A;
  for (auto _ : state) {
    benchmark::DoNotOptimize(hba::graph::windowFactors(hessian, poses, nodes, pairs));
  }
}
BENCHMARK(BM_WindowFactors)
    ->Args({10, static_cast<int>(hba::graph::FactorPairs::Adjacent)})
    ->Args({10, static_cast<int>(hba::graph::FactorPairs::AllPairs)})
    ->Args({20, static_cast<int>(hba::graph::FactorPairs::Adjacent)})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
