#pragma once
// The members of a dist::Group as threads of this process: what mpirun's
// processes do, without MPI, so that any build tests the spreading.
#include <condition_variable>
#include <mutex>
#include <vector>

#include "hba/dist/group.hpp"

namespace hba::test {

class ThreadedGroups {
 public:
  explicit ThreadedGroups(int size) : slots_(static_cast<std::size_t>(size)) {
    for (int rank = 0; rank < size; ++rank) members_.emplace_back(*this, rank);
  }
  const dist::Group& member(int rank) const { return members_[static_cast<std::size_t>(rank)]; }
  int size() const { return static_cast<int>(slots_.size()); }

 private:
  class Member final : public dist::Group {
   public:
    Member(ThreadedGroups& all, int rank) : all_(all), rank_(rank) {}
    int rank() const override { return rank_; }
    int size() const override { return all_.size(); }
    std::vector<dist::Bytes> allGather(const dist::Bytes& mine) const override {
      return all_.gather(rank_, mine);
    }

   private:
    ThreadedGroups& all_;
    int rank_;
  };

  // Waits until every member has sent; the last to arrive publishes them.
  std::vector<dist::Bytes> gather(int rank, const dist::Bytes& mine) {
    std::unique_lock<std::mutex> lock(mutex_);
    const long generation = generation_;
    slots_[static_cast<std::size_t>(rank)] = mine;
    if (++arrived_ == size()) {
      gathered_ = slots_;
      arrived_ = 0;
      ++generation_;
      done_.notify_all();
    } else {
      done_.wait(lock, [&] { return generation_ != generation; });
    }
    return gathered_;  // stays until every member has taken it: none can gather again before
  }

  std::vector<Member> members_;
  std::mutex mutex_;
  std::condition_variable done_;
  std::vector<dist::Bytes> slots_, gathered_;
  int arrived_ = 0;
  long generation_ = 0;
};

}  // namespace hba::test
