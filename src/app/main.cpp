// caustica: entry point. Under mpirun or srun the process joins the MPI job first.
#include "app/cli.h"
#include "trace/cluster.h"

int main(int argc, char** argv) {
  caustica::Cluster::init(argc, argv);
  const int code = caustica::run_cli(argc, argv);
  caustica::Cluster::finalize();
  return code;
}
