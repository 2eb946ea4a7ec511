// hba built without recordings (HBA_WITH_RECORDINGS=OFF): a recording is
// recognized by its name and refused with the way to read it.
#include <fmt/format.h>

#include "hba/core/error.hpp"
#include "hba/rec/recording.hpp"

namespace hba::rec {
namespace fs = std::filesystem;

struct Recording::Clouds {};

std::string describeTopics(const std::vector<RecordingTopic>& topics) {
  std::string text;
  for (const RecordingTopic& topic : topics) {
    text += fmt::format("  {}  {}  {} messages\n", topic.topic, topic.type, topic.messages);
  }
  return text.empty() ? "  (none)" : text.substr(0, text.size() - 1);
}

bool isRecording(const fs::path& path) {
  std::error_code error;
  const std::string extension = path.extension().string();
  if (fs::is_directory(path, error)) return fs::is_regular_file(path / "metadata.yaml", error);
  return extension == ".bag" || extension == ".mcap" || extension == ".db3";
}

Recording::Recording() = default;
Recording::~Recording() = default;
Recording::Recording(Recording&&) noexcept = default;
Recording& Recording::operator=(Recording&&) noexcept = default;

Recording Recording::open(const fs::path& path, const RecordingOptions&) {
  failAt(
      path,
      "this hba was built without recordings (cmake -DHBA_WITH_RECORDINGS=OFF): rebuild with "
      "-DHBA_WITH_RECORDINGS=ON (liblz4-dev, libzstd-dev, libbz2-dev, libsqlite3-dev), or give a folder of "
      "scans (hba extract on a build that reads recordings writes one)");
}

PointCloud Recording::loadScan(std::size_t) const { return {}; }

}  // namespace hba::rec
