#pragma once
// A layer's windows spread over the members of a group (processes under
// mpirun): each optimizes a contiguous range of them, then every member
// gets every window's summary and keyframe, so that all go on from the same
// layer. Each window's result does not depend on which member found it, so
// the poses are those of one process.
#include <cstddef>
#include <vector>

#include "hba/dist/group.hpp"
#include "keyframe_store.hpp"
#include "streamed_clouds.hpp"
#include "window_summary.hpp"

namespace hba::pyramid {

struct WindowRange {
  std::size_t first = 0;
  std::size_t end = 0;  // one past the last
};

// Member `rank` of `size`'s windows: consecutive ranges that split the
// layer's work (one value per window, >= 0) as evenly as whole windows allow.
WindowRange windowsOfMember(const std::vector<double>& work, int rank, int size);

struct Shared {
  std::size_t cloud_points = 0;  // of the frames any member loaded, each frame once
  std::size_t bytes = 0;         // every member's message, summed
  std::size_t largest = 0;       // the largest member's message
};

// Sends `mine` (the summaries, and the keyframes stored in `next` when the
// layer makes them) to every member and takes theirs into `summaries` and
// `next`. A collective: every member calls it.
Shared shareWindows(const dist::Group& group, const WindowRange& mine, std::vector<WindowSummary>& summaries,
                    const KeyframeStore* next, const StreamedClouds& streamed);

}  // namespace hba::pyramid
