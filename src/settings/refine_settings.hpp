#pragma once
// The run's settings as the last stage (src/refine) reads them.
#include "hba/settings/settings.hpp"
#include "refine/refinement.hpp"

namespace hba::settings {

refine::RefineSettings refineSettingsOf(const HbaSettings& settings);

}  // namespace hba::settings
