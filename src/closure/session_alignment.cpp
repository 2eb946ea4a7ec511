#include "hba/closure/session_alignment.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "core/kd_tree.hpp"
#include "core/stopwatch.hpp"
#include "hba/closure/point_features.hpp"
#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "neighbourhood.hpp"
#include "place_alignment.hpp"

namespace hba::closure {

FrameRange submapFrames(const std::vector<Pose>& poses, std::size_t centre, double path_m,
                        std::size_t max_frames, FrameRange bounds) {
  FrameRange range{centre, centre};
  double walked = 0.0;
  while (range.first > bounds.first && centre - range.first < max_frames) {
    walked += (poses[range.first].t - poses[range.first - 1].t).norm();
    if (walked > path_m) break;
    --range.first;
  }
  walked = 0.0;
  while (range.last < bounds.last && range.last - centre < max_frames) {
    walked += (poses[range.last + 1].t - poses[range.last].t).norm();
    if (walked > path_m) break;
    ++range.last;
  }
  return range;
}

namespace {

double medianRange(const PointCloud& scan) {
  if (scan.empty()) return 0.0;
  std::vector<float> ranges;
  for (const Vec3f& p : scan.points) ranges.push_back(p.norm());
  std::nth_element(ranges.begin(), ranges.begin() + static_cast<std::ptrdiff_t>(ranges.size() / 2),
                   ranges.end());
  return ranges[ranges.size() / 2];
}

}  // namespace

double featureVoxel(const std::vector<const Side*>& sides) {
  std::vector<std::pair<const Side*, std::size_t>> places;
  for (const Side* side : sides) {
    for (std::size_t frame : side->places) places.emplace_back(side, frame);
  }
  std::vector<double> ranges(places.size());
  tbb::parallel_for(std::size_t{0}, ranges.size(), [&](std::size_t i) {
    ranges[i] = medianRange(places[i].first->scans.load(places[i].second));
  });
  std::nth_element(ranges.begin(), ranges.begin() + static_cast<std::ptrdiff_t>(ranges.size() / 2),
                   ranges.end());
  return std::clamp(ranges[ranges.size() / 2] / 20.0, 0.1, 1.0);
}

namespace {

// Describes the places of `which` (indices into `side.places`) into `out`.
void describePlaces(const Side& side, const std::vector<std::size_t>& which, double voxel,
                    const SessionAlignmentSettings& s, std::vector<FeatureCloud>& out) {
  tbb::parallel_for(std::size_t{0}, which.size(), [&](std::size_t k) {
    const std::size_t frame = side.places[which[k]];
    out[which[k]] =
        describeCloud(mergeNeighbourhood(side.scans, side.poses, frame, side.submap(frame, s), voxel), voxel);
  });
}

// Votes take a near-nearest descriptor (within 1 + eps of the nearest's
// distance): exact search in 33 dimensions visits most of the tree.
constexpr float kVoteEps = 1.0F;

struct Candidate {
  std::size_t reference = 0;  // index into the places
  std::size_t session = 0;
  std::size_t votes = 0;
};

// Each session place's descriptors vote for the reference place holding
// their nearest descriptor; its `shortlist` most voted places, all
// candidates most voted first.
std::vector<Candidate> vote(const std::vector<FeatureCloud>& reference,
                            const std::vector<std::size_t>& reference_ids,
                            const std::vector<FeatureCloud>& session,
                            const std::vector<std::size_t>& session_ids, const SessionAlignmentSettings& s) {
  std::vector<Fpfh> all;
  std::vector<std::size_t> owner;
  for (std::size_t a : reference_ids) {
    const std::vector<Fpfh>& theirs = reference[a].features;
    const std::size_t stride =
        std::max<std::size_t>(1, theirs.size() / std::max<std::size_t>(1, s.voted_per_place));
    for (std::size_t i = 0; i < theirs.size(); i += stride) {
      all.push_back(theirs[i]);
      owner.push_back(a);
    }
  }
  const KdTree<33> tree(all);
  std::vector<std::vector<Candidate>> per_place(session_ids.size());
  tbb::parallel_for(std::size_t{0}, session_ids.size(), [&](std::size_t k) {
    const std::size_t b = session_ids[k];
    std::vector<std::size_t> counts(reference.size(), 0);
    const std::vector<Fpfh>& mine = session[b].features;
    const std::size_t stride =
        std::max<std::size_t>(1, mine.size() / std::max<std::size_t>(1, s.votes_per_place));
    for (std::size_t i = 0; i < mine.size(); i += stride) {
      const std::size_t j = tree.nearest(mine[i], kVoteEps).first;
      if (j < all.size()) ++counts[owner[j]];
    }
    std::vector<Candidate>& list = per_place[k];
    for (std::size_t a = 0; a < reference.size(); ++a) {
      if (counts[a] > 0) list.push_back({a, b, counts[a]});
    }
    const std::size_t keep = std::min(s.shortlist, list.size());
    std::partial_sort(list.begin(), list.begin() + static_cast<std::ptrdiff_t>(keep), list.end(),
                      [](const Candidate& x, const Candidate& y) { return x.votes > y.votes; });
    list.resize(keep);
  });
  std::vector<Candidate> candidates;
  for (const auto& list : per_place) candidates.insert(candidates.end(), list.begin(), list.end());
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& x, const Candidate& y) { return x.votes > y.votes; });
  return candidates;
}

