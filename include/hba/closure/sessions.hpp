#pragma once
// Several sessions optimized as one sequence: their frames one after the
// other, each session's first frame a "start" that no odometry step links to
// the frame before it.
#include <cstddef>
#include <vector>

namespace hba::closure {

// The session of each of `frames` frames, given the frames that start a
// session (in any order; 0 implied). Throws hba::Error for a start beyond
// the frames.
std::vector<std::size_t> sessionOfFrames(std::size_t frames, std::vector<std::size_t> starts);

}  // namespace hba::closure
