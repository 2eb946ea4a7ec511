#include "core/available_memory.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "hba/core/error.hpp"

namespace hba {
namespace fs = std::filesystem;

namespace {

// A cgroup limit at or above this is "no limit" (v1 writes 2^63 rounded to a page).
constexpr std::size_t kNoLimit = std::size_t{1} << 60;

std::optional<std::size_t> readNumber(const fs::path& file) {
  std::ifstream in(file);
  std::string text;
  if (!(in >> text) || text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;  // absent, or "max"
  }
  return std::stoull(text);
}

// The value of `key` in a "key value" file (meminfo, memory.stat), times `unit`.
std::optional<std::size_t> readField(const fs::path& file, const std::string& key, std::size_t unit) {
  std::ifstream in(file);
  std::string name;
  std::size_t value = 0;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    if (fields >> name >> value && (name == key || name == key + ":")) return value * unit;
  }
  return std::nullopt;
}

// Room left under one cgroup's limit: the limit less what is used, the
// page cache not counted (the kernel reclaims it before killing).
std::optional<std::size_t> roomIn(const fs::path& dir, const char* limit_file, const char* usage_file,
                                  const char* cache_key) {
  const std::optional<std::size_t> limit = readNumber(dir / limit_file);
  if (!limit || *limit >= kNoLimit) return std::nullopt;
  const std::size_t usage = readNumber(dir / usage_file).value_or(0);
  const std::size_t cache = std::min(usage, readField(dir / "memory.stat", cache_key, 1).value_or(0));
  return *limit - std::min(*limit, usage - cache);
}

// This process's cgroup path in one hierarchy of /proc/self/cgroup: the
// unified one (v2, "0::/path") or v1's memory controller ("4:memory:/path").
std::optional<fs::path> cgroupPath(const fs::path& root, bool v2) {
  std::ifstream in(root / "proc/self/cgroup");
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find(':');
    const auto second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const bool match = v2 ? line.compare(0, first, "0") == 0 && controllers.empty()
                          : ("," + controllers + ",").find(",memory,") != std::string::npos;
    if (match) return fs::path(line.substr(second + 1)).relative_path();
  }
  return std::nullopt;
}

// The least room under this process's cgroup and its ancestors (a limit
// may sit on any of them); in a container, the hierarchy's root is its own.
std::optional<std::size_t> cgroupRoom(const fs::path& root) {
  std::optional<std::size_t> least;
  auto take = [&](std::optional<std::size_t> room) {
    if (room && (!least || *room < *least)) least = room;
  };
  for (const bool v2 : {true, false}) {
    const fs::path mount = root / (v2 ? "sys/fs/cgroup" : "sys/fs/cgroup/memory");
    const char* limit = v2 ? "memory.max" : "memory.limit_in_bytes";
    const char* usage = v2 ? "memory.current" : "memory.usage_in_bytes";
    const char* cache = v2 ? "file" : "total_cache";
    const fs::path own = cgroupPath(root, v2).value_or(fs::path());
    for (fs::path dir = own; !dir.empty(); dir = dir.parent_path())
      take(roomIn(mount / dir, limit, usage, cache));
    take(roomIn(mount, limit, usage, cache));
  }
  return least;
}

}  // namespace

std::optional<AvailableMemory> availableMemory(const fs::path& root) {
  if (const char* faked = std::getenv("HBA_MEMORY_AVAILABLE_BYTES")) {
    const std::string text = faked;
    if (text.empty() || text.size() > 19 || text.find_first_not_of("0123456789") != std::string::npos) {
      throw Error("HBA_MEMORY_AVAILABLE_BYTES: '" + text + "' is not a number of bytes");
    }
    return AvailableMemory{std::stoull(text), "HBA_MEMORY_AVAILABLE_BYTES"};
  }
  std::optional<AvailableMemory> available;
  if (const auto bytes = readField(root / "proc/meminfo", "MemAvailable", 1024)) {
    available = AvailableMemory{*bytes, "MemAvailable in /proc/meminfo"};
  }
  if (const auto room = cgroupRoom(root); room && (!available || *room < available->bytes)) {
    available = AvailableMemory{*room, "the room left under this process's cgroup memory limit"};
  }
  return available;
}

std::string humanBytes(double bytes) {
  constexpr double kMiB = 1024.0 * 1024.0;
  char text[32];
  if (bytes >= 1024.0 * kMiB) {
    std::snprintf(text, sizeof text, "%.1f GiB", bytes / (1024.0 * kMiB));
  } else {
    std::snprintf(text, sizeof text, "%.0f MiB", bytes / kMiB);
  }
  return text;
}

}  // namespace hba
