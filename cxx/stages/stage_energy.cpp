// The energy stage: kinetic and internal energy, momentum and the rate of the external work
// bound of all particles, as one column of partial sums per patch (and one for the particles
// outside the grid), folded in column order.
#include <cmath>
#include <cstddef>

#include "core/lanes.hpp"
#include "core/patch_loops.hpp"
#include "stages/update_step.hpp"

using namespace mpm3d;

namespace {

// Particles per lane group of the column loops: their products are formed side by side,
// their sums still one particle after the other.
constexpr int kEnergyLanes = 2;
// List entries ahead whose particle data the column loops prefetch. The lists skip the
// particles that left their patch, and the hardware prefetchers lose the stream at the gaps:
// without it the stage took twice as long on taylor_coarse (300 steps, docs/PERFORMANCE.md).
constexpr int kPrefetchAhead = 96;

// One column's running sums: m |v|^2 / 2, e, m v (3), |f . v|, f . v.
struct Sums {
  double f[kReduceFields] = {0, 0, 0, 0, 0, 0, 0};
};

// Adds the particles p[0 .. L::W-1] (in this order) to s: m |v|^2 / 2, e, m v (3) and,
// with body forces (kWork), |f . v| with f = m g + f_ext (neither ramped nor damped): the
// rate of the health check's bound of the external work (Simulation::external_work), per
// particle in absolute value so that forces changing sign (vibrations, manufactured
// solutions) do not cancel out; and f . v with the point loads ramped as P2G applies them
// (QuLo), the rate of the work of gravity and loads (Simulation::load_work). Each lane
// performs the scalar operations (lanes.hpp).
template <bool kWork, class L>
inline void add_particles(const StepContext* c, const int* p, Sums& s) {
  int i3[L::W];
  for (int k = 0; k < L::W; ++k) i3[k] = 3 * p[k];
  const auto m = L::gather(c->part.mass, p);
  const auto vx = L::gather(c->part.v, i3), vy = L::gather(c->part.v + 1, i3), vz = L::gather(c->part.v + 2, i3);
  const auto ke = (0.5 * m) * ((vx * vx + vy * vy) + vz * vz);
  const auto e = L::gather(c->part.ie, p);
  const auto mx = m * vx, my = m * vy, mz = m * vz;
  decltype(L::splat(0.0)) work = L::splat(0.0), signed_work = L::splat(0.0);
  if (kWork) {
    int g3[L::W];
    for (int k = 0; k < L::W; ++k) g3[k] = 3 * c->part.body[p[k]];
    const double* fext = c->part.fext;
    const auto zero = L::splat(0.0);
    const auto fx = m * L::gather(c->part.gravity, g3) + (fext ? L::gather(fext, i3) : zero);
    const auto fy = m * L::gather(c->part.gravity + 1, g3) + (fext ? L::gather(fext + 1, i3) : zero);
    const auto fz = m * L::gather(c->part.gravity + 2, g3) + (fext ? L::gather(fext + 2, i3) : zero);
    const auto pw = ((zero + fx * vx) + fy * vy) + fz * vz;
    for (int k = 0; k < L::W; ++k) L::set(work, k, std::fabs(L::get(pw, k)));
    signed_work = pw;
    const double T = c->method.load_ramp_time, t = c->clock.time;
    if (fext && T > 0.0 && t < T) {  // QuLo: (f_ext / T) t, as transfer_common.hpp's body force
      const auto rx = m * L::gather(c->part.gravity, g3) + (L::gather(fext, i3) / T) * t;
      const auto ry = m * L::gather(c->part.gravity + 1, g3) + (L::gather(fext + 1, i3) / T) * t;
      const auto rz = m * L::gather(c->part.gravity + 2, g3) + (L::gather(fext + 2, i3) / T) * t;
      signed_work = ((zero + rx * vx) + ry * vy) + rz * vz;
    }
  }
  for (int k = 0; k < L::W; ++k) {
    s.f[0] += L::get(ke, k);
    s.f[1] += L::get(e, k);
    s.f[2] += L::get(mx, k);
    s.f[3] += L::get(my, k);
    s.f[4] += L::get(mz, k);
    if (kWork) s.f[5] += L::get(work, k);
    if (kWork) s.f[6] += L::get(signed_work, k);
  }
}

// Adds the particles list[0 .. n-1], in this order, to s; prefetches the data of the entry
// kPrefetchAhead places ahead (while that is before list_end, the end of all lists).
template <bool kWork>
inline void add_list(const StepContext* c, const int* list, int n, const int* list_end, Sums& s) {
  typedef VectorLane<kEnergyLanes> VL;
  int i = 0;
  for (; i + kEnergyLanes <= n; i += kEnergyLanes) {
    if (kPrefetchAhead > 0 && list + i + kPrefetchAhead + 1 < list_end) {
      const int a = list[i + kPrefetchAhead], b = list[i + kPrefetchAhead + 1];
      __builtin_prefetch(c->part.v + 3 * size_t(a));
      __builtin_prefetch(c->part.v + 3 * size_t(b) + 2);
      __builtin_prefetch(c->part.mass + a);
      __builtin_prefetch(c->part.ie + a);
    }
    add_particles<kWork, VL>(c, list + i, s);
  }
  for (; i < n; ++i) add_particles<kWork, ScalarLane>(c, list + i, s);
}

// Every column of c->out.partials: column q < npatch sums patch q's list, then (contact)
// component 2's list of the same patch; column npatch the particles outside the grid in
// ascending index (c->ranks.order's, when set; one pass over the cells, only when there are any). Each column is one
// serial sum, whichever thread computes it; each thread takes its run of patches
// (for_patches: the particles it updated in the stress stage).
template <bool kWork>
void compute_columns(StepContext* c) {
  const int npatch = c->patch.npatch;
  const StepContext* c2 = c->contact.other;
  const bool any_outside = c->out.noutside + (c2 ? c2->out.noutside : 0) > 0;
  const int* end1 = c->patch.patch_part + c->patch.patch_start[npatch];
  for_patches(c, [&](int q) {
    Sums s;
    add_list<kWork>(c, c->patch.patch_part + c->patch.patch_start[q], c->patch.patch_start[q + 1] - c->patch.patch_start[q], end1, s);
    if (c2)
      add_list<kWork>(c, c2->patch.patch_part + c2->patch.patch_start[q], c2->patch.patch_start[q + 1] - c2->patch.patch_start[q],
                      c2->patch.patch_part + c2->patch.patch_start[npatch], s);
    for (int f = 0; f < kReduceFields; ++f) c->out.partials[size_t(kReduceFields) * q + f] = s.f[f];
  });
  Sums s;
  if (any_outside)  // the cell array is shared by both contact components
    for (int i = 0; i < c->part.np; ++i) {
      const int p = c->ranks.order ? c->ranks.order[i] : i;
      if (c->part.cell[p] < 0) add_particles<kWork, ScalarLane>(c, &p, s);
    }
  for (int f = 0; f < kReduceFields; ++f) c->out.partials[size_t(kReduceFields) * npatch + f] = s.f[f];
}

}  // namespace

// result[0..4] = sum_p (m_p |v_p|^2 / 2, e_p, m_p v_p), result[8] = sum_p |f_p . v_p| and
// result[9] = sum_p f_p . v_p (0 without body forces). All npatch + 1 columns are computed first and then folded, every
// column, empty or not, in column order: ((0.0 + col 0) + col 1) + ... + col npatch. The
// columns depend on the patch lists only, so the sums are the same for any thread count and
// (folding gathered columns) for any split of the patches among ranks.
extern "C" void mpm3d_cxx_energy(StepContext* c) {
  if (c->method.has_body_force)
    compute_columns<true>(c);
  else
    compute_columns<false>(c);
  if (c->ranks.exchange) c->ranks.exchange(c, EXCHANGE_PARTIALS, 0, 0);  // other ranks' columns
  double sum[kReduceFields] = {0, 0, 0, 0, 0, 0, 0};
  for (int q = 0; q <= c->patch.npatch; ++q)
    for (int f = 0; f < kReduceFields; ++f) sum[f] += c->out.partials[size_t(kReduceFields) * q + f];
  for (int f = 0; f < 5; ++f) c->out.result[f] = sum[f];
  c->out.result[8] = sum[5];
  c->out.result[9] = sum[6];
}
