// Smoothed-gradient MPM (sgmp): the cell-centre fields and the particles' weights on the
// auxiliary grid of cell centres (smoothed_gradient.cpp says what they are), and the
// family's stages. Internal linkage, like patch_index.hpp, but for the stages.
#pragma once
#include <cstddef>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "core/patch_index.hpp"
#include "core/step_state.hpp"

namespace mpm3d {

// The family's stages (smoothed_gradient.cpp): the exchanges through the cell centres
// (StepContext::aux, kAuxFields per cell). P2G: the nodes' mass and momentum and/or forces;
// G2P: the particles' velocities and positions, with remap the nodes' momenta; stress: the
// cells' velocity gradients from the node velocities gvel (each particle's:
// sg_velocity_gradient, below, with the weights of sg_ensure_weights: each
// patch-list entry's, in sg_w and sg_cell, computed once a step; with_reach: also what
// the scatters of several threads need).
void sg_p2g(StepContext* c, bool with_mass_mom, bool with_forces);
void sg_g2p(StepContext* c, bool remap);
void sg_cell_gradients(StepContext* c, const double* gvel);
void sg_ensure_weights(StepContext* c, bool with_reach);

namespace {

// Fields of one cell centre in StepContext::aux (kAuxFields doubles per cell).
enum : int {
  AUX_M = 0,    // mass
  AUX_P = 1,    // momentum (3)
  AUX_FB = 4,   // body force (3)
  AUX_S = 7,    // sigma V, Voigt xx yy zz yz xz xy (6); TLmp: V0 P, row-major (9)
  AUX_V = 16,   // G2P: velocity (3)
  AUX_A = 19,   // G2P: acceleration (3)
  AUX_RP = 22,  // MUSL remap: momentum (3)
  AUX_L = 25,   // stress: velocity gradient L[3a+b] = dv_a/dx_b (9; TLmp: dv_a/dX_b)
};

// An entry's weights in StepContext::sg_w (kSgWeights each): the P2G rule's eight, then
// the G2P rule's (sg_corner_weights).
inline double* sg_p2g_weights(const StepContext* c, int e) { return c->sgmp.sg_w + size_t(kSgWeights) * size_t(e); }
inline double* sg_g2p_weights(const StepContext* c, int e) { return sg_p2g_weights(c, e) + 8; }

// The grid sizes and held faces that the weights read, as a value: the caller's loop stores
// ints (the corners' cells), which could alias the grid's own fields and make it reload them.
// With them the rules that move weights (read by sg_corner_weights<true> alone).
struct SgGeometry {
  int nc[3], nn[3];
  bool fix[6];
  bool lower_truncate, beyond_drop;  // rules sg_lower=truncate, sg_beyond=drop
  explicit SgGeometry(const StepContext* c) {
    for (int a = 0; a < 3; ++a) nc[a] = c->grid.nc[a], nn[a] = c->grid.nn[a];
    for (int f = 0; f < 6; ++f) fix[f] = c->grid.fix[f] != 0;
    lower_truncate = c->rules.sg_lower != 0;
    beyond_drop = c->rules.sg_beyond != 0;
  }
};

// Whether a run takes sg_corner_weights<true>: a rule moves weights.
inline bool sg_rules_move_weights(const StepContext* c) { return c->rules.sg_lower != 0 || c->rules.sg_beyond != 0; }

// The weights of a particle's eight auxiliary nodes (its cell and local coordinates lx),
// corner k = a + 2 b + 4 c of its auxiliary cell, under the P2G rule (w) and the G2P rule
// (wg, which differs on held axes alone), and the cells of its corners per axis (lower
// lo[a], upper hi[a]). kRules: the rules of the current program's auxiliary cells (g says
// which): sg_lower=truncate, in the outer half of a first cell the auxiliary cell of the
// first two centres (its truncation toward zero of (x - x0 - h/2) / h), with the weights
// meant for the cell around the face node; sg_beyond=drop, on a one-cell axis no weight
// for a centre beyond the grid where the current program's number for it is past its last
// cell (it skips those centres).
template <bool kRules = false>
__attribute__((always_inline)) inline void sg_corner_weights(const SgGeometry& g, const CellDecoder& dec, int cell,
                                                             const double* lx, int lo[3], int hi[3], double w[8],
                                                             double wg[8]) {
  int ci[3];
  dec(cell, ci[0], ci[1], ci[2]);
  double w0[3], w1[3], g0[3], g1[3];
  bool any_held = false;
  int beyond = 0;  // sg_beyond=drop: bit a, the upper centre lies beyond one-cell axis a
  for (int a = 0; a < 3; ++a) {
    const double s = lx[a];
    const int al = s < 0.5 ? ci[a] - 1 : ci[a];  // lower centre of the auxiliary cell
    const int near = al + 1;                      // nearest grid node
    const double X = s < 0.5 ? 2.0 * s : 2.0 * (s - 1.0);
    const bool held = (g.fix[2 * a] && near <= 1) || (g.fix[2 * a + 1] && near >= g.nn[a] - 2);
    if (held) {
      const double Xp = X > 0.0 ? 1.0 : (X < 0.0 ? -1.0 : 0.0);
      const double xn = 2.0 * s - 1.0;
      const double Xg = xn < 0.0 ? 1.0 + 2.0 * xn : 2.0 * xn - 1.0;
      w0[a] = 0.5 * (1.0 - Xp);
      w1[a] = 0.5 * (1.0 + Xp);
      g0[a] = 0.5 * (1.0 - Xg);
      g1[a] = 0.5 * (1.0 + Xg);
      any_held = true;
    } else {
      w0[a] = g0[a] = 0.5 * (1.0 - X);
      w1[a] = g1[a] = 0.5 * (1.0 + X);
    }
    const int last = g.nc[a] - 1;
    int cl = al;  // the auxiliary cell's lower centre
    if (kRules) {
      if (g.lower_truncate && cl < 0) cl = 0;
      if (g.beyond_drop && last == 0) {
        if (cl < 0) w0[a] = g0[a] = 0.0;
        beyond |= (cl + 1 > last ? 1 : 0) << a;
      }
    }
    lo[a] = cl < 0 ? 0 : (cl > last ? last : cl);
    hi[a] = cl + 1 > last ? last : cl + 1;
  }
  // Corner k's weight: the product (x * y) * z of its lower (f0) or upper (f1) factors.
  auto products = [](const double f0[3], const double f1[3], double out[8]) __attribute__((always_inline)) {
    for (int k = 0; k < 8; ++k) {
      const int bx = k & 1, by = (k >> 1) & 1, bz = (k >> 2) & 1;
      out[k] = ((bx ? f1[0] : f0[0]) * (by ? f1[1] : f0[1])) * (bz ? f1[2] : f0[2]);
    }
  };
  products(w0, w1, w);
  if (!any_held) {
    for (int k = 0; k < 8; ++k) wg[k] = w[k];
  } else {
    products(g0, g1, wg);
  }
  if (kRules && beyond != 0) {
    // The current program numbers that centre as one past the axis's last (its cell
    // numbers run x fastest), which is the first cell of the next row along the following
    // axes, and skips it only where that number is past its last cell: there the weight
    // is dropped; elsewhere it goes to the nearest centre (ours; the row it lands in is
    // not copied).
    for (int k = 0; k < 8; ++k) {
      if ((k & beyond) == 0) continue;
      int n = 0;
      for (int a = 2; a >= 0; --a) n = n * g.nc[a] + ((k >> a & 1) ? ((beyond >> a & 1) ? g.nc[a] : hi[a]) : lo[a]);
      if (n >= g.nc[0] * g.nc[1] * g.nc[2]) w[k] = wg[k] = 0.0;
    }
  }
}

// Cell index of corner k of an auxiliary cell with corner cells lo, hi per axis.
__attribute__((always_inline)) inline int sg_corner_cell(const SgGeometry& g, const int lo[3], const int hi[3], int k) {
  const int i = (k & 1) ? hi[0] : lo[0], j = ((k >> 1) & 1) ? hi[1] : lo[1], l = ((k >> 2) & 1) ? hi[2] : lo[2];
  return i + g.nc[0] * (j + g.nc[1] * l);
}

inline double* aux_cell(const StepContext* c, int cell) { return c->sgmp.aux + size_t(cell) * kAuxFields; }

// Bit k set where the weight of corner k is not zero (in vector compares where the
// compiler targets SSE2: the same test). A zero weight's terms are +-0 (of finite
// values), and a sum started at +0.0 is never -0.0 (x + y is -0.0 only for two -0.0), so
// adding them changes no bit: the scatters and the velocity gradient skip them. A
// one-cell axis with held faces (the current decks' thin models) has a zero weight on one
// side, half the corners.
inline unsigned nonzero_corners(const double w[8]) {
  unsigned m = 0;
#ifdef __SSE2__
  const __m128d zero = _mm_setzero_pd();
  for (int k = 0; k < 8; k += 2) m |= unsigned(_mm_movemask_pd(_mm_cmpneq_pd(_mm_loadu_pd(w + k), zero))) << k;
#else
  for (int k = 0; k < 8; ++k) m |= (w[k] != 0.0 ? 1u : 0u) << k;
#endif
  return m;
}

// The velocity gradient of a particle from the cells' (sg_cell_gradients), with its
// weights w on the centres cell[8].
inline void sg_velocity_gradient(const StepContext* c, const int cell[8], const double w[8], double L[9]) {
  double l[9] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};  // local: the loads cannot alias it
  for (unsigned left = nonzero_corners(w); left != 0; left &= left - 1) {  // corners in ascending order
    const int k = __builtin_ctz(left);
    const double wk = w[k];
    const double* a = aux_cell(c, cell[k]) + AUX_L;
#pragma omp simd
    for (int r = 0; r < 9; ++r) l[r] += wk * a[r];
  }
  for (int r = 0; r < 9; ++r) L[r] = l[r];
}

}  // namespace
}  // namespace mpm3d
