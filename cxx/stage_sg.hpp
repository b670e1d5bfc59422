// Smoothed-gradient MPM (sgmp): the cell-centre fields and the particles' weights on the
// auxiliary grid of cell centres (stage_sg.cpp says what they are), shared by stage_sg.cpp
// and the stress stage. Internal linkage, like patch_index.hpp.
#pragma once
#include <cstddef>

#include "patch_index.hpp"
#include "update_step.hpp"

namespace mpm3d {
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

// The weights w of particle p's eight auxiliary nodes, corner k = a + 2 b + 4 c of its
// auxiliary cell, and the cells of its corners per axis (lower lo[a], upper hi[a]); g2p:
// the G2P rule on held axes.
__attribute__((always_inline)) inline void sg_corner_weights(const StepContext* c, const CellDecoder& dec, int p, bool g2p, int lo[3], int hi[3],
                              double w[8]) {
  int ci[3];
  dec(c->cell[p], ci[0], ci[1], ci[2]);
  const double* lx = c->lx + 3 * p;
  double w0[3], w1[3];
  for (int a = 0; a < 3; ++a) {
    const double s = lx[a];
    const int al = s < 0.5 ? ci[a] - 1 : ci[a];  // lower centre of the auxiliary cell
    const int near = al + 1;                      // nearest grid node
    double X = s < 0.5 ? 2.0 * s : 2.0 * (s - 1.0);
    const bool held = (c->fix[2 * a] != 0 && near <= 1) || (c->fix[2 * a + 1] != 0 && near >= c->nn[a] - 2);
    if (held) {
      if (g2p) {
        const double xn = 2.0 * s - 1.0;
        X = xn < 0.0 ? 1.0 + 2.0 * xn : 2.0 * xn - 1.0;
      } else {
        X = X > 0.0 ? 1.0 : (X < 0.0 ? -1.0 : 0.0);
      }
    }
    w0[a] = 0.5 * (1.0 - X);
    w1[a] = 0.5 * (1.0 + X);
    const int last = c->nc[a] - 1;
    lo[a] = al < 0 ? 0 : (al > last ? last : al);
    hi[a] = al + 1 > last ? last : al + 1;
  }
  for (int k = 0; k < 8; ++k) {
    const int bx = k & 1, by = (k >> 1) & 1, bz = (k >> 2) & 1;
    w[k] = ((bx ? w1[0] : w0[0]) * (by ? w1[1] : w0[1])) * (bz ? w1[2] : w0[2]);
  }
}

// Cell index of corner k of an auxiliary cell with corner cells lo, hi per axis.
__attribute__((always_inline)) inline int sg_corner_cell(const StepContext* c, const int lo[3], const int hi[3], int k) {
  const int i = (k & 1) ? hi[0] : lo[0], j = ((k >> 1) & 1) ? hi[1] : lo[1], l = ((k >> 2) & 1) ? hi[2] : lo[2];
  return i + c->nc[0] * (j + c->nc[1] * l);
}

// The eight auxiliary nodes (cell indices idx) and weights w of particle p.
__attribute__((always_inline)) inline void sg_weights(const StepContext* c, const CellDecoder& dec, int p, bool g2p, int idx[8], double w[8]) {
  int lo[3], hi[3];
  sg_corner_weights(c, dec, p, g2p, lo, hi, w);
  for (int k = 0; k < 8; ++k) idx[k] = sg_corner_cell(c, lo, hi, k);
}

inline double* aux_cell(const StepContext* c, int cell) { return c->aux + size_t(cell) * kAuxFields; }

// The velocity gradient of a particle from the cells' (sg_cell_gradients), with its
// weights w on the centres cell[8].
inline void sg_velocity_gradient(const StepContext* c, const int cell[8], const double w[8], double L[9]) {
  double l[9] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};  // local: the loads cannot alias it
  for (int k = 0; k < 8; ++k) {
    const double wk = w[k];
    const double* a = aux_cell(c, cell[k]) + AUX_L;
#pragma omp simd
    for (int r = 0; r < 9; ++r) l[r] += wk * a[r];
  }
  for (int r = 0; r < 9; ++r) L[r] = l[r];
}

}  // namespace
}  // namespace mpm3d
