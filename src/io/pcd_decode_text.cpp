// PCD "DATA ascii": one point per line, the values of every field in order.
#include <algorithm>
#include <string>

#include "hba/core/error.hpp"
#include "pcd_format.hpp"
#include "point_columns.hpp"
#include "text_parsing.hpp"

namespace hba::io::detail {
namespace fs = std::filesystem;

namespace {

// float32 text is parsed as float directly: through double it could round
// twice. Other types are rounded to float once, as the binary reader does;
// float64 keeps its precision (addFinitePoint).
std::optional<double> parseValue(std::string_view word, ScalarType type) {
  if (type == ScalarType::Float32) {
    const std::optional<float> value = parseFloat(word);
    return value ? std::optional<double>(*value) : std::nullopt;
  }
  const std::optional<double> value = parseDouble(word);
  if (!value || type == ScalarType::Float64) return value;
  return static_cast<double>(static_cast<float>(*value));
}

// The word positions of the values hba keeps, in the order x y z intensity
// time; a field the file lacks is not wanted.
struct WantedWords {
  std::size_t index[5];
  ScalarType type[5];
  bool wanted[5];
};

WantedWords wantedWords(const PcdHeader& header, const PcdLayout& layout) {
  WantedWords wanted{};
  const std::optional<std::size_t> fields[5] = {layout.x, layout.y, layout.z, layout.intensity, layout.time};
  for (std::size_t k = 0; k < 5; ++k) {
    wanted.wanted[k] = fields[k].has_value();
    if (!fields[k]) continue;
    wanted.index[k] = layout.first_words[*fields[k]];
    // A time keeps every digit: stamps in ns need more than a float holds.
    wanted.type[k] = k == 4 ? ScalarType::Float64 : pcdScalarType(header.fields[*fields[k]]);
  }
  return wanted;
}

}  // namespace

template <typename Cloud>
Cloud decodePcdAscii(std::string_view body, const PcdHeader& header, const PcdLayout& layout,
                     const fs::path& path) {
  const WantedWords wanted = wantedWords(header, layout);
  Cloud cloud;
  // Every value takes at least two characters, which bounds a lying POINTS.
  const std::uint64_t most_possible = body.size() / (2 * layout.words_per_point) + 1;
  cloud.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(header.points, most_possible)),
                layout.intensity.has_value());

  const bool wide = wanted.type[0] == ScalarType::Float64 || wanted.type[1] == ScalarType::Float64 ||
                    wanted.type[2] == ScalarType::Float64;
  PointCollector collector(cloud, wide, layout.intensity.has_value(), layout.time.has_value());
  std::uint64_t points_read = 0;
  std::uint64_t line_number = 0;
  std::string_view rest = body;
  while (!rest.empty()) {
    std::string_view words = nextLine(rest);
    ++line_number;
    const std::string where = "data line " + std::to_string(line_number);
    std::string_view word = nextWord(words);
    if (word.empty()) continue;
    if (points_read == header.points) {
      failAt(path,
             where + ": more points than the " + std::to_string(header.points) + " the header declares");
    }
    double values[4] = {0, 0, 0, 0};
    double time = 0.0;
    std::size_t word_index = 0;
    for (; !word.empty(); word = nextWord(words), ++word_index) {
      for (std::size_t k = 0; k < 5; ++k) {
        if (!wanted.wanted[k] || wanted.index[k] != word_index) continue;
        const std::optional<double> value = parseValue(word, wanted.type[k]);
        if (!value) failAt(path, where + ": " + quoteToken(word) + " is not a number");
        (k == 4 ? time : values[k]) = *value;
      }
    }
    if (word_index != layout.words_per_point) {
      failAt(path, where + ": " + std::to_string(word_index) + " values, but the fields need " +
                       std::to_string(layout.words_per_point));
    }
    ++points_read;
    collector.add(values, time);
  }
  collector.finish();
  if (points_read != header.points) {
    failAt(path, "truncated: the header declares " + std::to_string(header.points) +
                     " points but the data holds " + std::to_string(points_read));
  }
  return cloud;
}

template PointCloud decodePcdAscii(std::string_view, const PcdHeader&, const PcdLayout&, const fs::path&);
template WideCloud decodePcdAscii(std::string_view, const PcdHeader&, const PcdLayout&, const fs::path&);

}  // namespace hba::io::detail
