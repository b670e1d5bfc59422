// The lane kernels of the step stages (transfer_lanes.hpp) compiled for AVX2
// (cxx/CMakeLists.txt adds -mavx2 to this file alone; no FMA, -ffp-contract=off as
// everywhere): the same bits as the baseline build. The stage files call these only
// where lanes_use_avx2() (constitution.cpp) says the CPU has AVX2.
#include "transfer/stencil27_lanes.hpp"
#include "transfer/transfer_lanes.hpp"

namespace mpm3d {

int bin_range_avx2(const StepContext* c, int lo, int hi, int* patch_of) {
  return bin_range<VectorLane<kLanes>>(c, lo, hi, patch_of);
}

void p2g_patch_avx2(const StepContext* c, int q, bool with_mass_mom, bool with_forces) {
  p2g_patch<VectorLane<kLanes>>(c, CellDecoder(c), q, with_mass_mom, with_forces);
}

void g2p_patch_avx2(StepContext* c, int q, bool remap) {
  g2p_patch<VectorLane<kLanes>>(c, CellDecoder(c), q, remap);
}

void stress_list_avx2(StepContext* c, const int* list, int count, const double* gvel,
                      const StressBlockArgs& args) {
  stress_list<VectorLane<kLanes>>(c, CellDecoder(c), list, count, gvel, args);
}

void stencil27_block_avx2(const StepContext* c, const int* part, int n, bool gradients, Stencil27Block& s) {
  stencil27_block<VectorLane<kStencilLanes>>(c, part, n, gradients, s);
}

void g2p27_block_avx2(StepContext* c, const Stencil27Block& s, const int* part, int n, const int* of) {
  g2p27_block<VectorLane<kStencilLanes>>(c, s, part, n, of);
}

void gradient27_block_avx2(const StepContext* c, const Stencil27Block& s, int n, const double* gvel, const int* of,
                           double L[9][kStencilLanes]) {
  gradient27_block<VectorLane<kStencilLanes>>(c, s, n, gvel, of, L);
}

}  // namespace mpm3d
