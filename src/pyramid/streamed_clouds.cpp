#include "streamed_clouds.hpp"

#include <tbb/parallel_for.h>

#include <iterator>

namespace hba::pyramid {

StreamedClouds::StreamedClouds(const io::ScanSource& source)
    : source_(source), counted_(source.size(), false), frame_points_(source.size(), 0) {}

void StreamedClouds::keepRange(std::size_t first, std::size_t end) {
  for (auto it = held_.begin(); it != held_.end();) {
    it = it->first < first ? held_.erase(it) : std::next(it);
  }
  std::vector<std::size_t> missing;
  for (std::size_t i = first; i < end; ++i) {
    if (!held_.count(i)) missing.push_back(i);
  }
  std::vector<PointCloud> loaded(missing.size());
  tbb::parallel_for(std::size_t{0}, missing.size(),
                    [&](std::size_t k) { loaded[k] = source_.load(missing[k]); });
  for (std::size_t k = 0; k < missing.size(); ++k) {
    const std::size_t i = missing[k];
    if (i < counted_.size() && !counted_[i]) {
      counted_[i] = true;
      frame_points_[i] = loaded[k].size();
      points_loaded_ += loaded[k].size();
    }
    held_[i] = std::move(loaded[k]);
  }
}

std::vector<std::pair<std::size_t, std::size_t>> StreamedClouds::framesLoaded() const {
  std::vector<std::pair<std::size_t, std::size_t>> frames;
  for (std::size_t i = 0; i < counted_.size(); ++i) {
    if (counted_[i]) frames.emplace_back(i, frame_points_[i]);
  }
  return frames;
}

std::vector<const PointCloud*> StreamedClouds::cloudsOf(const Window& window) const {
  std::vector<const PointCloud*> clouds(window.count);
  for (std::size_t k = 0; k < window.count; ++k) clouds[k] = get(window.first + k);
  return clouds;
}

}  // namespace hba::pyramid
