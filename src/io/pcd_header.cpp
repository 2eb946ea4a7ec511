// PCD header parsing. Accepts the variants found in the wild: comment lines
// anywhere before DATA, keywords and the DATA value in any case, CRLF line
// ends, no VIEWPOINT, no COUNT (all 1), no HEIGHT (1), and either WIDTH or
// POINTS missing (derived from the other), and WIDTH 0 HEIGHT 0 with POINTS
// given (one row of POINTS, as PCL reads it; a public SLAM project's
// keyframes are written so).
#include <cctype>
#include <string>

#include "checked_size.hpp"
#include "core/input_file.hpp"
#include "file_bytes.hpp"
#include "hba/core/error.hpp"
#include "io/file_warnings.hpp"
#include "pcd_format.hpp"
#include "text_parsing.hpp"

namespace hba::io {
namespace detail {
namespace fs = std::filesystem;

namespace {

// The header's lines as written, before any cross-checking.
struct RawHeader {
  std::optional<std::vector<std::string_view>> fields, sizes, types, counts;
  std::optional<std::uint64_t> width, height, points;
  std::optional<PcdEncoding> encoding;
};

std::vector<std::string_view> remainingWords(std::string_view text) {
  std::vector<std::string_view> words;
  for (std::string_view word = nextWord(text); !word.empty(); word = nextWord(text)) {
    words.push_back(word);
  }
  return words;
}

std::uint64_t parseCount(std::string_view key, std::string_view value, const fs::path& path) {
  if (!value.empty() && value.front() == '-') {
    failAt(path, std::string(key) + " must not be negative, got " + quoteToken(value));
  }
  const std::optional<std::uint64_t> number = parseUnsigned(value);
  if (!number) {
    failAt(path, std::string(key) + " must be a whole number that fits 64 bits, got " + quoteToken(value));
  }
  return *number;
}

std::uint64_t parseSingleCount(std::string_view key, std::string_view rest, const fs::path& path) {
  const std::vector<std::string_view> words = remainingWords(rest);
  if (words.size() != 1) failAt(path, std::string(key) + " needs exactly one value");
  return parseCount(key, words.front(), path);
}

PcdEncoding parseEncoding(std::string_view rest, const fs::path& path) {
  const std::vector<std::string_view> words = remainingWords(rest);
  const std::string_view value = words.empty() ? std::string_view() : words.front();
  if (words.size() == 1) {
    if (equalsIgnoreCase(value, "ascii")) return PcdEncoding::Ascii;
    if (equalsIgnoreCase(value, "binary")) return PcdEncoding::Binary;
    if (equalsIgnoreCase(value, "binary_compressed")) return PcdEncoding::BinaryCompressed;
  }
  failAt(path,
         "unknown DATA encoding " + quoteToken(value) + " (expected ascii, binary or binary_compressed)");
}

template <typename T>
void setOnce(std::optional<T>& slot, T value, std::string_view key, const fs::path& path) {
  if (slot) failAt(path, "header line " + std::string(key) + " appears twice");
  slot = std::move(value);
}

// Stores one header line; returns true for the DATA line, which ends the header.
bool takeHeaderLine(std::string_view key, std::string_view rest, RawHeader& raw, const fs::path& path) {
  const auto is = [&](std::string_view name) { return equalsIgnoreCase(key, name); };
  if (is("VERSION") || is("VIEWPOINT")) return false;  // nothing hba needs
  if (is("FIELDS") || is("COLUMNS")) {
    setOnce(raw.fields, remainingWords(rest), "FIELDS", path);
  } else if (is("SIZE")) {
    setOnce(raw.sizes, remainingWords(rest), "SIZE", path);
  } else if (is("TYPE")) {
    setOnce(raw.types, remainingWords(rest), "TYPE", path);
  } else if (is("COUNT")) {
    setOnce(raw.counts, remainingWords(rest), "COUNT", path);
  } else if (is("WIDTH")) {
    setOnce(raw.width, parseSingleCount("WIDTH", rest, path), "WIDTH", path);
  } else if (is("HEIGHT")) {
    setOnce(raw.height, parseSingleCount("HEIGHT", rest, path), "HEIGHT", path);
  } else if (is("POINTS")) {
    setOnce(raw.points, parseSingleCount("POINTS", rest, path), "POINTS", path);
  } else if (is("DATA")) {
    raw.encoding = parseEncoding(rest, path);
    return true;
  } else {
    failAt(path, "not a PCD header: unexpected line starting with " + quoteToken(key));
  }
  return false;
}

void checkListLength(const std::optional<std::vector<std::string_view>>& list, std::string_view key,
                     std::size_t field_count, const fs::path& path) {
  if (!list) failAt(path, "the header has no " + std::string(key) + " line");
  if (list->size() != field_count) {
    failAt(path, std::string(key) + " lists " + std::to_string(list->size()) + " values but FIELDS lists " +
                     std::to_string(field_count));
  }
}

PcdField makeField(std::string_view name, std::string_view size_word, std::string_view type_word,
                   std::string_view count_word, const fs::path& path) {
  const std::string where = " of field " + quoteToken(name);
  const std::uint64_t size = parseCount("SIZE", size_word, path);
  if (type_word.size() != 1) failAt(path, "unknown TYPE " + quoteToken(type_word) + where);
  const char type = static_cast<char>(std::toupper(static_cast<unsigned char>(type_word.front())));
  if (type != 'F' && type != 'I' && type != 'U') {
    failAt(path, "unknown TYPE " + quoteToken(type_word) + where + " (expected F, I or U)");
  }
  const bool size_ok =
      type == 'F' ? (size == 4 || size == 8) : (size == 1 || size == 2 || size == 4 || size == 8);
  if (!size_ok) {
    failAt(path, "SIZE " + std::to_string(size) + " does not fit TYPE " + std::string(1, type) + where);
  }
  // A count beyond this is not a point field; the bound keeps record sizes far
  // from overflow on every platform.
  constexpr std::uint64_t kMaxCount = 1u << 20;
  const std::uint64_t count = parseCount("COUNT", count_word, path);
  if (count == 0 || count > kMaxCount) {
    failAt(path, "COUNT " + std::to_string(count) + where + " is out of range");
  }
  PcdField field;
  field.name = std::string(name);
  field.size = static_cast<int>(size);
  field.type = type;
  field.count = static_cast<int>(count);
  return field;
}

PcdHeader validate(const RawHeader& raw, const fs::path& path) {
  if (!raw.fields || raw.fields->empty()) failAt(path, "the header has no FIELDS");
  const std::size_t n = raw.fields->size();
  checkListLength(raw.sizes, "SIZE", n, path);
  checkListLength(raw.types, "TYPE", n, path);
  if (raw.counts) checkListLength(raw.counts, "COUNT", n, path);

  PcdHeader header;
  for (std::size_t i = 0; i < n; ++i) {
    header.fields.push_back(makeField((*raw.fields)[i], (*raw.sizes)[i], (*raw.types)[i],
                                      raw.counts ? (*raw.counts)[i] : std::string_view("1"), path));
  }
  if (!raw.width && !raw.points) failAt(path, "the header has neither WIDTH nor POINTS");
  header.height = raw.height.value_or(1);
  if (raw.width == 0u && raw.height == 0u && raw.points.value_or(0) > 0) {
    // Some writers leave the grid at 0 x 0 and count the points in POINTS
    // alone; PCL reads such a file as one row of POINTS points, and so does hba.
    warnOncePerFolder(path, "PCD grid 0 x 0",
                      "the header says WIDTH 0 HEIGHT 0 but POINTS " + std::to_string(*raw.points) +
                          ": read as one row of " + std::to_string(*raw.points) + " points, as PCL reads it");
    header.width = *raw.points;
    header.height = 1;
  } else if (raw.width) {
    header.width = *raw.width;
  } else if (header.height == 0 || *raw.points % header.height != 0) {
    failAt(path, "POINTS is not a multiple of HEIGHT and WIDTH is missing");
  } else {
    header.width = *raw.points / header.height;
  }
  const std::uint64_t grid = checkedMul(header.width, header.height, path, "WIDTH x HEIGHT");
  header.points = raw.points.value_or(grid);
  if (header.points != grid) {
    failAt(path, "the header is inconsistent: WIDTH x HEIGHT = " + std::to_string(grid) +
                     " but POINTS = " + std::to_string(header.points));
  }
  header.encoding = *raw.encoding;
  return header;
}

}  // namespace

void failNoPcdDataLine(const fs::path& path) {
  failAt(path,
         "no DATA line in the first " + std::to_string(kMaxPcdHeaderBytes) + " bytes (not a PCD file?)");
}

std::optional<PcdHeader> parsePcdHeader(std::string_view bytes, bool is_whole_file, const fs::path& path) {
  if (bytes.empty() && is_whole_file) failAt(path, "empty file");
  // Only the first kMaxPcdHeaderBytes are searched, so a huge file without a
  // header costs one bounded scan.
  const std::string_view window = bytes.substr(0, kMaxPcdHeaderBytes);
  const bool window_is_whole_file = is_whole_file && window.size() == bytes.size();
  RawHeader raw;
  std::string_view rest = withoutByteOrderMark(window);  // an ascii PCD saved by a Windows editor
  while (!rest.empty()) {
    const bool line_complete = rest.find('\n') != std::string_view::npos;
    if (!line_complete && !window_is_whole_file) return std::nullopt;
    std::string_view words = nextLine(rest);
    const std::string_view key = nextWord(words);
    if (key.empty() || key.front() == '#') continue;
    if (takeHeaderLine(key, words, raw, path)) {
      PcdHeader header = validate(raw, path);
      header.data_offset = window.size() - rest.size();
      return header;
    }
  }
  if (!window_is_whole_file) return std::nullopt;
  failAt(path, "the header ends without a DATA line (not a PCD file, or truncated)");
}

}  // namespace detail

PcdHeader readPcdHeader(const std::filesystem::path& path) {
  // Most headers fit in the first small read; long ones get one more try.
  for (const std::size_t limit : {std::size_t{4096}, detail::kMaxPcdHeaderBytes}) {
    const detail::FileBytes head = detail::readFileHead(path, limit);
    const bool whole_file = head.size() < limit;
    if (auto header = detail::parsePcdHeader(head.view(), whole_file, path)) return *header;
  }
  detail::failNoPcdDataLine(path);
}

}  // namespace hba::io
