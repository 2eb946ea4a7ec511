#pragma once
// The processes one run is spread over, and the one exchange the pyramid
// needs from them. The library links no transport: a single process is a
// group of one, and the hba tool brings MPI's (apps/hba/mpi_group.cpp), so
// the library, its Python module and find_package(hba) users need no MPI.
#include <cstdint>
#include <vector>

namespace hba::dist {

using Bytes = std::vector<std::uint8_t>;

class Group {
 public:
  virtual ~Group() = default;
  virtual int rank() const = 0;  // 0 .. size() - 1
  virtual int size() const = 0;
  bool root() const { return rank() == 0; }
  // Every member's `mine`, in rank order. Every member calls it, the same
  // number of times in the same order (a collective). Throws hba::Error.
  virtual std::vector<Bytes> allGather(const Bytes& mine) const = 0;
  // What every member sent this one: `to_each[r]` goes to member r, and
  // the result's [r] came from member r. A collective, like allGather.
  virtual std::vector<Bytes> allToAll(const std::vector<Bytes>& to_each) const = 0;
};

// This process alone: rank 0 of 1, and a gather hands back `mine`.
const Group& singleProcess();

// The first member's `mine`, in every member (the others' are not sent).
// A collective.
Bytes fromRoot(const Group& group, const Bytes& mine);

}  // namespace hba::dist
