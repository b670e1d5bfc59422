// MPM3D (the original's main program): the simulation (simulation.hpp), its time loop
// (time_loop.hpp) and the command-line driver run_main (cli.cpp); the one include for the
// program, the bindings and the tests.
#pragma once
#include "solver/simulation.hpp"
#include "solver/time_loop.hpp"

namespace mpm3d {

// Command-line driver (used by main): returns the process exit code. ranks: the other
// processes of a distributed run (cxx/parallel/ranks.hpp), or null.
int run_main(int argc, char** argv, Ranks* ranks = nullptr);
// The program's entry with MPI (cxx/parallel/ranks_mpi.cpp, built with MPM3D_MPI): run_main on every
// rank when started by mpirun, else run_main alone (MPI never initialised).
int run_main_mpi(int argc, char** argv);

// JSON text of the summary files: a string's content (quotes and backslashes escaped,
// control characters as spaces) and a number (shortest round-trip form, null when not
// finite).
std::string json_escape(const std::string& s);
std::string json_number(double v);

}  // namespace mpm3d
