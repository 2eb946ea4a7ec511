#pragma once
// What Ctrl-C, SIGTERM and SIGHUP leave behind. The command-line tool blocks
// those signals in every thread and waits for them in one thread of its own
// (startInterruptWatcher). On a signal that thread marks the process as
// interrupted, waits for any output being moved into place (InterruptDeferral),
// removes the registered scratch and staging paths, says which outputs are
// complete and which were not written, and exits with 128 + signal.
//
// So an interrupted run leaves every output either complete (moved into
// place before the signal) or as it was before the run (absent, or the
// earlier output), and no hidden staging or temporary files.
#include <filesystem>

namespace hba {

class RemoveOnInterrupt {
 public:
  // A scratch file or folder (a temporary, a lock, spilled scans): removed on
  // an interrupt, not mentioned.
  explicit RemoveOnInterrupt(std::filesystem::path path);
  // A staging folder that will become `destination`: removed on an
  // interrupt, and the message says that `destination` was not written.
  RemoveOnInterrupt(std::filesystem::path staging, std::filesystem::path destination);
  ~RemoveOnInterrupt();  // unregisters (the owner removes the path itself)
  RemoveOnInterrupt(const RemoveOnInterrupt&) = delete;
  RemoveOnInterrupt& operator=(const RemoveOnInterrupt&) = delete;

  const std::filesystem::path& path() const { return path_; }
  const std::filesystem::path& destination() const { return destination_; }

 private:
  std::filesystem::path path_;
  std::filesystem::path destination_;
};

// Held while an output is moved into place (renames that must not be cut in
// half): an interrupt waits until it is released, so it finds the output
// either not begun or complete. Once an interrupt is being handled, making
// one blocks until the process exits.
class InterruptDeferral {
 public:
  InterruptDeferral();
  ~InterruptDeferral();
  InterruptDeferral(const InterruptDeferral&) = delete;
  InterruptDeferral& operator=(const InterruptDeferral&) = delete;
};

// Records that `destination` is complete, for the interrupt message. Call
// while holding an InterruptDeferral, right after moving it into place.
void noteOutputInPlace(const std::filesystem::path& destination);

// True once an interrupt signal arrived. A failure seen after that (a file
// removed from under a writer) is the interrupt's doing, not the input's.
bool interruptArrived();

// If an interrupt arrived, blocks until the watcher ends the process (so
// that no error caused by the removal is printed and the process does not
// exit under the watcher's feet); otherwise returns.
void waitIfInterrupted();

// For the end of main(): from now on an interrupt is ignored (the outputs are
// complete), or, if one is being handled, waits for it to end the process.
void closeInterruptWindow();

// For tests that must interrupt at an exact point (the middle of a swap):
// with HBA_TEST_INTERRUPT_AT=NAME[:N] in the environment, the N-th (default
// first) call with that name sends the process HBA_TEST_INTERRUPT_SIGNAL
// (default SIGINT; or TERM, HUP) and gives the watcher 100 ms to act.
// Without the variable it does nothing.
void interruptPointForTests(const char* name);

// Blocks SIGINT, SIGTERM and SIGHUP in the calling thread (and the threads
// it starts later) and starts the watcher thread. Call first thing in main().
void startInterruptWatcher();

}  // namespace hba
