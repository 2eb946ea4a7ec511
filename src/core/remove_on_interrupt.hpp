#pragma once
// Scratch and staging folders to delete when the process is interrupted
// (Ctrl-C, SIGTERM, SIGHUP) before it is done with them. The command-line
// tool blocks those signals in every thread and waits for them in one
// thread of its own (startInterruptWatcher), which removes the registered
// folders in ordinary context, then exits.
#include <filesystem>

namespace hba {

class RemoveOnInterrupt {
 public:
  explicit RemoveOnInterrupt(std::filesystem::path path);
  ~RemoveOnInterrupt();  // unregisters (the owner removes the path itself)
  RemoveOnInterrupt(const RemoveOnInterrupt&) = delete;
  RemoveOnInterrupt& operator=(const RemoveOnInterrupt&) = delete;

 private:
  std::filesystem::path path_;
};

// Removes every registered path; returns how many there were.
std::size_t removeRegisteredPaths();

// Blocks SIGINT, SIGTERM and SIGHUP in the calling thread (and the threads
// it starts later) and starts a thread that, on one of them, removes the
// registered paths, prints a line on stderr and exits with 128 + signal.
// Call first thing in main().
void startInterruptWatcher();

}  // namespace hba
