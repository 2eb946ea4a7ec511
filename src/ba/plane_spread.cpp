#include "hba/ba/plane_spread.hpp"

#include <algorithm>

#include "dist/bytes.hpp"
#include "hba/core/types.hpp"

namespace hba::ba {

std::vector<std::size_t> sumChunks(const std::vector<std::uint32_t>& plane_begin, std::size_t frames) {
  const std::size_t planes = plane_begin.empty() ? 0 : plane_begin.size() - 1;
  const std::size_t observations = plane_begin.empty() ? 0 : plane_begin.back();
  const std::size_t partial_bytes = std::max<std::size_t>(frames * (sizeof(Vec6) + 2 * sizeof(Mat6)), 1);
  const std::size_t by_memory = (std::size_t{16} << 20) / partial_bytes;
  const std::size_t chunks =
      std::clamp<std::size_t>(std::min({std::size_t{64}, by_memory, observations / 16384}), 1, 64);
  std::vector<std::size_t> begin{0};
  for (std::size_t c = 1; c < chunks; ++c) {
    const std::size_t target = observations * c / chunks;
    // The first plane whose observations start at or after the target.
    const auto it = std::lower_bound(plane_begin.begin() + static_cast<long>(begin.back()),
                                     plane_begin.begin() + static_cast<long>(planes), target);
    begin.push_back(static_cast<std::size_t>(it - plane_begin.begin()));
  }
  begin.push_back(planes);
  return begin;
}

std::vector<std::size_t> memberChunkStarts(const std::vector<std::size_t>& chunk_begin,
                                           const std::vector<std::size_t>& plane_start) {
  const std::size_t chunks = chunk_begin.size() - 1;
  std::vector<std::size_t> starts;
  for (std::size_t m = 0; m + 1 < plane_start.size(); ++m) {
    const auto it = std::lower_bound(chunk_begin.begin(), chunk_begin.end() - 1, plane_start[m]);
    starts.push_back(m == 0 ? 0 : static_cast<std::size_t>(it - chunk_begin.begin()));
  }
  starts.push_back(chunks);
  return starts;
}

std::vector<std::vector<double>> gatherPerMember(const dist::Group& group, const std::vector<double>& mine) {
  if (group.size() == 1) return {mine};
  dist::ByteWriter writer;
  writer.putVector(mine);
  std::vector<std::vector<double>> all;
  for (const dist::Bytes& bytes : group.allGather(writer.take())) {
    dist::ByteReader reader(bytes);
    all.push_back(reader.getVector<double>());
  }
  return all;
}

std::vector<double> gatherInOrder(const dist::Group& group, const std::vector<double>& mine) {
  if (group.size() == 1) return mine;
  std::vector<double> all;
  for (const std::vector<double>& theirs : gatherPerMember(group, mine))
    all.insert(all.end(), theirs.begin(), theirs.end());
  return all;
}

}  // namespace hba::ba
