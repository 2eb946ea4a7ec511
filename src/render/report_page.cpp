// The report page: the map thinned to a budget, encoded into typed arrays,
// and set with the run's figures into the page's template.
#include "hba/render/report_page.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <fstream>
#include <functional>

#include "aligned_ground_truth.hpp"
#include "core/input_file.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "page_assets.hpp"
#include "page_blocks.hpp"
#include "page_points.hpp"

namespace hba::render {
namespace {

constexpr const char* kMarker = "<!DOCTYPE html>\n<!-- hba report page";  // how the template starts

void checkCount(const std::vector<Pose>& poses, std::size_t scans, const char* what) {
  if (poses.size() != scans) {
    throw Error(std::string(what) + ": " + std::to_string(poses.size()) + " poses for " +
                std::to_string(scans) + " scans");
  }
}

// The picture's bytes (InputFile names the file on any failure).
Bytes readBytes(const std::filesystem::path& path) {
  InputFile file(path);
  Bytes bytes(static_cast<std::size_t>(file.size()));
  bytes.resize(file.read(reinterpret_cast<char*>(bytes.data()), bytes.size()));
  return bytes;
}

std::string escapeHtml(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// JSON safe inside a <script> element: "</" cannot end it early.
std::string scriptJson(const nlohmann::json& value) {
  const std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out += '\\';
  }
  return out;
}

struct Block {
  std::string id;
  Bytes bytes;
};

// The page's data: the map thinned to the budget, encoded (the points
// themselves are freed on return), and what the script reads first.
struct PageData {
  std::vector<Block> blocks;
  nlohmann::json header;
  std::size_t points = 0;
  double voxel = 0.0;
};

PageData encodeData(const io::ScanSource& scans, const ReportPageInput& input,
                    const ReportPageSettings& settings) {
  const PagePoints points = samplePagePoints(scans, input.after, settings.point_budget, settings.voxel,
                                             settings.scans_voxel, settings.memory);
  const Vec3 origin = input.after.empty() ? Vec3::Zero() : input.after.front().t;
  const double cell = std::max(1.0, 4.0 * points.voxel);
  QuantizedPoints xyz = quantizePoints(points);
  PageData out;
  out.points = points.size();
  out.voxel = points.voxel;
  out.blocks = {{"xyz", std::move(xyz.xyz)},
                {"per-scan", pointsPerScan(points, scans.size())},
                {"change", thicknessChangeCodes(points, input.before, input.after, cell)},
                {"pose-input", poseRows(input.before, origin)},
                {"pose-optimized", poseRows(input.after, origin)}};
  if (points.has_intensity) out.blocks.push_back({"intensity", intensityCodes(points)});
  if (!input.ground_truth.empty())
    out.blocks.push_back(
        {"pose-ground-truth", poseRows(alignedGroundTruth(input.ground_truth, input.after), origin)});
  out.header = {{"title", input.title},
                {"frames", scans.size()},
                {"points", points.size()},
                {"voxel_m", points.voxel},
                {"kept_share", points.kept_share},
                {"step_m", xyz.step},
                {"origin", {origin.x(), origin.y(), origin.z()}},
                {"thickness_cell_m", cell},
                {"change_step_mm", kChangeStepMm},
                {"has_intensity", points.has_intensity},
                {"has_ground_truth", !input.ground_truth.empty()},
                {"report", input.report}};
  return out;
}

using Writer = std::function<void(std::ostream&)>;

// The template with each {{NAME}} written by its writer, in one pass: what
// is put in is never searched; the page is streamed, not held whole.
void writeTemplate(std::ostream& os, const std::string& page,
                   const std::vector<std::pair<std::string, Writer>>& values) {
  std::size_t at = 0;
  while (true) {
    const std::size_t open = page.find("{{", at);
    if (open == std::string::npos) break;
    const std::size_t close = page.find("}}", open);
    if (close == std::string::npos) break;
    const std::string name = page.substr(open + 2, close - open - 2);
    os.write(page.data() + at, static_cast<std::streamsize>(open - at));
    bool found = false;
    for (const auto& [key, write] : values) {
      if (key != name) continue;
      write(os);
      found = true;
    }
    if (!found) os.write(page.data() + open, static_cast<std::streamsize>(close + 2 - open));
    at = close + 2;
  }
  os << page.substr(at);
}

}  // namespace

ReportPageFigures writeReportPage(const io::ScanSource& scans, const ReportPageInput& input,
                                  const std::filesystem::path& html, const ReportPageSettings& settings) {
  const std::size_t frames = scans.size();
  checkCount(input.before, frames, "the input trajectory");
  checkCount(input.after, frames, "the optimized trajectory");
  if (!input.ground_truth.empty()) checkCount(input.ground_truth, frames, "the ground truth");
  const Bytes picture = input.picture.empty() ? Bytes{} : readBytes(input.picture);

  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point since) {
    return std::chrono::duration<double>(Clock::now() - since).count();
  };
  const Clock::time_point start = Clock::now();
  const PageData data = encodeData(scans, input, settings);
  const double encoded = seconds(start);
  const auto text = [](const std::string& value) { return [value](std::ostream& os) { os << value; }; };
  const Writer blocks = [&](std::ostream& os) {
    for (const Block& b : data.blocks) {
      os << "<script type=\"application/octet-stream\" id=\"hba-" << b.id << "\">";
      writeBase64(os, b.bytes);
      os << "</script>\n";
    }
  };
  const Writer image = [&](std::ostream& os) {
    if (picture.empty()) return;
    os << "<img alt=\"before and after, seen from above\" src=\"data:image/png;base64,";
    writeBase64(os, picture);
    os << "\">";
  };
  writeFileAtomically(html, [&](std::ostream& os) {
    writeTemplate(os, kReportPageTemplate,
                  {{"TITLE", text(escapeHtml(input.title))},
                   {"STYLE", text(kReportPageStyle)},
                   {"DATA", text(scriptJson(data.header))},
                   {"BLOCKS", blocks},
                   {"PICTURE", image},
                   {"SCRIPT", text(kReportPageScript)}});
  });
  spdlog::debug("report page: map thinned and encoded in {:.2f} s, written in {:.2f} s", encoded,
                seconds(start) - encoded);
  ReportPageFigures figures;
  figures.points = data.points;
  figures.voxel = data.voxel;
  figures.bytes = static_cast<std::size_t>(std::filesystem::file_size(html));
  return figures;
}

bool isReportPage(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(64, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.rfind(kMarker, 0) == 0;
}

}  // namespace hba::render
