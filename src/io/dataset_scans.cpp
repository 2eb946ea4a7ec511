// Lists and orders the scan files of a folder. Only the directory listing is
// read (no file content, a stat for symbolic links only), so 30 000 scans are
// listed in milliseconds.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

#include "core/input_file.hpp"
#include "dataset_parts.hpp"
#include "hba/core/error.hpp"
#include "hba/io/scan_file.hpp"
#include "hba/io/scan_formats.hpp"

namespace hba::io::detail {
namespace fs = std::filesystem;

namespace {

struct NumberedScan {
  std::uint64_t number = 0;
  fs::path path;
};

bool isHidden(const fs::path& path) {
  const std::string name = path.filename().string();
  return !name.empty() && name.front() == '.';
}

std::string lowercaseExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// The value of the last run of digits in the file's stem.
std::uint64_t numberInName(const fs::path& path) {
  const std::string stem = path.stem().string();
  const auto last_digit =
      std::find_if(stem.rbegin(), stem.rend(), [](unsigned char c) { return std::isdigit(c) != 0; });
  if (last_digit == stem.rend()) {
    failAt(path,
           "cannot order the scans: this file name has no number (expected names like "
           "000012.pcd or 12.pcd)");
  }
  const auto first_digit =
      std::find_if(last_digit, stem.rend(), [](unsigned char c) { return std::isdigit(c) == 0; });
  const std::string digits(first_digit.base(), last_digit.base());
  if (digits.size() > 18) failAt(path, "the number in this file name is too long");
  return std::stoull(digits);
}

bool allDigits(std::string_view text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

// The time a file is named by, in nanoseconds: "1577836980.099104600"
// (seconds.fraction, as bag-to-PCD exporters name scans), or a Unix time in
// milliseconds (13 digits), microseconds (16) or nanoseconds (17 to 19).
// Nothing for other names (000012, scan_7): no index runs to 13 digits.
std::optional<std::uint64_t> nanosecondsInName(const fs::path& path) {
  const std::string stem = path.stem().string();
  const std::size_t dot = stem.find('.');
  if (dot == std::string::npos) {
    if (!allDigits(stem) || stem.size() > 19) return std::nullopt;
    if (stem.size() == 13) return std::stoull(stem) * 1000000ULL;
    if (stem.size() == 16) return std::stoull(stem) * 1000ULL;
    if (stem.size() < 17) return std::nullopt;
    return std::stoull(stem);
  }
  const std::string_view seconds = std::string_view(stem).substr(0, dot);
  std::string fraction = stem.substr(dot + 1);
  // Ten digits of seconds reach the year 2286; fractions beyond ns are cut.
  if (!allDigits(seconds) || seconds.size() > 10 || !allDigits(fraction)) return std::nullopt;
  fraction.resize(9, '0');
  return std::stoull(std::string(seconds)) * 1000000000ULL + std::stoull(fraction);
}

void checkDistinctTimes(const std::vector<NumberedScan>& scans) {
  for (std::size_t i = 1; i < scans.size(); ++i) {
    if (scans[i].number == scans[i - 1].number) {
      failAt(scans[i].path, "is named by the same time as " + scans[i - 1].path.filename().string() +
                                "; remove one of them");
    }
  }
}

template <typename OnScan>
void forEachScanFile(const fs::path& dir, OnScan on_scan) {
  requireFolder(dir, "scans folder");
  std::error_code ec;
  fs::directory_iterator it(dir, ec);
  if (ec) failAt(dir, "cannot list the folder: " + ec.message());
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    if (ec) failAt(dir, "cannot list the folder: " + ec.message());
    const fs::path& path = it->path();
    if (isHidden(path) || !isScanFile(path)) continue;
    // The types come with the listing (a stat only for symbolic links).
    std::error_code type_ec;
    if (it->is_directory(type_ec)) continue;  // a folder is never a scan
    // Named like a scan but a FIFO, a device or a link loop: refused now,
    // naming it, rather than hanging or failing when it is read mid-run.
    if (!it->is_regular_file(type_ec)) requireRegularFile(path);
    if (!on_scan(path)) return;
  }
  if (ec) failAt(dir, "cannot list the folder: " + ec.message());
}

void checkConsecutive(const std::vector<NumberedScan>& scans) {
  for (std::size_t i = 1; i < scans.size(); ++i) {
    const NumberedScan& prev = scans[i - 1];
    const NumberedScan& next = scans[i];
    if (next.number == prev.number) {
      failAt(next.path, "has the same scan number (" + std::to_string(next.number) + ") as " +
                            prev.path.filename().string() + "; remove one of them");
    }
    if (next.number != prev.number + 1) {
      const std::string missing = next.number == prev.number + 2
                                      ? "number " + std::to_string(prev.number + 1) + " is missing"
                                      : "numbers " + std::to_string(prev.number + 1) + " to " +
                                            std::to_string(next.number - 1) + " are missing";
      failAt(prev.path.parent_path(), "gap in the scan numbering: " + prev.path.filename().string() +
                                          " is followed by " + next.path.filename().string() + " (" +
                                          missing + ")");
    }
  }
}

}  // namespace

std::string folderContents(const fs::path& dir) {
  std::map<std::string, std::vector<std::string>> files_by_extension;
  std::size_t folders = 0;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    if (isHidden(entry.path())) continue;
    std::error_code type_ec;
    if (entry.is_directory(type_ec)) {
      ++folders;
    } else {
      files_by_extension[lowercaseExtension(entry.path())].push_back(entry.path().filename().string());
    }
  }
  std::vector<std::pair<std::string, std::vector<std::string>>> kinds(files_by_extension.begin(),
                                                                      files_by_extension.end());
  std::stable_sort(kinds.begin(), kinds.end(),
                   [](const auto& a, const auto& b) { return a.second.size() > b.second.size(); });
  std::vector<std::string> parts;
  for (auto& [extension, names] : kinds) {
    if (parts.size() == 3) {
      parts.push_back("other files");
      break;
    }
    std::sort(names.begin(), names.end());
    const std::string kind =
        extension.empty() ? "file" + std::string(names.size() == 1 ? "" : "s") + " without an extension"
                          : extension + (names.size() == 1 ? " file" : " files");
    const std::string examples = names.size() == 1   ? names.front()
                                 : names.size() == 2 ? names.front() + ", " + names.back()
                                                     : names.front() + " ... " + names.back();
    parts.push_back(std::to_string(names.size()) + " " + kind + " (" + examples + ")");
  }
  if (folders > 0) parts.push_back(std::to_string(folders) + (folders == 1 ? " folder" : " folders"));
  if (parts.empty()) return "nothing";
  std::string text;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i > 0) text += i + 1 == parts.size() ? " and " : ", ";
    text += parts[i];
  }
  return text;
}

