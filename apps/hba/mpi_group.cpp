// With MPI: mpirun's ranks, MPI_COMM_WORLD.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>

#include "hba/core/error.hpp"
#include "process_group.hpp"

namespace hba::cli {
namespace {

// Launchers of Open MPI, MPICH (Hydra) and PMIx-based ones say so in the
// environment of the processes they start.
bool startedByALauncher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

void check(int code, const char* what) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw Error(std::string("MPI: ") + what +
              " failed: " + std::string(text, static_cast<std::size_t>(length)));
}

// Waits for `request` without spinning: a member waiting for the first one's
// refinement would otherwise keep a core busy that the first one needs.
void wait(MPI_Request& request, const char* what) {
  auto pause = std::chrono::microseconds(50);
  for (;;) {
    int done = 0;
    check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), what);
    if (done) return;
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(20000));
  }
}

// MPI counts bytes in int: one exchange stays under 2 GiB.
int byteCount(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT_MAX)) {
    throw Error("MPI: a message of " + std::to_string(bytes) + " bytes, beyond MPI's 2 GiB");
  }
  return static_cast<int>(bytes);
}

// Where each part starts in the parts laid end to end, and (last) their total.
std::vector<int> offsetsOf(const std::vector<int>& counts) {
  std::vector<int> offsets{0};
  std::size_t total = 0;
  for (const int count : counts) {
    total += static_cast<std::size_t>(count);
    offsets.push_back(byteCount(total));
  }
  return offsets;
}

std::vector<dist::Bytes> split(const dist::Bytes& joined, const std::vector<int>& counts,
                               const std::vector<int>& offsets) {
  std::vector<dist::Bytes> parts(counts.size());
  for (std::size_t r = 0; r < counts.size(); ++r) {
    parts[r].assign(joined.begin() + offsets[r], joined.begin() + offsets[r] + counts[r]);
  }
  return parts;
}

class MpiGroup final : public dist::Group {
 public:
  MpiGroup() {
    check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  std::vector<dist::Bytes> allToAll(const std::vector<dist::Bytes>& to_each) const override {
    if (to_each.size() != static_cast<std::size_t>(size_))
      throw Error("MPI: a message for each rank is needed");
    std::vector<int> send_counts;
    for (const dist::Bytes& part : to_each) send_counts.push_back(byteCount(part.size()));
    const std::vector<int> send_offsets = offsetsOf(send_counts);
    dist::Bytes joined;
    for (const dist::Bytes& part : to_each) joined.insert(joined.end(), part.begin(), part.end());
    std::vector<int> receive_counts(to_each.size());
    MPI_Request request;
    check(MPI_Ialltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, MPI_COMM_WORLD,
                        &request),
          "MPI_Ialltoall");
    wait(request, "MPI_Ialltoall");
    const std::vector<int> receive_offsets = offsetsOf(receive_counts);
    dist::Bytes incoming(static_cast<std::size_t>(receive_offsets.back()));
    check(MPI_Ialltoallv(joined.data(), send_counts.data(), send_offsets.data(), MPI_BYTE, incoming.data(),
                         receive_counts.data(), receive_offsets.data(), MPI_BYTE, MPI_COMM_WORLD, &request),
          "MPI_Ialltoallv");
    wait(request, "MPI_Ialltoallv");
    return split(incoming, receive_counts, receive_offsets);
  }

  std::vector<dist::Bytes> allGather(const dist::Bytes& mine) const override {
    const int count = byteCount(mine.size());
    std::vector<int> counts(static_cast<std::size_t>(size_));
    MPI_Request request;
    check(MPI_Iallgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD, &request),
          "MPI_Iallgather");
    wait(request, "MPI_Iallgather");
    const std::vector<int> offsets = offsetsOf(counts);
    dist::Bytes joined(static_cast<std::size_t>(offsets.back()));
    check(MPI_Iallgatherv(mine.data(), count, MPI_BYTE, joined.data(), counts.data(), offsets.data(),
                          MPI_BYTE, MPI_COMM_WORLD, &request),
          "MPI_Iallgatherv");
    wait(request, "MPI_Iallgatherv");
    return split(joined, counts, offsets);
  }

 private:
  int rank_ = 0;
  int size_ = 1;
};

std::unique_ptr<MpiGroup> world;

}  // namespace

const dist::Group& startProcessGroup(int& argc, char**& argv) {
  if (world || !startedByALauncher()) return processGroup();
  // Only the main thread calls MPI (the windows' threads never do).
  int provided = 0;
  check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  world = std::make_unique<MpiGroup>();
  return *world;
}

const dist::Group& processGroup() {
  return world ? static_cast<const dist::Group&>(*world) : dist::singleProcess();
}

int endProcessGroup(int code) {
  if (!world) return code;
  if (code != 0 && world->size() > 1) MPI_Abort(MPI_COMM_WORLD, code);
  world.reset();
  MPI_Finalize();
  return code;
}

}  // namespace hba::cli
