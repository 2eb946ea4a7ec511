#include "window_exchange.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>

#include "dist/bytes.hpp"
#include "factor_bytes.hpp"
#include "hba/core/error.hpp"

namespace hba::pyramid {
namespace {

void putSummary(dist::ByteWriter& out, const WindowSummary& s) {
  const WindowOutcome& o = s.outcome;
  out.put<std::uint64_t>(o.window.first);
  out.put<std::uint64_t>(o.window.count);
  dist::putPoses(out, o.optimized);
  putFactors(out, o.factors);
  putShapes(out, o.shapes);
  out.put<std::uint8_t>(o.has_planes);
  out.put<std::uint8_t>(o.kept_start);
  out.put(s.cost_before);
  out.put(s.cost_after);
  out.put(s.sq_rms_before);
  out.put(s.sq_rms_after);
  out.put<std::uint64_t>(s.planes);
  out.put<std::uint64_t>(s.plane_points);
  out.put<std::int32_t>(s.iterations);
  out.put<std::int32_t>(s.rounds);
  out.put<std::uint8_t>(s.trusted);
  out.put<std::uint8_t>(s.settled);
  out.put<std::uint8_t>(s.solved_again);
}

WindowSummary getSummary(dist::ByteReader& in) {
  WindowSummary s;
  WindowOutcome& o = s.outcome;
  o.window.first = in.get<std::uint64_t>();
  o.window.count = in.get<std::uint64_t>();
  o.optimized = dist::getPoses(in);
  o.factors = getFactors<graph::RelativePoseFactor>(in);
  o.shapes = getShapes(in);
  o.has_planes = in.get<std::uint8_t>() != 0;
  o.kept_start = in.get<std::uint8_t>() != 0;
  s.cost_before = in.get<double>();
  s.cost_after = in.get<double>();
  s.sq_rms_before = in.get<double>();
  s.sq_rms_after = in.get<double>();
  s.planes = in.get<std::uint64_t>();
  s.plane_points = in.get<std::uint64_t>();
  s.iterations = in.get<std::int32_t>();
  s.rounds = in.get<std::int32_t>();
  s.trusted = in.get<std::uint8_t>() != 0;
  s.settled = in.get<std::uint8_t>() != 0;
  s.solved_again = in.get<std::uint8_t>() != 0;
  return s;
}

void putCloud(dist::ByteWriter& out, const PointCloud& cloud) {
  out.put(cloud.origin);
  out.putVector(cloud.points);
  out.putVector(cloud.intensity);
}

PointCloud getCloud(dist::ByteReader& in) {
  PointCloud cloud;
  cloud.origin = in.get<Vec3>();
  cloud.points = in.getVector<Vec3f>();
  cloud.intensity = in.getVector<float>();
  return cloud;
}

}  // namespace

WindowRange windowsOfMember(const std::vector<double>& work, int rank, int size) {
  if (size < 1 || rank < 0 || rank >= size) {
    throw Error("windows of member " + std::to_string(rank) + " of " + std::to_string(size));
  }
  double total = 0.0;
  for (const double w : work) total += w;
  // Window k goes to the member whose even share of the total holds the
  // middle of its work (by count when there is no work): the members
  // never decrease along the windows, so each gets a consecutive range.
  std::vector<int> members(work.size());
  double before = 0.0;
  for (std::size_t k = 0; k < work.size(); ++k) {
    const double share = total > 0.0 ? (before + 0.5 * work[k]) / total
                                     : (static_cast<double>(k) + 0.5) / static_cast<double>(work.size());
    members[k] = std::min(size - 1, static_cast<int>(share * size));
    before += work[k];
  }
  const auto lo = std::lower_bound(members.begin(), members.end(), rank);
  const auto hi = std::upper_bound(members.begin(), members.end(), rank);
  return {static_cast<std::size_t>(lo - members.begin()), static_cast<std::size_t>(hi - members.begin())};
}

WindowRange framesOf(const std::vector<Window>& windows, const WindowRange& range) {
  if (range.first >= range.end) return {0, 0};
  WindowRange frames{windows[range.first].first, windows[range.first].first};
  for (std::size_t w = range.first; w < range.end; ++w) {
    frames.end = std::max(frames.end, windows[w].first + windows[w].count);
  }
  return frames;
}

std::vector<double> workOf(const std::vector<Window>& windows,
                           const std::function<double(std::size_t)>& frame_work) {
  std::vector<double> work;
  work.reserve(windows.size());
  for (const Window& window : windows) {
    double sum = 0.0;
    for (std::size_t k = 0; k < window.count; ++k) sum += frame_work(window.first + k);
    work.push_back(sum);
  }
  return work;
}

Shared shareWindows(const dist::Group& group, const WindowRange& mine, std::vector<WindowSummary>& summaries,
                    const io::CloudStore* next, const std::vector<Window>& next_windows,
                    const StreamedClouds& streamed) {
  // First every window's summary and keyframe size, to every member.
  dist::ByteWriter out;
  out.put<std::uint64_t>(mine.first);
  out.put<std::uint64_t>(mine.end);
  for (std::size_t w = mine.first; w < mine.end; ++w) {
    putSummary(out, summaries[w]);
    out.put<std::uint64_t>(next ? next->points(w) : 0);
  }
  const std::vector<std::pair<std::size_t, std::size_t>> loaded = streamed.framesLoaded();
  out.put<std::uint64_t>(loaded.size());
  for (const auto& [frame, points] : loaded) {
    out.put<std::uint64_t>(frame);
    out.put<std::uint64_t>(points);
  }
  const std::vector<dist::Bytes> all = group.allGather(out.take());

  Shared shared;
  shared.keyframe_points.assign(summaries.size(), 0);
  std::map<std::size_t, std::size_t> points_of;  // every member's frames, each once
  for (std::size_t member = 0; member < all.size(); ++member) {
    dist::ByteReader in(all[member]);
    const auto first = in.get<std::uint64_t>();
    const auto end = in.get<std::uint64_t>();
    if (first > end || end > summaries.size()) {
      throw Error("exchange between processes: member " + std::to_string(member) + " sent windows " +
                  std::to_string(first) + "-" + std::to_string(end) + " of " +
                  std::to_string(summaries.size()));
    }
    const bool own = static_cast<int>(member) == group.rank();
    for (std::size_t w = first; w < end; ++w) {
      WindowSummary summary = getSummary(in);
      shared.keyframe_points[w] = in.get<std::uint64_t>();
      if (!own) summaries[w] = std::move(summary);  // one's own are here already, as found
    }
    const auto frames = in.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < frames; ++k) {
      const auto frame = in.get<std::uint64_t>();
      points_of[frame] = in.get<std::uint64_t>();
    }
    if (!in.done())
      throw Error("exchange between processes: member " + std::to_string(member) + " sent more than read");
  }
  for (const auto& [frame, n] : points_of) shared.cloud_points += n;
  std::size_t my_bytes = all[static_cast<std::size_t>(group.rank())].size();

