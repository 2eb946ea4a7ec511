#include "hba/closure/session_alignment.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "neighbourhood.hpp"
#include "place_signature.hpp"

namespace hba::closure {
namespace {

std::vector<PlaceSignature> signatures(const io::ScanSource& scans, const std::vector<Pose>& poses,
                                       const std::vector<std::size_t>& places,
                                       const LoopCheckSettings& check) {
  std::vector<PlaceSignature> out(places.size());
  tbb::parallel_for(std::size_t{0}, places.size(), [&](std::size_t i) {
    const FrameRange frames = neighbourhoodFrames(places[i], check.neighbourhood_frames, poses.size());
    out[i] = placeSignature(mergeNeighbourhood(scans, poses, places[i], frames, check.neighbourhood_voxel));
  });
  return out;
}

struct Trial {
  std::size_t reference = 0;  // frame
  std::size_t session = 0;    // frame
  double distance = 0.0;      // of the signatures
};

// For each place of the session, its `shortlist` most alike reference
// places; all trials, most alike first.
std::vector<Trial> shortlist(const std::vector<std::size_t>& reference_places,
                             const std::vector<PlaceSignature>& reference,
                             const std::vector<std::size_t>& session_places,
                             const std::vector<PlaceSignature>& session, std::size_t count) {
  std::vector<Trial> trials;
  for (std::size_t b = 0; b < session.size(); ++b) {
    std::vector<Trial> mine;
    for (std::size_t a = 0; a < reference.size(); ++a) {
      mine.push_back({reference_places[a], session_places[b], signatureDistance(reference[a], session[b])});
    }
    const std::size_t keep = std::min(count, mine.size());
    std::partial_sort(mine.begin(), mine.begin() + static_cast<std::ptrdiff_t>(keep), mine.end(),
                      [](const Trial& x, const Trial& y) { return x.distance < y.distance; });
    trials.insert(trials.end(), mine.begin(), mine.begin() + static_cast<std::ptrdiff_t>(keep));
  }
  std::stable_sort(trials.begin(), trials.end(),
                   [](const Trial& x, const Trial& y) { return x.distance < y.distance; });
  return trials;
}

bool agree(const Pose& a, const Pose& b, const SessionAlignmentSettings& s) {
  const Pose d = a.inverse() * b;
  return d.t.norm() < s.agree_m && so3Log(d.q).norm() * 180.0 / M_PI < s.agree_deg;
}

// The placement that most others agree with, and how many agree with it.
std::pair<std::size_t, std::size_t> largestAgreement(const std::vector<Pose>& placements,
                                                     const SessionAlignmentSettings& s) {
  std::size_t best = 0, best_count = 0;
  for (std::size_t i = 0; i < placements.size(); ++i) {
    std::size_t count = 0;
    for (const Pose& other : placements) count += agree(placements[i], other, s) ? 1 : 0;
    if (count > best_count) {
      best = i;
      best_count = count;
    }
  }
  return {best, best_count};
}

}  // namespace

std::vector<std::size_t> samplePlaces(const std::vector<Pose>& poses, double spacing, std::size_t max_count) {
  std::vector<std::size_t> places;
  double path = 0.0, next = 0.0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (k > 0) path += (poses[k].t - poses[k - 1].t).norm();
    if (path >= next) {
      places.push_back(k);
      next = path + spacing;
    }
  }
  if (places.size() <= max_count || max_count == 0) return places;
  std::vector<std::size_t> spread;
  for (std::size_t i = 0; i < max_count; ++i) spread.push_back(places[i * places.size() / max_count]);
  return spread;
}

SessionAlignment alignSession(const io::ScanSource& reference_scans, const std::vector<Pose>& reference_poses,
                              const io::ScanSource& session_scans, const std::vector<Pose>& session_poses,
                              const SessionAlignmentSettings& settings) {
  if (reference_poses.size() != reference_scans.size() || session_poses.size() != session_scans.size()) {
    throw Error("session alignment: pose and scan counts differ");
  }
  SessionAlignment result;
  const std::vector<std::size_t> reference_places =
      samplePlaces(reference_poses, settings.sample_spacing_m, settings.max_samples);
  const std::vector<std::size_t> session_places =
      samplePlaces(session_poses, settings.sample_spacing_m, settings.max_samples);
  const std::vector<Trial> trials = shortlist(
      reference_places, signatures(reference_scans, reference_poses, reference_places, settings.check),
      session_places, signatures(session_scans, session_poses, session_places, settings.check),
      settings.shortlist);

  // One sequence of both, the session's poses moved per trial so that its
  // place coincides with the reference's: verifyLoop then searches a full
  // turn and `reach_m` around it.
  const io::ConcatenatedScanSource both({&reference_scans, &session_scans});
  const std::size_t offset = reference_poses.size();
  LoopCheckSettings check = settings.check;
  check.search_radius_m = settings.reach_m;
  check.search_yaw_deg = 180.0;

  std::vector<Pose> placements;
  const std::size_t batch = 4;  // verified together; stop between batches once enough agree
  for (std::size_t first = 0; first < trials.size(); first += batch) {
    const std::size_t last = std::min(trials.size(), first + batch);
    std::vector<LoopCheck> checks(last - first);
    tbb::parallel_for(first, last, [&](std::size_t t) {
      const Trial& trial = trials[t];
      const Pose coincide = reference_poses[trial.reference] * session_poses[trial.session].inverse();
      std::vector<Pose> poses = reference_poses;
      for (const Pose& p : session_poses) poses.push_back(coincide * p);
      checks[t - first] =
          verifyLoop(both, poses, {trial.reference, offset + trial.session, std::nullopt}, check);
    });
    for (std::size_t t = first; t < last; ++t) {
      ++result.tried;
      const LoopCheck& c = checks[t - first];
      if (!c.accepted) continue;
      ++result.verified;
      // T_ref * relative is where the session's frame puts that scan: T_world_session * T_session.
      placements.push_back(reference_poses[trials[t].reference] * c.relative *
                           session_poses[trials[t].session].inverse());
    }
    if (largestAgreement(placements, settings).second >= settings.enough_agreeing) break;
  }
  const auto [best, count] = largestAgreement(placements, settings);
  result.agreeing = count;
  if (count < settings.min_agreeing) {
    result.reason = std::to_string(result.verified) + " of " + std::to_string(result.tried) +
                    " place pairs verified, " + std::to_string(count) + " agreeing (" +
                    std::to_string(settings.min_agreeing) + " needed): the sessions may not overlap";
    return result;
  }
  result.found = true;
  result.world_from_session = placements[best];
  return result;
}

}  // namespace hba::closure
