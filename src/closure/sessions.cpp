#include "hba/closure/sessions.hpp"

#include <algorithm>
#include <string>

#include "hba/core/error.hpp"

namespace hba::closure {

std::vector<std::size_t> sessionOfFrames(std::size_t frames, std::vector<std::size_t> starts) {
  std::sort(starts.begin(), starts.end());
  starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
  if (!starts.empty() && starts.back() >= frames) {
    throw Error("a session starts at frame " + std::to_string(starts.back()) + " of " +
                std::to_string(frames));
  }
  std::vector<std::size_t> session(frames, 0);
  std::size_t current = 0, next = 0;
  for (std::size_t k = 0; k < frames; ++k) {
    while (next < starts.size() && starts[next] == k) {
      if (k > 0) ++current;
      ++next;
    }
    session[k] = current;
  }
  return session;
}

}  // namespace hba::closure
