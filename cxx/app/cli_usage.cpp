// The text of `mpm3d --help`: the options, then the rules (core/rules.hpp). README's option
// block is checked against it (test docs).
#include <string>

#include "app/cli.hpp"
#include "core/rules.hpp"

namespace mpm3d {

namespace {

const char* const kOptions =
    "usage: mpm3d [options] DECK.mpm\n"
    "  --threads N        OpenMP threads (default: OMP_NUM_THREADS or all cores)\n"
    "  --team adaptive|fixed  adaptive (default): each step runs on the threads or on one,\n"
    "                     whichever the run measures faster (small decks, busy machines);\n"
    "                     fixed: every step on all of them. The bits are the same.\n"
    "  --steps N          stop after N steps\n"
    "  --end-time T       stop at time T instead of the deck's end time\n"
    "  --out-dir DIR      where result files go, created if missing (default: the current\n"
    "                     directory)\n"
    "  --no-output        no animation, curve or log files\n"
    "  --summary F.json   write a summary of the run\n"
    "  --state F.h5       write the final particle state (HDF5)\n"
    "  --patch-cells N    cells per patch edge of the grid decomposition (default 4)\n"
    "  --rebalance-above R  under mpirun: redraw the ranks' patch runs before a step when\n"
    "                     the largest particle share exceeds R times the mean (default 1.03)\n"
    "  --regrid-every N   adaptive background grid: redefine the grid from the particles'\n"
    "                     extent every N steps (0: off; default: the deck's 'adgr', else off)\n"
    "  --rules ours|original|book|current  where mpm3d differs from the original programs:\n"
    "                     ours (default) our rules; original: the rules of the program the\n"
    "                     deck's keywords name (current for decks with a keyword of the current\n"
    "                     version: neoh, UVFp, vsin, QuLo, Damp, smoo, bimp, sgmp, TLmp, drda,\n"
    "                     blod, cicl, ksin, nuli; else book); book, current: that program's\n"
    "                     rules whatever the deck's keywords (the rules are listed below)\n"
    "  --rule NAME=VALUE  set one rule, after --rules (repeatable)\n"
    "  --time-step book|current  the same as --rule time_step=...: book keeps the initial dt\n"
    "                     for the whole run; current recomputes dt after every step from the\n"
    "                     wave speed plus the largest particle velocity (default: the\n"
    "                     program's, see --rules)\n"
    "  --particle-order blocks|deck  storage order of the particles (default blocks: sorted by\n"
    "                     patch-sized blocks of cells, so each thread's patches hold a run of\n"
    "                     memory; deck: as read). Outputs are in deck order either way\n"
    "  --hdf5             write the animation as an HDF5 + XDMF series (name_anim.h5/.xdmf)\n"
    "  --vtu-binary       the ParaView files (para: name_anim_<k>.vtu, name_Grid.vtu) as\n"
    "                     appended raw binary instead of ASCII: the same fields, exact values\n"
    "  --checkpoint F.h5  write a checkpoint when the run ends (and every N steps, below)\n"
    "  --checkpoint-every N   also write it every N steps (default file name_checkpoint.h5)\n"
    "  --restart F.h5     continue the run of the same deck from a checkpoint\n"
    "  --kernel cxx|fortran       take every step stage from one language\n"
    "  --kernels STAGE=LANG,...   take single stages from a language (see --list-stages)\n"
    "  --list-stages      print the stage names, one per line\n"
    "  --no-rest-skip     compute the patches at rest too (the same results, slower;\n"
    "                     see docs/PERFORMANCE.md)\n"
    "  --strict-energy    stop (exit 3) at the first energy warning: a body's internal energy\n"
    "                     below -0.1% of the initial total energy plus the external work, or\n"
    "                     the kinetic energy above that total by more than 0.1%\n"
    "  --quiet            no progress lines\n"
    "  --help, --version\n";

}  // namespace

std::string usage_text() {
  return std::string(kOptions) + "rules (--rule NAME=VALUE; the first value is ours):\n" + rules_usage();
}

}  // namespace mpm3d
