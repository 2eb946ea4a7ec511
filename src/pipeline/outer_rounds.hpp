#pragma once
// When the outer rounds (bottom-up + top-down) of hba optimize stop:
// --iterations is a maximum. A round that moved no pose beyond the settle
// tolerances settles the poses; a round that moved them no less than the
// round before has reached the data's own noise floor (the rounds only trade
// places there, by centimetres on real scans), and more rounds cannot help.
#include <string>

#include "hba/core/pose.hpp"
#include "hba/settings/settings.hpp"

namespace hba::pipeline {

enum class RoundsStop {
  Limit,    // reached --iterations
  Settled,  // the last round moved no pose beyond the tolerances
  Stalled,  // the last round moved the poses no less than the one before
};

class OuterRounds {
 public:
  explicit OuterRounds(const HbaSettings& settings) : settings_(settings) {}
  // After round `round` (from 1) moved the poses by `move`: true to stop.
  bool stopAfter(int round, const PoseChange& move);
  RoundsStop why() const { return why_; }
  // "settled after 3 rounds: largest move 0.0041 m, 0.0020 deg (within 0.01 m, 0.01 deg)"
  const std::string& reason() const { return reason_; }

 private:
  const HbaSettings& settings_;
  double previous_ = 0.0;  // the last round's move, in tolerances
  RoundsStop why_ = RoundsStop::Limit;
  std::string reason_;
};

const char* toString(RoundsStop stop);

}  // namespace hba::pipeline
