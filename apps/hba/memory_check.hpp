#pragma once
// `hba optimize` weighs its estimated peak memory against what the machine
// has before any heavy work, and refuses a run that cannot fit instead of
// being killed by the kernel without a word (docs/pyramid.md, "Memory").
#include <nlohmann/json.hpp>

#include "hba/pipeline/plan.hpp"

namespace hba::cli::optimize {

// Estimates the peak of a run of `settings` (threads resolved) over `scans`
// from a few of them, logs it at debug level, and returns it for
// report.json. Throws hba::Error, naming the stage, its figures, the memory
// available and settings that would fit, when the estimate exceeds the
// memory available; with `ignore` (--no-memory-check) it warns instead.
nlohmann::json checkMemory(const pipeline::Plan& plan, bool ignore);

}  // namespace hba::cli::optimize
