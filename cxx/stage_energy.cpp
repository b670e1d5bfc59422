// The energy stage: kinetic and internal energy and momentum of all particles, from the
// partial sums of fixed particle blocks folded in block order.
#include "update_step.hpp"

using namespace mpm3d;

// result = sum_p (m_p |v_p|^2 / 2, e_p, m_p v_p): each block's partial sums in particle
// order, folded in block order, so the sums do not depend on the thread count.
extern "C" void mpm3d_cxx_energy(StepContext* c) {
  const int B = c->reduce_block;
  const int nblock = (c->np + B - 1) / B;
#pragma omp parallel for schedule(static)
  for (int blk = 0; blk < nblock; ++blk) {
    double part[kReduceFields] = {0, 0, 0, 0, 0};
    const int end = (blk + 1) * B < c->np ? (blk + 1) * B : c->np;
    for (int p = blk * B; p < end; ++p) {
      const double m = c->mass[p];
      const double* vp = c->v + 3 * p;
      part[0] += (0.5 * m) * ((vp[0] * vp[0] + vp[1] * vp[1]) + vp[2] * vp[2]);
      part[1] += c->ie[p];
      part[2] += m * vp[0];
      part[3] += m * vp[1];
      part[4] += m * vp[2];
    }
    for (int f = 0; f < kReduceFields; ++f) c->partials[kReduceFields * blk + f] = part[f];
  }
  // Fixed-order fold of the block partials: the same sums for any thread count.
  for (int f = 0; f < kReduceFields; ++f) {
    double s = 0.0;
    for (int blk = 0; blk < nblock; ++blk) s += c->partials[kReduceFields * blk + f];
    c->result[f] = s;
  }
}
