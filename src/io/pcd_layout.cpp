// Where x, y, z and intensity sit in a PCD point, from the validated header.
#include <cstdint>
#include <string>

#include "checked_size.hpp"
#include "hba/core/error.hpp"
#include "pcd_format.hpp"
#include "text_parsing.hpp"

namespace hba::io::detail {
namespace fs = std::filesystem;

ScalarType pcdScalarType(const PcdField& field) {
  if (field.type == 'F') return field.size == 8 ? ScalarType::Float64 : ScalarType::Float32;
  const bool is_signed = field.type == 'I';
  switch (field.size) {
    case 1:
      return is_signed ? ScalarType::Int8 : ScalarType::UInt8;
    case 2:
      return is_signed ? ScalarType::Int16 : ScalarType::UInt16;
    case 4:
      return is_signed ? ScalarType::Int32 : ScalarType::UInt32;
    default:
      return is_signed ? ScalarType::Int64 : ScalarType::UInt64;
  }
}

namespace {

// Records the index of a field hba reads, refusing duplicates and arrays
// (which coordinate of a COUNT 3 "x" would be meant?).
void claimField(std::optional<std::size_t>& slot, std::size_t index, const PcdField& field,
                const fs::path& path) {
  if (slot) failAt(path, "field " + quoteToken(field.name) + " appears twice");
  if (field.count != 1) {
    failAt(path, "field " + quoteToken(field.name) + " has COUNT " + std::to_string(field.count) +
                     "; hba reads it only as a single value");
  }
  slot = index;
}

}  // namespace

PcdLayout pcdLayout(const PcdHeader& header, const fs::path& path) {
  PcdLayout layout;
  std::optional<std::size_t> x, y, z;
  std::uint64_t bytes = 0;
  std::uint64_t words = 0;
  for (std::size_t i = 0; i < header.fields.size(); ++i) {
    const PcdField& field = header.fields[i];
    if (field.name == "x") claimField(x, i, field, path);
    if (field.name == "y") claimField(y, i, field, path);
    if (field.name == "z") claimField(z, i, field, path);
    if (equalsIgnoreCase(field.name, "intensity")) claimField(layout.intensity, i, field, path);
    layout.byte_offsets.push_back(static_cast<std::size_t>(bytes));
    layout.first_words.push_back(static_cast<std::size_t>(words));
    const auto count = static_cast<std::uint64_t>(field.count);
    bytes = checkedAdd(bytes, checkedMul(static_cast<std::uint64_t>(field.size), count, path, "field size"),
                       path, "point size");
    words = checkedAdd(words, count, path, "values per point");
  }
  if (!x || !y || !z) failAt(path, "the cloud has no x, y and z fields");
  // The first of the usual per-point time fields, by the name drivers give it.
  for (const char* name : kPointTimeFields) {
    for (std::size_t i = 0; i < header.fields.size() && !layout.time; ++i) {
      if (header.fields[i].name == name && header.fields[i].count == 1) layout.time = i;
    }
  }
  if (bytes > SIZE_MAX / 2) failAt(path, "point size " + std::to_string(bytes) + " is too large");
  layout.point_bytes = static_cast<std::size_t>(bytes);
  layout.words_per_point = static_cast<std::size_t>(words);
  layout.x = *x;
  layout.y = *y;
  layout.z = *z;
  return layout;
}

}  // namespace hba::io::detail