bool containsScanFile(const fs::path& dir) {
  bool found = false;
  forEachScanFile(dir, [&](const fs::path&) {
    found = true;
    return false;
  });
  return found;
}

ScanFiles listScans(const fs::path& dir) {
  std::vector<fs::path> files;
  forEachScanFile(dir, [&](const fs::path& path) {
    if (!files.empty() && lowercaseExtension(path) != lowercaseExtension(files.front())) {
      failAt(dir, "mixed scan formats: " + files.front().filename().string() + " and " +
                      path.filename().string() + "; keep one kind of scan file per folder");
    }
    files.push_back(path);
    return true;
  });
  if (files.empty()) {
    failAt(dir, "no scan files in this folder: it holds " + folderContents(dir) + "; hba reads scans as " +
                    scanFormatList() + " files");
  }

  std::vector<NumberedScan> scans;
  scans.reserve(files.size());
  const bool named_by_time = std::all_of(
      files.begin(), files.end(), [](const fs::path& path) { return nanosecondsInName(path).has_value(); });
  for (fs::path& path : files) {
    const std::uint64_t key = named_by_time ? *nanosecondsInName(path) : numberInName(path);
    scans.push_back({key, std::move(path)});
  }
  // Numeric order: 2.pcd before 10.pcd; ties broken by name so errors are stable.
  std::sort(scans.begin(), scans.end(), [](const NumberedScan& a, const NumberedScan& b) {
    return a.number != b.number ? a.number < b.number : a.path < b.path;
  });
  if (named_by_time) {
    checkDistinctTimes(scans);
  } else {
    checkConsecutive(scans);
  }
  ScanFiles result;
  result.paths.reserve(scans.size());
  for (NumberedScan& scan : scans) {
    if (named_by_time) result.stamps.push_back(static_cast<double>(scan.number) * 1e-9);
    result.paths.push_back(std::move(scan.path));
  }
  return result;
}

}  // namespace hba::io::detail
