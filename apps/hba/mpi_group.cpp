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
    std::vector<int> send_counts(to_each.size()), send_offsets(to_each.size());
    long long sent = 0;
    for (std::size_t r = 0; r < to_each.size(); ++r) {
      send_offsets[r] = static_cast<int>(sent);
      sent += static_cast<long long>(to_each[r].size());
      send_counts[r] = static_cast<int>(to_each[r].size());
    }
    if (sent > INT_MAX)
      throw Error("MPI: rank " + std::to_string(rank_) + " would send " + std::to_string(sent) +
                  " bytes at once, beyond MPI's 2 GiB a message");
    dist::Bytes joined;
    joined.reserve(static_cast<std::size_t>(sent));
    for (const dist::Bytes& part : to_each) joined.insert(joined.end(), part.begin(), part.end());
    std::vector<int> receive_counts(to_each.size()), receive_offsets(to_each.size());
    MPI_Request request;
    check(MPI_Ialltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, MPI_COMM_WORLD,
                        &request),
          "MPI_Ialltoall");
    wait(request, "MPI_Ialltoall");
    long long received = 0;
    for (std::size_t r = 0; r < receive_counts.size(); ++r) {
      receive_offsets[r] = static_cast<int>(received);
      received += receive_counts[r];
    }
    if (received > INT_MAX)
      throw Error("MPI: an exchange of " + std::to_string(received) + " bytes, beyond 2 GiB");
    dist::Bytes incoming(static_cast<std::size_t>(received));
    check(MPI_Ialltoallv(joined.data(), send_counts.data(), send_offsets.data(), MPI_BYTE, incoming.data(),
                         receive_counts.data(), receive_offsets.data(), MPI_BYTE, MPI_COMM_WORLD, &request),
          "MPI_Ialltoallv");
    wait(request, "MPI_Ialltoallv");
    std::vector<dist::Bytes> from_each(receive_counts.size());
    for (std::size_t r = 0; r < receive_counts.size(); ++r) {
      from_each[r].assign(incoming.begin() + receive_offsets[r],
                          incoming.begin() + receive_offsets[r] + receive_counts[r]);
    }
    return from_each;
  }

  std::vector<dist::Bytes> allGather(const dist::Bytes& mine) const override {
    if (mine.size() > static_cast<std::size_t>(INT_MAX)) {
      throw Error("MPI: rank " + std::to_string(rank_) + " would send " + std::to_string(mine.size()) +
                  " bytes at once, beyond MPI's 2 GiB a message");
    }
    const int count = static_cast<int>(mine.size());
    std::vector<int> counts(static_cast<std::size_t>(size_));
    MPI_Request request;
    check(MPI_Iallgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD, &request),
          "MPI_Iallgather");
    wait(request, "MPI_Iallgather");
    std::vector<int> offsets(counts.size());
    long long total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
      offsets[r] = static_cast<int>(total);
      total += counts[r];
    }
    if (total > INT_MAX) throw Error("MPI: an exchange of " + std::to_string(total) + " bytes, beyond 2 GiB");
    dist::Bytes joined(static_cast<std::size_t>(total));
    check(MPI_Iallgatherv(mine.data(), count, MPI_BYTE, joined.data(), counts.data(), offsets.data(),
                          MPI_BYTE, MPI_COMM_WORLD, &request),
          "MPI_Iallgatherv");
    wait(request, "MPI_Iallgatherv");
    std::vector<dist::Bytes> all(counts.size());
    for (std::size_t r = 0; r < counts.size(); ++r) {
      all[r].assign(joined.begin() + offsets[r], joined.begin() + offsets[r] + counts[r]);
    }
    return all;
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
