#pragma once
// The run's settings as the last stage (src/refine) reads them.
#include "hba/pyramid/settings.hpp"
#include "refine/refinement.hpp"

namespace hba::pyramid {

refine::RefineSettings refineSettingsOf(const HbaSettings& settings);

}  // namespace hba::pyramid
