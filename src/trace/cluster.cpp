// MPI behind Cluster. Without CAUSTICA_MPI every collective is the identity of one process.
#include "trace/cluster.h"
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <type_traits>
#include <utility>
#ifdef CAUSTICA_MPI
#include <mpi.h>
#endif

namespace caustica {
namespace {

Cluster g_world;

#ifdef CAUSTICA_MPI
// Whether an MPI launcher started this process. Open MPI's singleton start-up (MPI_Init without
// mpirun) spawns a daemon and can stall in containers, so a lone process never calls MPI_Init.
bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(v)) return true;
  }
  return false;
}

// Element-wise sum of 128-bit integers, each sent as two 64-bit words.
void add_fixed(void* in, void* inout, int* len, MPI_Datatype*) {
  for (int i = 0; i < *len; ++i) {
    FixedSum a, b;
    std::memcpy(&a, static_cast<const char*>(in) + size_t(i) * sizeof(FixedSum), sizeof a);
    std::memcpy(&b, static_cast<char*>(inout) + size_t(i) * sizeof(FixedSum), sizeof b);
    add_saturating(b, a);
    std::memcpy(static_cast<char*>(inout) + size_t(i) * sizeof(FixedSum), &b, sizeof b);
  }
}

// MPI counts are ints: large images go in slices.
constexpr size_t kSlice = size_t(1) << 22;

template <class T>
void reduce_sum(std::vector<T>& values, MPI_Datatype type, MPI_Op op, bool root) {
  for (size_t first = 0; first < values.size(); first += kSlice) {
    const int count = int(std::min(kSlice, values.size() - first));
    void* data = values.data() + first;
    if (root) {
      MPI_Reduce(MPI_IN_PLACE, data, count, type, op, 0, MPI_COMM_WORLD);
    } else {
      MPI_Reduce(data, nullptr, count, type, op, 0, MPI_COMM_WORLD);
    }
  }
}
#endif

}  // namespace

void Cluster::init(int& argc, char**& argv) {
#ifdef CAUSTICA_MPI
  if (!launched_by_mpi()) return;
  int provided = 0;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    std::cerr << "error: MPI_Init_thread failed\n";
    std::exit(1);
  }
  if (provided < MPI_THREAD_FUNNELED) {
    std::cerr << "error: this MPI library does not support threads (MPI_THREAD_FUNNELED)\n";
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  // Errors end the job rather than leave ranks waiting in a collective.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_ARE_FATAL);
  g_world.joined_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_world.rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &g_world.size_);
  // The ranks sharing this machine's memory (and cores).
  MPI_Comm local;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, g_world.rank_, MPI_INFO_NULL, &local);
  MPI_Comm_size(local, &g_world.local_size_);
  MPI_Comm_free(&local);
#else
  (void)argc;
  (void)argv;
  // Started by a launcher of several processes without MPI support: each renders the whole
  // image by itself. Rank 0 says so.
  for (const auto& [size, rank] : {std::pair{"OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_RANK"},
                                   std::pair{"PMI_SIZE", "PMI_RANK"}, std::pair{"SLURM_NTASKS", "SLURM_PROCID"}}) {
    const char* n = std::getenv(size);
    const char* r = std::getenv(rank);
    if (n && r && std::atoi(n) > 1 && std::atoi(r) == 0) {
      std::cerr << "warning: started as one of " << n << " MPI processes, but this caustica was built without MPI "
                << "(CAUSTICA_MPI off): every process renders the whole image by itself\n";
    }
  }
#endif
}

void Cluster::finalize() {
#ifdef CAUSTICA_MPI
  if (g_world.joined_) MPI_Finalize();
  g_world.joined_ = false;
#endif
}

const Cluster& Cluster::world() { return g_world; }

bool Cluster::built_with_mpi() {
#ifdef CAUSTICA_MPI
  return true;
#else
  return false;
#endif
}

std::string Cluster::describe_rank() const {
  return "rank " + std::to_string(rank_) + " of " + std::to_string(size_);
}

bool Cluster::any(bool flag) const {
#ifdef CAUSTICA_MPI
  if (distributed()) {
    int in = flag ? 1 : 0, out = 0;
    MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
    return out != 0;
  }
#endif
  return flag;
}

bool Cluster::same_everywhere(uint64_t value) const {
#ifdef CAUSTICA_MPI
  if (distributed()) {
    unsigned long long lo = value, hi = value;
    MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_UNSIGNED_LONG_LONG, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_UNSIGNED_LONG_LONG, MPI_MAX, MPI_COMM_WORLD);
    return lo == hi;
  }
#endif
  (void)value;
  return true;
}

void Cluster::sum_to_root(std::vector<FixedSum>& values) const {
#ifdef CAUSTICA_MPI
  if (!distributed()) return;
  MPI_Datatype pair;
  MPI_Type_contiguous(2, MPI_UINT64_T, &pair);
  MPI_Type_commit(&pair);
  MPI_Op op;
  MPI_Op_create(&add_fixed, /*commute=*/1, &op);
  reduce_sum(values, pair, op, root());
  MPI_Op_free(&op);
  MPI_Type_free(&pair);
#else
  (void)values;
#endif
}

// Element-wise MPI_SUM of a vector of int or uint64_t, to rank 0.
template <class T>
static void sum_integers(const Cluster& cluster, std::vector<T>& values) {
  static_assert(std::is_same_v<T, int> || std::is_same_v<T, uint64_t>);
#ifdef CAUSTICA_MPI
  const MPI_Datatype type = std::is_same_v<T, int> ? MPI_INT : MPI_UINT64_T;
  if (cluster.distributed()) reduce_sum(values, type, MPI_SUM, cluster.root());
#else
  (void)cluster;
  (void)values;
#endif
}

void Cluster::sum_to_root(std::vector<int>& values) const { sum_integers(*this, values); }
void Cluster::sum_to_root(std::vector<uint64_t>& values) const { sum_integers(*this, values); }

void Cluster::barrier() const {
#ifdef CAUSTICA_MPI
  if (distributed()) MPI_Barrier(MPI_COMM_WORLD);
#endif
}

void Cluster::abort(int code) const {
#ifdef CAUSTICA_MPI
  if (joined_ && distributed()) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

}  // namespace caustica
