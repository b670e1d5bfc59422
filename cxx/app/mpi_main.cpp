// The program's MPI entry run_main_mpi: starts MPI only under mpirun and runs the program
// with the ranks (MpiRanks, mpi_ranks.hpp). Linked into the mpm3d program only when CMake
// finds MPI (MPM3D_MPI).
#include <cstdlib>
#include <iostream>

#include "app/cli.hpp"
#include "parallel/mpi_ranks.hpp"

namespace mpm3d {
namespace {

// Launched by mpirun (Open MPI's or another's environment): the caller starts MPI only then,
// so that a plain `mpm3d deck` never initialises it.
bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

}  // namespace

int run_main_mpi(int argc, char** argv) {
  if (!launched_by_mpirun()) return run_main(argc, argv, nullptr);
  int provided = 0;
  // The stages call MPI between their parallel regions, from the master thread only.
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    std::cerr << "mpm3d: MPI_Init_thread failed\n";
    return 1;
  }
  int rc = 0;
  {
    MpiRanks ranks(MPI_COMM_WORLD);
    rc = run_main(argc, argv, ranks.size() > 1 ? &ranks : nullptr);
    // Every rank returns the same status (deck errors, refusals and health errors are
    // reached by all of them); the root's is the run's.
    check(MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD), "status");
  }
  MPI_Finalize();
  return rc;
}

}  // namespace mpm3d
