#pragma once
// The ranks of a distributed run as threads of one process: a stand-in for MPI's collective
// operations (petsc_plugin::Communicator), so that a unit test can compare what each rank of a
// distributed system computes with the whole system, without mpirun.
#include <barrier>
#include <functional>
#include <numeric>
#include <thread>
#include <vector>

#include "moreau/fem/petsc/petsc_plugin_api.hpp"

namespace moreau::test {

class ThreadRanks {
 public:
  explicit ThreadRanks(int size) : size_(size), sync_(size) {}

  /// Runs body(world) on every rank at once, each in its own thread, and waits for all of them.
  void run(const std::function<void(const petsc_plugin::Communicator&)>& body) {
    std::vector<Rank> ranks;
    ranks.reserve(static_cast<size_t>(size_));
    for (int r = 0; r < size_; ++r) ranks.emplace_back(*this, r);
    std::vector<std::jthread> threads;
    for (int r = 0; r < size_; ++r) threads.emplace_back([&, r] { body(ranks[r]); });
  }

 private:
  class Rank final : public petsc_plugin::Communicator {
   public:
    Rank(ThreadRanks& all, int rank) : all_(&all), rank_(rank) {}
    int rank() const override { return rank_; }
    int size() const override { return all_->size_; }
    // Rank 0 sizes the shared buffer, every rank writes its part, every rank reads the whole;
    // a barrier between the phases.
    void all_gather(const double* mine, const int* counts, double* all) const override {
      const int total = std::accumulate(counts, counts + all_->size_, 0);
      const int first = std::accumulate(counts, counts + rank_, 0);
      if (rank_ == 0) all_->buffer_.assign(static_cast<size_t>(total), 0.0);
      all_->sync_.arrive_and_wait();
      std::copy(mine, mine + counts[rank_], all_->buffer_.begin() + first);
      all_->sync_.arrive_and_wait();
      std::copy(all_->buffer_.begin(), all_->buffer_.end(), all);
      all_->sync_.arrive_and_wait();
    }
   private:
    ThreadRanks* all_;
    int rank_;
  };

  int size_;
  std::barrier<> sync_;
  std::vector<double> buffer_;
};

}  // namespace moreau::test
