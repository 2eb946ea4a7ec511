#pragma once
// One way to name an enum's values, for every enum a user can type: files,
// flags and reports use the same names, and a wrong name gets the same
// error everywhere. An enum opts in by specializing EnumNames:
//
//   template <> struct hba::EnumNames<io::PoseFormat> {
//     static constexpr const char* what = "pose format";
//     static constexpr EnumName<io::PoseFormat> names[] = {{io::PoseFormat::Kitti, "kitti"}, ...};
//   };
//
// Names use '_' between words; parsing also takes '-' (the command line's
// spelling: pose-graph for pose_graph).
#include <algorithm>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hba/core/did_you_mean.hpp"
#include "hba/core/error.hpp"

namespace hba {

template <typename E>
struct EnumName {
  E value;
  const char* name;
};

template <typename E>
struct EnumNames;  // specialized by each named enum: `what` and `names`

// '-' and '_' are the same letter in a name.
inline std::string normalizedEnumName(std::string_view name) {
  std::string out(name);
  std::replace(out.begin(), out.end(), '-', '_');
  return out;
}

template <typename E>
std::string toString(E value) {
  for (const EnumName<E>& entry : EnumNames<E>::names) {
    if (entry.value == value) return entry.name;
  }
  return "unknown";
}

template <typename E>
std::vector<std::string> enumNames() {
  std::vector<std::string> out;
  for (const EnumName<E>& entry : EnumNames<E>::names) out.emplace_back(entry.name);
  return out;
}

// "a, b or c"
template <typename E>
std::string enumNameList() {
  const std::vector<std::string> names = enumNames<E>();
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
    out += names[i];
  }
  return out;
}

// Nothing for an unknown name.
template <typename E>
std::optional<E> findEnum(std::string_view name) {
  const std::string wanted = normalizedEnumName(name);
  for (const EnumName<E>& entry : EnumNames<E>::names) {
    if (wanted == entry.name) return entry.value;
  }
  return std::nullopt;
}

// Throws hba::Error "unknown <what> 'x' (did you mean ...); expected a, b or c".
template <typename E>
E parseEnum(std::string_view name) {
  if (const std::optional<E> found = findEnum<E>(name)) return *found;
  const std::string given(name);
  throw Error("unknown " + std::string(EnumNames<E>::what) + " '" + given + "'" +
              didYouMean(normalizedEnumName(given), enumNames<E>()) + "; expected " + enumNameList<E>());
}

}  // namespace hba
