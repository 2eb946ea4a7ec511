#pragma once
// How much more memory this process can take before the kernel kills it:
// the system's MemAvailable, or less where a cgroup (a container, a
// systemd slice, a batch job) limits it. A run that cannot fit is refused
// up front with this figure, instead of being killed without a word.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

namespace hba {

struct AvailableMemory {
  std::size_t bytes = 0;
  std::string source;  // where the figure comes from, for messages
};

// The smaller of /proc/meminfo's MemAvailable and the room left under this
// process's cgroup limit (v2 memory.max, v1 memory.limit_in_bytes; the
// page cache counted as free, the kernel drops it first). The environment
// variable HBA_MEMORY_AVAILABLE_BYTES, when set, is taken instead (tests
// fake a small machine with it). nullopt when nothing tells (not Linux).
// `root` is where /proc and /sys are looked up (tests give a fake tree).
// Throws hba::Error when HBA_MEMORY_AVAILABLE_BYTES is not a byte count.
std::optional<AvailableMemory> availableMemory(const std::filesystem::path& root = "/");

// "1.2 GiB", "350 MiB": a byte count for a message.
std::string humanBytes(double bytes);

}  // namespace hba
