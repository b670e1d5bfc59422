// MPM3D (the original's main program): the simulation (simulation.hpp) and its time loop
// (time_loop.hpp); the one include of the library for the bindings, the programs and the
// tests. The command line (run_main) is the program's: app/cli.hpp.
#pragma once
#include "solver/simulation.hpp"
#include "solver/time_loop.hpp"
