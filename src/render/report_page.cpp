// The report page: the map thinned to a budget, encoded into typed arrays,
// and set with the run's figures into the page's template.
#include "hba/render/report_page.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <fstream>
#include <iterator>
#include <sstream>

#include "aligned_ground_truth.hpp"
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

Bytes readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string() + ": cannot be read for the report page");
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
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

// The template with each {{NAME}} replaced once, in one pass: text put in
// is never searched again.
std::string fillTemplate(const std::string& page,
                         const std::vector<std::pair<std::string, std::string>>& values) {
  std::string out;
  std::size_t at = 0;
  while (true) {
    const std::size_t open = page.find("{{", at);
    if (open == std::string::npos) break;
    const std::size_t close = page.find("}}", open);
    if (close == std::string::npos) break;
    const std::string name = page.substr(open + 2, close - open - 2);
    out.append(page, at, open - at);
    bool found = false;
    for (const auto& [key, value] : values) {
      if (key != name) continue;
      out += value;
      found = true;
    }
    if (!found) out.append(page, open, close + 2 - open);
    at = close + 2;
  }
  out.append(page, at, std::string::npos);
  return out;
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
  const PagePoints points = samplePagePoints(scans, input.after, settings.point_budget, settings.voxel,
                                             settings.scans_voxel, settings.memory);
  const double sampled = seconds(start);
  const Vec3 origin = input.after.empty() ? Vec3::Zero() : input.after.front().t;
  const double cell = std::max(1.0, 4.0 * points.voxel);
  const QuantizedPoints xyz = quantizePoints(points);
  std::vector<Block> blocks = {{"xyz", xyz.xyz},
                               {"per-scan", pointsPerScan(points, frames)},
                               {"change", thicknessChangeCodes(points, input.before, input.after, cell)},
                               {"pose-input", poseRows(input.before, origin)},
                               {"pose-optimized", poseRows(input.after, origin)}};
  if (!points.intensity.empty()) blocks.push_back({"intensity", intensityCodes(points.intensity)});
  if (!input.ground_truth.empty())
    blocks.push_back(
        {"pose-ground-truth", poseRows(alignedGroundTruth(input.ground_truth, input.after), origin)});

  const nlohmann::json data = {{"title", input.title},
                               {"frames", frames},
                               {"points", points.size()},
                               {"voxel_m", points.voxel},
                               {"step_m", xyz.step},
                               {"origin", {origin.x(), origin.y(), origin.z()}},
                               {"thickness_cell_m", cell},
                               {"change_step_mm", kChangeStepMm},
                               {"has_intensity", !points.intensity.empty()},
                               {"has_ground_truth", !input.ground_truth.empty()},
                               {"report", input.report}};
  std::string block_text;
  for (const Block& b : blocks)
    block_text += "<script type=\"application/octet-stream\" id=\"hba-" + b.id + "\">" + base64(b.bytes) +
                  "</script>\n";
  const std::string picture_text =
      picture.empty() ? std::string()
                      : "<img alt=\"before and after, seen from above\" src=\"data:image/png;base64," +
                            base64(picture) + "\">";
  const std::string page = fillTemplate(kReportPageTemplate, {{"TITLE", escapeHtml(input.title)},
                                                              {"STYLE", kReportPageStyle},
                                                              {"DATA", scriptJson(data)},
                                                              {"BLOCKS", block_text},
                                                              {"PICTURE", picture_text},
                                                              {"SCRIPT", kReportPageScript}});
  const double encoded = seconds(start);
  writeFileAtomically(html, [&](std::ostream& os) { os << page; });
  spdlog::debug("report page: map thinned in {:.2f} s, encoded in {:.2f} s, written in {:.2f} s", sampled,
                encoded - sampled, seconds(start) - encoded);
  ReportPageFigures figures;
  figures.points = points.size();
  figures.voxel = points.voxel;
  figures.bytes = page.size();
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
