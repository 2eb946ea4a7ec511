#include "refinement_priors.hpp"

#include <algorithm>
#include <iterator>
#include <utility>

namespace hba::pyramid {

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

ba::PositionPriors groupPriors(const std::vector<graph::PositionPriorFactor>& priors,
                               const std::vector<std::size_t>& group_first, const std::vector<Pose>& poses,
                               double point_sigma) {
  std::vector<ba::PositionTerm> terms;
  for (const graph::PositionPriorFactor& prior : priors) {
    if (group_first.empty() || prior.node < group_first.front() || prior.node >= poses.size()) continue;
    // The last group starting at or before the prior's frame.
    const auto after = std::upper_bound(group_first.begin(), group_first.end(), prior.node);
    const auto k = static_cast<std::size_t>(std::distance(group_first.begin(), after) - 1);
    ba::PositionTerm term;
    term.frame = k;
    term.offset = (poses[group_first[k]].inverse() * poses[prior.node]).t;
    term.position = prior.position;
    term.weight = point_sigma * point_sigma * prior.information;
    terms.push_back(term);
  }
  return ba::PositionPriors(std::move(terms));
}

}  // namespace hba::pyramid
