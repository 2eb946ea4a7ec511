// The closure stage's text inputs: loop pairs (--loops) and position priors
// (--priors), read as `hba optimize` reads them.
#include <cstdlib>
#include <limits>

#include "harness.hpp"
#include "harness_checks.hpp"
#include "hba/io/loop_file.hpp"
#include "hba/io/position_prior_file.hpp"

namespace hba::fuzz {
namespace fs = std::filesystem;

namespace {

// Pairs of two different frames of the sequence; a given relative pose is finite.
void checkLoops(const std::vector<io::LoopRecord>& loops, std::size_t frame_count) {
  for (const io::LoopRecord& loop : loops) {
    if (loop.from >= frame_count || loop.to >= frame_count || loop.from == loop.to) std::abort();
    if (loop.relative) {
      if (!loop.relative->t.allFinite()) std::abort();
      checkRotation(loop.relative->q);
    }
  }
}

}  // namespace

void feedLoopFile(const fs::path& input) {
  // A short sequence (indices beyond it refused) and the longest one.
  for (const std::size_t frames : {std::size_t{100}, std::numeric_limits<std::size_t>::max()}) {
    rejectOnlyWithError([&] { checkLoops(io::readLoopFile(input, frames), frames); });
  }
}

// Finite positions, positive finite sigmas, stamps that increase.
void feedPriorFile(const fs::path& input) {
  rejectOnlyWithError([&] {
    const std::vector<io::TimedPosition> priors = io::readPositionPriorFile(input);
    for (std::size_t i = 0; i < priors.size(); ++i) {
      const io::TimedPosition& prior = priors[i];
      if (!std::isfinite(prior.stamp) || !prior.position.allFinite() || !prior.sigma.allFinite())
        std::abort();
      if (!(prior.sigma.minCoeff() > 0.0)) std::abort();
      if (i > 0 && !(prior.stamp > priors[i - 1].stamp)) std::abort();
    }
  });
}

}  // namespace hba::fuzz
