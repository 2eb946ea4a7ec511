#pragma once
// The run report as JSON (the body of report.json written by `hba optimize`).
#include <nlohmann/json.hpp>

#include <vector>

#include "hba/pyramid/hierarchical_ba.hpp"
#include "hba/pyramid/window_errors.hpp"

namespace hba::pyramid {

nlohmann::json reportToJson(const HbaReport& report);

// report.json's `window_errors`: one object per layer and round.
nlohmann::json windowErrorsToJson(const std::vector<LayerWindowErrors>& rows);

}  // namespace hba::pyramid
