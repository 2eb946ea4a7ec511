#include "hba/core/memory_budget.hpp"

#include <unistd.h>

#include <fstream>
#include <utility>

#include "core/available_memory.hpp"
#include "core/release_memory.hpp"

namespace hba {

std::size_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t size = 0, resident = 0;
  if (!(statm >> size >> resident)) return 0;
  return resident * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
}

MemoryBudget::MemoryBudget(std::size_t bytes, std::string source)
    : bytes_(bytes), start_(residentBytes()), source_(std::move(source)) {}

MemoryBudget MemoryBudget::ofAvailableMemory() {
  // Growth is measured from what the process really holds, not from pages
  // it freed and the allocator kept (which its next allocations reuse).
  releaseFreedMemory();
  return ofAvailableMemoryAsHeld();
}

MemoryBudget MemoryBudget::ofAvailableMemoryAsHeld() {
  const std::optional<AvailableMemory> available = availableMemory();
  if (!available) return {};
  return MemoryBudget(available->bytes / 10 * 9, available->source);
}

bool MemoryBudget::exceeded(std::size_t still_to_come) const {
  return bytes_ && residentBytes() + still_to_come > start_ + *bytes_;
}

MemoryExceeded MemoryBudget::exceededBy(const std::string& what) const {
  const std::size_t now = residentBytes();
  const std::size_t grown = now > start_ ? now - start_ : 0;
  return MemoryExceeded(
      what + " outgrew the memory available: it took " + humanBytes(static_cast<double>(grown)) + " of the " +
      humanBytes(static_cast<double>(bytes_.value_or(0))) + " there were (" + source_ + ", less a tenth)");
}

}  // namespace hba
