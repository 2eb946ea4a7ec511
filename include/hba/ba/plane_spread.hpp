#pragma once
// A refinement's plane problem spread over the members of a process group
// (docs/mpi.md): each member holds whole chunks of the planes, in order.
// Every sum over planes is taken in these chunks, added in chunk order, in
// one process as in many, so a group gets the poses of one process, bit
// for bit.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "hba/dist/group.hpp"

namespace hba::ba {

struct PlaneSpread {
  const dist::Group* group = nullptr;  // null: one process holds every plane
  // Chunks as ranges of all planes: [chunk_begin[c], chunk_begin[c + 1]),
  // all planes at the end; the member holds chunks [first_chunk, end_chunk).
  std::vector<std::size_t> chunk_begin;
  std::size_t first_chunk = 0;
  std::size_t end_chunk = 0;

  bool spread() const { return group != nullptr && group->size() > 1; }
  // The member's first plane among all, and all planes over the group.
  std::size_t firstPlane() const { return chunk_begin.empty() ? 0 : chunk_begin[first_chunk]; }
  std::size_t allPlanes() const { return chunk_begin.empty() ? 0 : chunk_begin.back(); }
};

// The chunks the sums over planes are taken in: ranges of about equal
// observation counts (`plane_begin[p]`: observations before plane p, and
// the total last) that hold whole planes. Each sums into its own partial
// result of `frames` frames' gradients and 6x6 blocks: enough for two
// cores to share (up to 64), few enough that the partials stay within
// 16 MB and a chunk holds at least 16 384 observations. Depends on the
// sizes only: the same chunks for any thread or process count.
std::vector<std::size_t> sumChunks(const std::vector<std::uint32_t>& plane_begin, std::size_t frames);

// The first chunk of each member, and the chunk count last: the chunk
// that starts at or after the member's first plane in `plane_start` (one
// per member, ascending, then all planes), so that planes move between
// members only near where their shares meet.
std::vector<std::size_t> memberChunkStarts(const std::vector<std::size_t>& chunk_begin,
                                           const std::vector<std::size_t>& plane_start);

// Every member's `mine`, in rank order (a collective).
std::vector<std::vector<double>> gatherPerMember(const dist::Group& group, const std::vector<double>& mine);

// Every member's `mine`, one after another in rank order (a collective).
std::vector<double> gatherInOrder(const dist::Group& group, const std::vector<double>& mine);

}  // namespace hba::ba
