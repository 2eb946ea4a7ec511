#pragma once
// Seeding rules that keep the simulator deterministic whatever the thread
// count: every frame (and every independent stream of a frame) draws from its
// own generator, seeded by hashing (seed, stream, index). No generator is ever
// shared between threads.
#include <cstdint>
#include <random>

namespace hba::sim {

// Independent random streams of one simulation.
enum class Stream : std::uint64_t { World = 1, Terrain, Sensor, Drift, Trajectory, Jitter, Session };

// SplitMix64 finalizer: a strong 64-bit mix of its input.
constexpr std::uint64_t mix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

inline std::mt19937_64 makeRng(std::uint64_t seed, Stream stream, std::uint64_t index = 0) {
  return std::mt19937_64(mix64(mix64(seed ^ mix64(static_cast<std::uint64_t>(stream))) + index));
}

}  // namespace hba::sim
