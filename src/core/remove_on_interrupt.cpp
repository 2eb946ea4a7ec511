#include "core/remove_on_interrupt.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace hba {
namespace fs = std::filesystem;

namespace {

// Never destroyed: the watcher may still use them while exit() runs the
// destructors of static objects.
struct Registry {
  std::mutex mutex;
  std::vector<const RemoveOnInterrupt*> entries;
  std::vector<fs::path> in_place;  // outputs complete before any interrupt
  // The watcher is removing the entries (it holds the gate for good): a
  // path registered now would be made after the removal and left behind.
  bool removing = false;
};

Registry& registry() {
  static auto* instance = new Registry;
  return *instance;
}

// Held by whoever moves an output into place, and, once a signal came, by
// the watcher for good. Recursive: a move may write a file that defers too.
std::recursive_mutex& gate() {
  static auto* instance = new std::recursive_mutex;
  return *instance;
}

std::atomic<bool>& arrived() {
  static std::atomic<bool> flag{false};
  return flag;
}

sigset_t interruptSignals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGHUP);
  return signals;
}

[[noreturn]] void waitForever() {
  for (;;) std::this_thread::sleep_for(std::chrono::hours(1));
}

// Other threads may still be writing into the folder (until their next write
// fails): a file they add between the listing and the rmdir makes one pass
// fail, so the removal is repeated until nothing is left.
void removeWhole(const fs::path& path) {
  for (int attempt = 0; attempt < 200; ++attempt) {
    std::error_code ec;
    fs::remove_all(path, ec);
    if (!fs::exists(fs::symlink_status(path, ec))) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

// What the user finds in each output, for the last line the run prints.
std::string removeAndDescribe(Registry& state) {
  std::string said;
  for (const RemoveOnInterrupt* entry : state.entries) {
    removeWhole(entry->path());
    if (entry->destination().empty()) continue;
    std::error_code ec;
    const bool earlier = fs::exists(fs::symlink_status(entry->destination(), ec));
    said += "; the unfinished output was removed: " + entry->destination().string() +
            (earlier ? " holds the earlier output, unchanged" : " was not created");
  }
  for (const fs::path& destination : state.in_place) {
    said += "; " + destination.string() + " was complete before the interrupt";
  }
  return said;
}

struct TestInterruptPoint {
  std::string name;
  long occurrence = 1;
  int signal = SIGINT;
  mutable std::atomic<long> seen{0};
};

// Read once: the environment does not change while the tool runs.
const TestInterruptPoint* testInterruptPoint() {
  static const TestInterruptPoint* point = []() -> const TestInterruptPoint* {
    const char* at = std::getenv("HBA_TEST_INTERRUPT_AT");
    if (at == nullptr || *at == '\0') return nullptr;
    auto* parsed = new TestInterruptPoint;
    const std::string text = at;
    const std::size_t colon = text.find(':');
    parsed->name = text.substr(0, colon);
    if (colon != std::string::npos) parsed->occurrence = std::strtol(text.c_str() + colon + 1, nullptr, 10);
    const char* signal = std::getenv("HBA_TEST_INTERRUPT_SIGNAL");
    const std::string signal_name = signal ? signal : "INT";
    parsed->signal = signal_name == "TERM" ? SIGTERM : signal_name == "HUP" ? SIGHUP : SIGINT;
    return parsed;
  }();
  return point;
}

}  // namespace

void interruptPointForTests(const char* name) {
  const TestInterruptPoint* point = testInterruptPoint();
  if (point == nullptr || point->name != name) return;
  if (point->seen.fetch_add(1) + 1 != point->occurrence) return;
  ::kill(::getpid(), point->signal);  // blocked here: the watcher takes it
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
}

RemoveOnInterrupt::RemoveOnInterrupt(fs::path path) : RemoveOnInterrupt(std::move(path), fs::path()) {}

RemoveOnInterrupt::RemoveOnInterrupt(fs::path staging, fs::path destination)
    : path_(std::move(staging)), destination_(std::move(destination)) {
  Registry& state = registry();
  std::unique_lock<std::mutex> lock(state.mutex);
  if (state.removing) {
    // The process is ending: this path is never made. (The watcher holds
    // the gate, so this thread holds no deferral it waits for.)
    lock.unlock();
    waitForever();
  }
  state.entries.push_back(this);
}

RemoveOnInterrupt::~RemoveOnInterrupt() {
  Registry& state = registry();
  const std::lock_guard<std::mutex> lock(state.mutex);
  const auto it = std::find(state.entries.begin(), state.entries.end(), this);
  if (it != state.entries.end()) state.entries.erase(it);
}

InterruptDeferral::InterruptDeferral() { gate().lock(); }

InterruptDeferral::~InterruptDeferral() { gate().unlock(); }

void noteOutputInPlace(const fs::path& destination) {
  Registry& state = registry();
  const std::lock_guard<std::mutex> lock(state.mutex);
  state.in_place.push_back(destination);
}

bool interruptArrived() { return arrived().load(); }

void waitIfInterrupted() {
  if (interruptArrived()) waitForever();
}

void closeInterruptWindow() {
  gate().lock();  // never released: the process is ending
  // A signal already sent but not yet taken by the watcher is still
  // answered: it came before the end.
  sigset_t pending;
  sigemptyset(&pending);
  sigpending(&pending);
  const sigset_t signals = interruptSignals();
  bool waiting = interruptArrived();
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
    waiting = waiting || (sigismember(&signals, signal) == 1 && sigismember(&pending, signal) == 1);
  }
  if (waiting) {
    gate().unlock();
    waitForever();
  }
}

void startInterruptWatcher() {
  const sigset_t signals = interruptSignals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread([signals] {
    int signal = 0;
    if (sigwait(&signals, &signal) != 0) return;
    arrived().store(true);
    gate().lock();  // an output being moved into place is finished first; never released
    Registry& state = registry();
    std::string said;
    {
      const std::lock_guard<std::mutex> lock(state.mutex);
      state.removing = true;
      said = removeAndDescribe(state);
    }
    // Tests widen the moment between the removal and the exit, in which
    // other threads still run (a slow build's is long).
    if (const char* pause = std::getenv("HBA_TEST_INTERRUPT_PAUSE_MS")) {
      std::this_thread::sleep_for(std::chrono::milliseconds(std::strtol(pause, nullptr, 10)));
    }
    std::fprintf(stderr, "[error] interrupted (%s)%s\n", strsignal(signal), said.c_str());
    std::fflush(stderr);
    ::_exit(128 + signal);
  }).detach();
}

}  // namespace hba
