// Plain-text point clouds (.xyz, as CloudCompare and many survey tools
// write them): one point a line, "x y z" or "x y z intensity", separated by
// spaces, tabs or commas (colours or normals are refused: the line names
// the count). Blank lines and lines starting with '#' or '//' are skipped.
// Numbers are read whatever the locale, and written in their shortest
// round-trip form: doubles come back to the bit.
#include <fmt/format.h>

#include <iterator>
#include <optional>
#include <string>
#include <string_view>

#include "cloud_view.hpp"
#include "core/input_file.hpp"
#include "file_bytes.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "hba/io/scan_formats.hpp"
#include "point_columns.hpp"
#include "text_parsing.hpp"

namespace hba::io {
namespace {

// The next number of a line whose words are separated by blanks or commas;
// empty when the line is spent.
std::string_view nextField(std::string_view& line) {
  while (!line.empty() && (line.front() == ',' || line.front() == ' ' || line.front() == '\t')) {
    line.remove_prefix(1);
  }
  std::size_t end = 0;
  while (end < line.size() && line[end] != ',' && line[end] != ' ' && line[end] != '\t' &&
         line[end] != '\r') {
    ++end;
  }
  const std::string_view field = line.substr(0, end);
  line.remove_prefix(end);
  return field;
}

bool skipped(std::string_view line) {
  const std::size_t start = line.find_first_not_of(" \t\r");
  return start == std::string_view::npos || line[start] == '#' || line.compare(start, 2, "//") == 0;
}

template <typename Cloud>
Cloud readXyz(const std::filesystem::path& path) {
  const detail::FileBytes bytes = detail::readFileBytes(path);  // refuses folders, FIFOs, unreadable files
  std::string_view text = withoutByteOrderMark(bytes.view());
  Cloud cloud;
  std::optional<detail::PointCollector<Cloud>> collector;
  std::size_t columns = 0;
  for (std::size_t number = 1; !text.empty(); ++number) {
    std::string_view line = detail::nextLine(text);
    if (skipped(line)) continue;
    double values[4] = {0.0, 0.0, 0.0, 0.0};
    std::size_t count = 0;
    for (std::string_view field = nextField(line); !field.empty(); field = nextField(line), ++count) {
      const std::optional<double> value = detail::parseDouble(field);
      if (!value) failAt(path, fmt::format("line {}: {} is not a number", number, detail::quoteToken(field)));
      if (count < 4) values[count] = *value;
    }
    if (columns == 0) {
      if (count != 3 && count != 4) {
        failAt(path, fmt::format("line {}: {} numbers, expected x y z or x y z intensity", number, count));
      }
      columns = count;
      collector.emplace(cloud, /*wide=*/true, columns == 4);
    } else if (count != columns) {
      failAt(path,
             fmt::format("line {}: {} numbers, expected {} as on the first line", number, count, columns));
    }
    collector->add(values);
  }
  if (collector) collector->finish();
  return cloud;
}

void writeXyz(const std::filesystem::path& path, const detail::CloudView& cloud) {
  cloud.requireOneValuePerPoint(path);
  fmt::memory_buffer text;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3 p = cloud.world(i);
    // {} is the shortest text that reads back to the same double.
    fmt::format_to(std::back_inserter(text), "{} {} {}", p.x(), p.y(), p.z());
    if (cloud.hasIntensity()) fmt::format_to(std::back_inserter(text), " {}", cloud.intensity(i));
    text.push_back('\n');
  }
  writeFileAtomically(
      path, [&](std::ostream& out) { out.write(text.data(), static_cast<std::streamsize>(text.size())); },
      /*binary=*/false);
}

}  // namespace

ScanFormat xyzTextFormat() {
  return {".xyz",
          "XYZ text",
          true,
          &readXyz<PointCloud>,
          [](const std::filesystem::path& p, const PointCloud& c) { writeXyz(p, detail::CloudView(c)); },
          &readXyz<WideCloud>,
          [](const std::filesystem::path& p, const WideCloud& c) { writeXyz(p, detail::CloudView(c)); },
          [](const std::filesystem::path& p) -> std::uint64_t { return readXyz<WideCloud>(p).size(); },
          [](const std::filesystem::path& p) {
            ScanFileFields out{{"x", "y", "z"}, "XYZ text"};
            if (readXyz<WideCloud>(p).hasIntensity()) out.fields.push_back("intensity");
            return out;
          }};
}

}  // namespace hba::io
