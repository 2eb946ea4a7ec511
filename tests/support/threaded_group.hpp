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
  explicit ThreadedGroups(int size) : sent_(static_cast<std::size_t>(size)) {
    for (int rank = 0; rank < size; ++rank) members_.emplace_back(*this, rank);
  }
  const dist::Group& member(int rank) const { return members_[static_cast<std::size_t>(rank)]; }
  int size() const { return static_cast<int>(sent_.size()); }

 private:
  class Member final : public dist::Group {
   public:
    Member(ThreadedGroups& all, int rank) : all_(all), rank_(rank) {}
    int rank() const override { return rank_; }
    int size() const override { return all_.size(); }
    std::vector<dist::Bytes> allGather(const dist::Bytes& mine) const override {
      return all_.exchange(rank_, std::vector<dist::Bytes>(static_cast<std::size_t>(all_.size()), mine));
    }
    std::vector<dist::Bytes> allToAll(const std::vector<dist::Bytes>& to_each) const override {
      return all_.exchange(rank_, to_each);
    }

   private:
    ThreadedGroups& all_;
    int rank_;
  };

  // Member `rank` sends to_each[r] to member r and gets what each sent it.
  // Waits until every member has sent; the last to arrive publishes them.
  std::vector<dist::Bytes> exchange(int rank, const std::vector<dist::Bytes>& to_each) {
    std::unique_lock<std::mutex> lock(mutex_);
    const long generation = generation_;
    sent_[static_cast<std::size_t>(rank)] = to_each;
    if (++arrived_ == size()) {
      published_ = sent_;
      arrived_ = 0;
      ++generation_;
      done_.notify_all();
    } else {
      done_.wait(lock, [&] { return generation_ != generation; });
    }
    // Stays until every member has taken its part: none can send again before.
    std::vector<dist::Bytes> received;
    for (const std::vector<dist::Bytes>& from : published_)
      received.push_back(from.at(static_cast<std::size_t>(rank)));
    return received;
  }

  std::vector<Member> members_;
  std::mutex mutex_;
  std::condition_variable done_;
  std::vector<std::vector<dist::Bytes>> sent_, published_;  // [from][to]
  int arrived_ = 0;
  long generation_ = 0;
};

}  // namespace hba::test
