#include "block_maps.hpp"

#include <cmath>
#include <string>

#include "block.hpp"

namespace hba::refine {

void addRegions(const FixedPlaneMap& map, const std::vector<double>& region_input,
                const std::vector<double>& region_final, std::size_t first, std::vector<RegionFigures>& out) {
  for (std::size_t k = 0; k < map.regions(); ++k) {
    out.push_back({first + map.regionStarts()[k], region_input[k], region_final[k]});
  }
}

void RmsSum::add(double rms, double n) {
  squares += rms * rms * n;
  points += n;
}

double RmsSum::rms() const { return points > 0.0 ? std::sqrt(squares / points) : 0.0; }

void BlockMaps::keep(const FixedPlaneMap& map) {
  if (!folder_) folder_ = std::make_unique<io::CloudStore>(0);
  files_.push_back(folder_->folder() / ("map-" + std::to_string(files_.size()) + ".bin"));
  map.save(files_.back());
  groups_.push_back(map.group());
}

FixedPlaneMap BlockMaps::load(std::size_t block) const {
  return FixedPlaneMap::load(files_.at(block), groups_.at(block));
}

double remeasure(const std::vector<Pose>& initial, const std::vector<Pose>& result,
                 const std::vector<FrameSpan>& spans, const BlockMaps& kept,
                 std::vector<RegionFigures>& regions) {
  RmsSum final_sum;
  regions.clear();
  for (std::size_t b = 0; b < spans.size(); ++b) {
    const FrameSpan& span = spans[b];
    const std::vector<Pose> input = inputOnto(initial, result, span.first, span.end);
    const std::vector<Pose> poses = slice(result, span.first, span.end);
    const FixedPlaneMap map = kept.load(b);
    const FixedPlaneMap::Figures at_final = map.figures(poses);
    final_sum.add(at_final.rms, map.points());
    addRegions(map, map.regionRms(input), at_final.region_rms, span.first, regions);
  }
  return final_sum.rms();
}

}  // namespace hba::refine
