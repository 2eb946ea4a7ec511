#pragma once
// The run report as JSON (the body of report.json written by `hba optimize`).
#include <nlohmann/json.hpp>

#include "hba/pyramid/hierarchical_ba.hpp"

namespace hba::pyramid {

nlohmann::json reportToJson(const HbaReport& report);

}  // namespace hba::pyramid
