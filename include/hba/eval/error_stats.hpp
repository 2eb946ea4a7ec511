#pragma once
// Summary statistics of a list of non-negative errors.
#include <cstddef>
#include <vector>

namespace hba::eval {

struct ErrorStats {
  std::size_t count = 0;
  double rmse = 0.0;
  double mean = 0.0;
  double median = 0.0;  // mean of the two middle values for an even count
  double std = 0.0;     // population standard deviation (divided by n, as evo's numpy)
  double min = 0.0;
  double max = 0.0;
};

// All zeros for an empty list.
ErrorStats summarize(std::vector<double> errors);

}  // namespace hba::eval
