#pragma once
// A stage whose memory grows with what it reads and cannot be known before
// (a merged map: how much the scans overlap) checks itself as it grows, and
// stops with a clear message while the machine still has room, instead of
// being killed by the kernel without a word.
#include <cstddef>
#include <optional>
#include <string>

#include "hba/core/error.hpp"

namespace hba {

// What a stage that outgrew its budget throws: the caller may skip the
// stage (a picture) rather than fail the run.
class MemoryExceeded : public Error {
 public:
  using Error::Error;
};

class MemoryBudget {
 public:
  MemoryBudget() = default;  // no limit
  // The process may grow by `bytes` beyond its resident memory now;
  // `source` says where the figure comes from, for the message.
  MemoryBudget(std::size_t bytes, std::string source);
  // Nine tenths of the memory available now (availableMemory(); the rest
  // for the system's own growth), from what the process holds once it has
  // handed back the pages it freed (releaseFreedMemory); no limit where
  // that is unknown.
  static MemoryBudget ofAvailableMemory();
  // The same without handing freed pages back first: for a short stage
  // after a long one, which reuses the pages the long one freed (handed
  // back, each costs a page fault when touched again: a tenth of a second
  // for the report page of a one-second run).
  static MemoryBudget ofAvailableMemoryAsHeld();

  bool limited() const { return bytes_.has_value(); }
  // Whether the process has grown beyond the budget, or would with
  // `still_to_come` bytes more (reads /proc/self/statm: once per scan or
  // so, not per point).
  bool exceeded(std::size_t still_to_come = 0) const;
  // The error saying that `what` outgrew the budget, and by how much.
  MemoryExceeded exceededBy(const std::string& what) const;

 private:
  std::optional<std::size_t> bytes_;
  std::size_t start_ = 0;  // resident bytes when the budget was made
  std::string source_;
};

// This process's resident memory (bytes); 0 where unknown.
std::size_t residentBytes();

}  // namespace hba
