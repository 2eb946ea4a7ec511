#include "progress_display.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include "core/progress.hpp"

namespace hba::cli {
namespace {

// Seconds between plain lines: 10, or HBA_PROGRESS_SECONDS.
double lineInterval() {
  const char* text = std::getenv("HBA_PROGRESS_SECONDS");
  char* end = nullptr;
  const double value = text ? std::strtod(text, &end) : 0.0;
  return text && end != text && value >= 0.0 ? value : 10.0;
}

std::string summary(const ProgressState& s) {
  const double left = s.secondsLeft();
  return fmt::format("{}: {}/{} {} ({:.0f} %), {:.1f} {}/s, ETA {}", s.label, s.done, s.total, s.unit,
                     s.total ? 100.0 * static_cast<double>(s.done) / static_cast<double>(s.total) : 100.0,
                     s.rate(), s.unit, left < 0.0 ? "?" : formatDuration(left));
}

void drawBar(const ProgressState& s) {
  if (s.finished) {
    std::fputs("\r\033[K", stderr);  // the layer's own summary line follows
    std::fflush(stderr);
    return;
  }
  constexpr int kWidth = 30;
  const int filled = s.total ? static_cast<int>(kWidth * s.done / s.total) : kWidth;
  const std::string bar = std::string(static_cast<std::size_t>(filled), '#') +
                          std::string(static_cast<std::size_t>(kWidth - filled), '.');
  const double left = s.secondsLeft();
  std::fprintf(stderr, "\r\033[K%s [%s] %zu/%zu %s  %.1f/s  ETA %s", s.label.c_str(), bar.c_str(), s.done,
               s.total, s.unit.c_str(), s.rate(), left < 0.0 ? "?" : formatDuration(left).c_str());
  std::fflush(stderr);
}

}  // namespace

void installProgressDisplay(bool show_bar) {
  // Seconds at which each task last printed a plain line.
  auto last_line = std::make_shared<std::map<std::string, double>>();
  const double every = lineInterval();
  setProgressSink([show_bar, last_line, every](const ProgressState& s) {
    if (show_bar) drawBar(s);
    double& last = (*last_line)[s.label];
    if (s.finished) {
      last_line->erase(s.label);
      return;
    }
    if (s.seconds - last < every) return;
    last = s.seconds;
    // On a terminal the bar shows it; the log file still gets the line.
    if (show_bar) {
      spdlog::debug("{}", summary(s));
    } else {
      spdlog::info("{}", summary(s));
    }
  });
}

}  // namespace hba::cli