// Every `stride`-th index below `count` not yet in `done` (which it joins).
std::vector<std::size_t> newPlaces(std::size_t count, std::size_t stride, std::vector<bool>& done) {
  std::vector<std::size_t> fresh;
  for (std::size_t i = 0; i < count; i += stride) {
    if (!done[i]) fresh.push_back(i);
    done[i] = true;
  }
  return fresh;
}

std::vector<std::size_t> describedPlaces(const std::vector<bool>& done) {
  std::vector<std::size_t> ids;
  for (std::size_t i = 0; i < done.size(); ++i) {
    if (done[i]) ids.push_back(i);
  }
  return ids;
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

std::string fixed(double value, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

// Registers candidate pairs and verifies the registered ones with the plane
// BA. Both sides form one sequence, each in its own frame: verifyLoop
// merges each end's submap by its own side's poses and starts from the
// registration's relative pose.
class PairVerifier {
 public:
  PairVerifier(const Side& reference, const Side& session, const SessionAlignmentSettings& settings)
      : reference_(reference),
        session_(session),
        both_({&reference.scans, &session.scans}),
        offset_(reference.poses.size()),
        settings_(settings) {
    poses_ = reference.poses;
    poses_.insert(poses_.end(), session.poses.begin(), session.poses.end());
    check_ = settings.check;
    check_.search_radius_m = 0.0;
    check_.search_yaw_deg = 0.0;
  }

  // Each candidate's trial and, when verified, the relative pose (T_ref^-1 T_session) it found.
  std::vector<std::pair<SessionPairTrial, Pose>> run(const std::vector<Candidate>& candidates,
                                                     const std::vector<FeatureCloud>& reference,
                                                     const std::vector<FeatureCloud>& session) const {
    std::vector<std::pair<SessionPairTrial, Pose>> out(candidates.size());
    tbb::parallel_for(std::size_t{0}, candidates.size(), [&](std::size_t c) {
      const Candidate& candidate = candidates[c];
      SessionPairTrial& trial = out[c].first;
      trial.reference_frame = reference_.places[candidate.reference];
      trial.session_frame = session_.places[candidate.session];
      trial.votes = candidate.votes;
      const Registration r =
          registerClouds(session[candidate.session], reference[candidate.reference], settings_.registration);
      trial.matches = r.matches;
      trial.inliers = r.inliers;
      trial.fitness = r.fitness;
      trial.outcome = registrationProblem(r);
      if (!trial.outcome.empty()) return;
      // The plane BA sees the submaps the descriptors described.
      const FrameRange from = reference_.submap(trial.reference_frame, settings_);
      const FrameRange to = session_.submap(trial.session_frame, settings_);
      const LoopCheck verified = verifyLoop(
          both_, poses_, {trial.reference_frame, offset_ + trial.session_frame, r.target_from_source}, check_,
          LoopEnds{{from.first, from.last}, {offset_ + to.first, offset_ + to.last}});
      trial.verified = verified.accepted;
      trial.outcome = verified.accepted ? "verified" : "plane BA: " + verified.reason;
      out[c].second = verified.relative;
    });
    return out;
  }

 private:
  // Why a registration does not go on to the plane BA, or "".
  std::string registrationProblem(const Registration& r) const {
    if (!r.found) return "registration: " + r.reason;
    if (r.fitness < settings_.min_fitness) {
      return "registration: " + fixed(r.fitness, 2) + " of the submap on the other's surfaces (" +
             fixed(settings_.min_fitness, 2) + " needed)";
    }
    return "";
  }

  const Side& reference_;
  const Side& session_;
  io::ConcatenatedScanSource both_;
  std::vector<Pose> poses_;
  std::size_t offset_;
  LoopCheckSettings check_;
  const SessionAlignmentSettings& settings_;
};

constexpr std::size_t kBatch = 4;  // pairs registered together; stop between batches once enough agree

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

SessionAlignment alignSides(const Side& reference_side, const Side& session_side, double voxel,
                            const SessionAlignmentSettings& settings) {
  SessionAlignment result;
  result.reference_places = reference_side.places.size();
  result.session_places = session_side.places.size();
  result.feature_voxel_m = voxel;
  const PairVerifier verifier(reference_side, session_side, settings);
  std::vector<FeatureCloud> reference(reference_side.places.size()), session(session_side.places.size());
  std::vector<bool> reference_done(reference.size(), false), session_done(session.size(), false);
  std::set<std::pair<std::size_t, std::size_t>> registered;
  std::vector<Pose> placements;
  // A sparse round first (every third place): sessions that overlap much
  // meet there; the rest of the places only when they do not.
  for (const std::size_t stride : {std::size_t{3}, std::size_t{1}}) {
    Clock::time_point started = Clock::now();
    describePlaces(reference_side, newPlaces(reference.size(), stride, reference_done), voxel, settings,
                   reference);
    describePlaces(session_side, newPlaces(session.size(), stride, session_done), voxel, settings, session);
    result.seconds_describing += secondsSince(started);
    started = Clock::now();
    std::vector<Candidate> candidates =
        vote(reference, describedPlaces(reference_done), session, describedPlaces(session_done), settings);
    result.seconds_voting += secondsSince(started);
    started = Clock::now();
    std::vector<Candidate> fresh;
    for (const Candidate& c : candidates) {
      if (registered.size() + fresh.size() >= settings.max_trials) break;
      if (registered.count({c.reference, c.session}) == 0) fresh.push_back(c);
    }
    for (const Candidate& c : fresh) registered.insert({c.reference, c.session});
    for (std::size_t first = 0; first < fresh.size(); first += kBatch) {
      const std::vector<Candidate> batch(
          fresh.begin() + static_cast<std::ptrdiff_t>(first),
          fresh.begin() + static_cast<std::ptrdiff_t>(std::min(fresh.size(), first + kBatch)));
      for (const auto& [trial, relative] : verifier.run(batch, reference, session)) {
        ++result.tried;
        if (trial.verified) {
          ++result.verified;
          // T_ref * relative is where the session's frame puts that scan: T_world_session * T_session.
          placements.push_back(reference_side.poses[trial.reference_frame] * relative *
                               session_side.poses[trial.session_frame].inverse());
        }
        result.trials.push_back(trial);
      }
      if (largestAgreement(placements, settings).second >= settings.enough_agreeing) break;
    }
    result.seconds_registering += secondsSince(started);
    if (largestAgreement(placements, settings).second >= settings.min_agreeing) break;
  }
  const auto [best, count] = largestAgreement(placements, settings);
  result.agreeing = count;
  if (count < settings.min_agreeing) {
    std::size_t unregistered = 0;
    for (const SessionPairTrial& t : result.trials)
      unregistered += t.outcome.rfind("registration", 0) == 0 ? 1 : 0;
    result.reason =
        std::to_string(result.reference_places) + " and " + std::to_string(result.session_places) +
        " places described (descriptor voxel " + fixed(voxel, 2) + " m); of " + std::to_string(result.tried) +
        " most alike pairs, " + std::to_string(unregistered) + " did not register, " +
        std::to_string(result.tried - unregistered - result.verified) + " failed the plane BA, " +
        std::to_string(result.verified) + " verified, " + std::to_string(count) + " agreeing (" +
        std::to_string(settings.min_agreeing) + " needed): the sessions may not overlap (-v logs every pair)";
    return result;
  }
  result.found = true;
  result.world_from_session = placements[best];
  return result;
}

SessionAlignment alignSession(const io::ScanSource& reference_scans, const std::vector<Pose>& reference_poses,
                              const io::ScanSource& session_scans, const std::vector<Pose>& session_poses,
                              const SessionAlignmentSettings& settings) {
  if (reference_poses.size() != reference_scans.size() || session_poses.size() != session_scans.size()) {
    throw Error("session alignment: pose and scan counts differ");
  }
  if (reference_poses.empty() || session_poses.empty()) {
    throw Error("session alignment: a session without scans");
  }
  const Side reference{reference_scans, reference_poses,
                       samplePlaces(reference_poses, settings.sample_spacing_m, settings.max_samples), false};
  const Side session{session_scans, session_poses,
                     samplePlaces(session_poses, settings.sample_spacing_m, settings.max_samples), false};
  const double voxel =
      settings.feature_voxel_m > 0.0 ? settings.feature_voxel_m : featureVoxel({&reference, &session});
  return alignSides(reference, session, voxel, settings);
}

}  // namespace hba::closure
