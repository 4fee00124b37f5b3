// The processes that render one image together: MPI ranks under mpirun or srun, or one process
// alone. Built without MPI (CAUSTICA_MPI off) or started without a launcher, every call is the
// single-process case. Only the main thread calls these (MPI_THREAD_FUNNELED).
#pragma once
#include <cstdint>
#include <string>
#include <vector>
#include "core/fixed_sum.h"

namespace caustica {

class Cluster {
 public:
  // Joins the MPI job when an MPI launcher started this process (Open MPI's mpirun, or a
  // PMI/PMIx launcher such as srun); otherwise the process stays alone and MPI is not touched.
  static void init(int& argc, char**& argv);
  // Leaves the job (MPI_Finalize); call once before main returns.
  static void finalize();
  // The cluster this process belongs to (alone until init joined a job).
  static const Cluster& world();
  // Whether this executable was built with MPI.
  static bool built_with_mpi();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  bool distributed() const { return size_ > 1; }
  // Processes of this job on this machine (for the default thread count), at least 1.
  int local_size() const { return local_size_; }
  // "rank 1 of 4", for messages.
  std::string describe_rank() const;

  // Collective calls: every rank makes them, in the same order.
  // True on every rank when `flag` is true on any.
  bool any(bool flag) const;
  // True when `value` is the same on every rank.
  bool same_everywhere(uint64_t value) const;
  // Element-wise sums over the ranks, left in rank 0's vector (the others' are unspecified).
  // Integer sums: the result does not depend on the order in which MPI adds the ranks.
  void sum_to_root(std::vector<FixedSum>& values) const;
  void sum_to_root(std::vector<int>& values) const;
  void sum_to_root(std::vector<uint64_t>& values) const;
  // Returns on every rank once all have called it.
  void barrier() const;
  // Ends the whole job at once (MPI_Abort) with `code`; alone, exits the process with it.
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1, local_size_ = 1;
  bool joined_ = false;
};

}  // namespace caustica
