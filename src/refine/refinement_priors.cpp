#include "refinement_priors.hpp"

#include <utility>

namespace hba::refine {

ba::PositionPriors blockPriors(const std::vector<graph::PositionPriorFactor>& priors, std::size_t first,
                               std::size_t end, double point_sigma) {
  std::vector<ba::PositionTerm> terms;
  for (const graph::PositionPriorFactor& prior : priors) {
    if (prior.node < first || prior.node >= end) continue;
    ba::PositionTerm term;
    term.frame = prior.node - first;
    term.position = prior.position;
    term.weight = point_sigma * point_sigma * prior.information;
    terms.push_back(term);
  }
  return ba::PositionPriors(std::move(terms));
}

}  // namespace hba::refine