  if (next) {
    // Then each keyframe to the members whose next windows read it.
    if (next_windows.empty())
      throw Error("exchange between processes: the next layer's windows are not known");
    const std::vector<double> work = workOf(
        next_windows, [&](std::size_t i) { return static_cast<double>(shared.keyframe_points.at(i)); });
    std::vector<dist::Bytes> to_each(all.size());
    for (int member = 0; member < group.size(); ++member) {
      if (member == group.rank()) continue;
      const WindowRange reads = framesOf(next_windows, windowsOfMember(work, member, group.size()));
      dist::ByteWriter part;
      for (std::size_t w = std::max(mine.first, reads.first); w < std::min(mine.end, reads.end); ++w) {
        part.put<std::uint64_t>(w);
        putCloud(part, next->load(w));
      }
      to_each[static_cast<std::size_t>(member)] = part.take();
      my_bytes += to_each[static_cast<std::size_t>(member)].size();
    }
    const std::vector<dist::Bytes> from_each = group.allToAll(to_each);
    for (const dist::Bytes& bytes : from_each) {
      dist::ByteReader in(bytes);
      while (!in.done()) {
        const auto w = in.get<std::uint64_t>();
        if (w >= summaries.size())
          throw Error("exchange between processes: keyframe " + std::to_string(w) + " of " +
                      std::to_string(summaries.size()));
        next->store(w, getCloud(in));
      }
    }
    const WindowRange reads = framesOf(next_windows, windowsOfMember(work, group.rank(), group.size()));
    for (std::size_t w = reads.first; w < reads.end; ++w) {
      if (next->points(w) != shared.keyframe_points[w]) {
        throw Error("exchange between processes: keyframe " + std::to_string(w) + " did not come (" +
                    std::to_string(next->points(w)) + " of " + std::to_string(shared.keyframe_points[w]) +
                    " points)");
      }
    }
  }
  // What each member sent, summed and at most.
  dist::ByteWriter sent;
  sent.put<std::uint64_t>(my_bytes);
  for (const dist::Bytes& bytes : group.allGather(sent.take())) {
    dist::ByteReader in(bytes);
    const auto n = static_cast<std::size_t>(in.get<std::uint64_t>());
    shared.bytes += n;
    shared.largest = std::max(shared.largest, n);
  }
  return shared;
}

}  // namespace hba::pyramid
