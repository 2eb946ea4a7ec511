// A stage that changes nothing: it logs how long each stage before it took.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <string>

#include "run.hpp"

namespace hba::pipeline {

void logStageTimes(Run& run) {
  std::string line;
  for (const auto& [name, seconds] : run.stage_seconds) {
    line += fmt::format("{}{} {:.2f} s", line.empty() ? "" : ", ", name, seconds);
  }
  spdlog::info("stages: {}", line);
}

}  // namespace hba::pipeline
