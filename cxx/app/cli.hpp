// The program's command line (cli.cpp), linked into the mpm3d program only:
// the library (mpm3d.hpp) keeps what the C API, the Fortran bindings and the programs share.
#pragma once
#include <string>

namespace mpm3d {

class Ranks;

// Command-line driver (used by main): returns the process exit code. ranks: the other
// processes of a distributed run (solver/ranks.hpp, implemented in cxx/parallel/), or null.
int run_main(int argc, char** argv, Ranks* ranks = nullptr);
// The text of --help: the options and the rules (app/cli_usage.cpp).
std::string usage_text();
// The program's entry with MPI (mpi_main.cpp, built with MPM3D_MPI): run_main on every
// rank when started by mpirun, else run_main alone (MPI never initialised).
int run_main_mpi(int argc, char** argv);

}  // namespace mpm3d
