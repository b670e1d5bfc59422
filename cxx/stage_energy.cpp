// The energy stage: kinetic and internal energy, momentum and the rate of the external work
// bound of all particles, as one column of partial sums per patch (and one for the particles
// outside the grid), folded in column order.
#include <cmath>
#include <cstddef>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "patch_loops.hpp"
#include "update_step.hpp"

using namespace mpm3d;

namespace {

// Adds particle p to one column's sums: m |v|^2 / 2, e, m v (3) and, with body forces
// (kWork), |f . v| with f = m g + f_ext (neither ramped nor damped): the rate of the health
// check's bound of the external work (Simulation::external_work), per particle in absolute
// value so that forces changing sign (vibrations, manufactured solutions) do not cancel out.
template <bool kWork>
inline void add_particle(const StepContext* c, int p, double part[kReduceFields]) {
  const double m = c->mass[p];
  const double* vp = c->v + 3 * size_t(p);
  part[0] += (0.5 * m) * ((vp[0] * vp[0] + vp[1] * vp[1]) + vp[2] * vp[2]);
  part[1] += c->ie[p];
  part[2] += m * vp[0];
  part[3] += m * vp[1];
  part[4] += m * vp[2];
  if (kWork) {
    const double* g = c->gravity + 3 * size_t(c->body[p]);
    double pw = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double f = m * g[a] + (c->fext ? c->fext[3 * size_t(p) + a] : 0.0);
      pw += f * vp[a];
    }
    part[5] += std::fabs(pw);
  }
}

// Adds the particles of patch q's list in s (c's or, with contact, component 2's).
template <bool kWork>
inline void add_list(const StepContext* c, const StepContext* s, int q, double part[kReduceFields]) {
  for (int i = s->patch_start[q]; i < s->patch_start[q + 1]; ++i) add_particle<kWork>(c, s->patch_part[i], part);
}

// Every column of c->partials: column q < npatch sums patch q's list, then (contact)
// component 2's list of the same patch; column npatch the particles outside the grid in
// ascending index (one pass over the cells, only when there are any). Each column is one
// serial sum, whichever thread computes it; each thread takes its run of patches
// (thread_patches: the particles it updated in the stress stage).
template <bool kWork>
void compute_columns(StepContext* c) {
  const int npatch = c->npatch;
  const StepContext* c2 = c->other;
  const bool any_outside = c->noutside + (c2 ? c2->noutside : 0) > 0;
#pragma omp parallel
  {
    int t = 0, T = 1;
#ifdef _OPENMP
    t = omp_get_thread_num();
    T = omp_get_num_threads();
#endif
    int lo, hi;
    thread_patches(c, t, T, lo, hi);
    for (int q = lo; q < hi; ++q) {
      double part[kReduceFields] = {0, 0, 0, 0, 0, 0};
      add_list<kWork>(c, c, q, part);
      if (c2) add_list<kWork>(c, c2, q, part);
      for (int f = 0; f < kReduceFields; ++f) c->partials[size_t(kReduceFields) * q + f] = part[f];
    }
    if (t == T - 1) {
      double part[kReduceFields] = {0, 0, 0, 0, 0, 0};
      if (any_outside)  // the cell array is shared by both contact components
        for (int p = 0; p < c->np; ++p)
          if (c->cell[p] < 0) add_particle<kWork>(c, p, part);
      for (int f = 0; f < kReduceFields; ++f) c->partials[size_t(kReduceFields) * npatch + f] = part[f];
    }
  }
}

}  // namespace

// result[0..4] = sum_p (m_p |v_p|^2 / 2, e_p, m_p v_p), result[8] = sum_p |f_p . v_p| (0
// without body forces). All npatch + 1 columns are computed first and then folded, every
// column, empty or not, in column order: ((0.0 + col 0) + col 1) + ... + col npatch. The
// columns depend on the patch lists only, so the sums are the same for any thread count and
// (folding gathered columns) for any split of the patches among ranks.
extern "C" void mpm3d_cxx_energy(StepContext* c) {
  if (c->has_body_force)
    compute_columns<true>(c);
  else
    compute_columns<false>(c);
  if (c->exchange) c->exchange(c, EXCHANGE_PARTIALS, 0, 0);  // other ranks' columns
  double sum[kReduceFields] = {0, 0, 0, 0, 0, 0};
  for (int q = 0; q <= c->npatch; ++q)
    for (int f = 0; f < kReduceFields; ++f) sum[f] += c->partials[size_t(kReduceFields) * q + f];
  for (int f = 0; f < 5; ++f) c->result[f] = sum[f];
  c->result[8] = sum[5];
}
