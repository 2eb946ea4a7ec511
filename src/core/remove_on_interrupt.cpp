#include "core/remove_on_interrupt.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <mutex>
#include <set>
#include <system_error>
#include <thread>

namespace hba {
namespace fs = std::filesystem;

namespace {

std::mutex& registryMutex() {
  static std::mutex mutex;
  return mutex;
}

std::multiset<fs::path>& registry() {
  static std::multiset<fs::path> paths;
  return paths;
}

sigset_t interruptSignals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGHUP);
  return signals;
}

}  // namespace

RemoveOnInterrupt::RemoveOnInterrupt(fs::path path) : path_(std::move(path)) {
  const std::lock_guard<std::mutex> lock(registryMutex());
  registry().insert(path_);
}

RemoveOnInterrupt::~RemoveOnInterrupt() {
  const std::lock_guard<std::mutex> lock(registryMutex());
  const auto it = registry().find(path_);
  if (it != registry().end()) registry().erase(it);
}

std::size_t removeRegisteredPaths() {
  const std::lock_guard<std::mutex> lock(registryMutex());
  for (const fs::path& path : registry()) {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  return registry().size();
}

void startInterruptWatcher() {
  const sigset_t signals = interruptSignals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread([signals] {
    int signal = 0;
    if (sigwait(&signals, &signal) != 0) return;
    const std::size_t removed = removeRegisteredPaths();
    std::fprintf(stderr, "[error] interrupted (%s)%s\n", strsignal(signal),
                 removed > 0 ? "; the unfinished output was removed" : "");
    std::fflush(stderr);
    ::_exit(128 + signal);
  }).detach();
}

}  // namespace hba
