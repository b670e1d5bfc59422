#include "app/cli.hpp"

int main(int argc, char** argv) {
#ifdef MPM3D_HAVE_MPI
  return mpm3d::run_main_mpi(argc, argv);
#else
  return mpm3d::run_main(argc, argv);
#endif
}
