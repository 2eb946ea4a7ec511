// The stages' times, logged once they all ran.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <string>
#include <utility>
#include <vector>

#include "stages.hpp"

namespace hba::pipeline {

void logStageTimes(const std::vector<std::pair<std::string, double>>& stage_seconds) {
  std::string line;
  for (const auto& [name, seconds] : stage_seconds) {
    line += fmt::format("{}{} {:.2f} s", line.empty() ? "" : ", ", name, seconds);
  }
  spdlog::info("stages: {}", line);
}

}  // namespace hba::pipeline
