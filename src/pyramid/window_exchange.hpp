#pragma once
// A layer's windows spread over the members of a group (processes under
// mpirun): each optimizes a contiguous range of them, then every member
// gets every window's summary and keyframe, so that all go on from the same
// layer. Each window's result does not depend on which member found it, so
// the poses are those of one process.
#include <cstddef>
#include <functional>
#include <vector>

#include "hba/dist/group.hpp"
#include "io/cloud_store.hpp"
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
  std::size_t cloud_points = 0;              // of the frames any member loaded, each frame once
  std::size_t bytes = 0;                     // every member's messages, summed
  std::size_t largest = 0;                   // the most one member sent
  std::vector<std::size_t> keyframe_points;  // of every window's keyframe, when the layer makes them
};

// Sends every member the summaries of `mine` and takes theirs into
// `summaries`; when the layer makes keyframes (`next`), sends each of its
// keyframes to the members whose windows of the next layer (`next_windows`,
// split as windowsOfMember splits them) read it, and stores those it gets.
// A collective: every member calls it. Throws hba::Error if a keyframe this
// member's next windows read did not come.
Shared shareWindows(const dist::Group& group, const WindowRange& mine, std::vector<WindowSummary>& summaries,
                    const io::CloudStore* next, const std::vector<Window>& next_windows,
                    const StreamedClouds& streamed);

// The frames [first, end) the windows of `range` read.
WindowRange framesOf(const std::vector<Window>& windows, const WindowRange& range);

// Each window's share of a layer's work: the sum of its frames' work.
std::vector<double> workOf(const std::vector<Window>& windows,
                           const std::function<double(std::size_t)>& frame_work);

}  // namespace hba::pyramid
