#include "core/grid.hpp"

#include <cmath>
#include <stdexcept>

namespace mpm3d {

void Grid::define(const double lo[3], const double hi[3], double cell, int patch_cells_, int halo) {
  h = cell;
  patch_cells = patch_cells_;
  patch_halo = halo;
  for (int a = 0; a < 3; ++a) {
    origin[a] = lo[a];
    const double n = std::floor((hi[a] - lo[a]) / cell + 0.5);
    if (!(n >= 1.0) || n > 1.0e6) throw std::runtime_error("grid: bad cell count");
    deck_nc[a] = static_cast<int>(n);
  }
  const int q = patch_cells + 1 + 2 * halo;
  patch_nodes = q * q * q;
}

void Grid::setup(const double lo[3], const double hi[3], double cell, int patch_cells_, int halo) {
  define(lo, hi, cell, patch_cells_, halo);
  const int zero[3] = {0, 0, 0};
  set_window(zero, deck_nc);
}

void Grid::set_window(const int off_[3], const int nc_[3]) {
  for (int a = 0; a < 3; ++a) {
    if (off_[a] < 0 || nc_[a] < 1 || off_[a] + nc_[a] > deck_nc[a]) throw std::logic_error("grid: bad window");
    off[a] = off_[a];
    nc[a] = nc_[a];
    nn[a] = nc[a] + 1;
    npd[a] = (nc[a] + patch_cells - 1) / patch_cells;
  }
  npatch = npd[0] * npd[1] * npd[2];
  const size_t nnodes = size_t(nnode());
  // Fresh arrays, so a shrunk window gives its memory back.
  std::vector<double>(nnodes, 0.0).swap(mass);
  std::vector<double>(3 * nnodes, 0.0).swap(mom);
  std::vector<double>(3 * nnodes, 0.0).swap(force);
  patch_start.assign(size_t(npatch) + 1, 0);
  patch_slot.assign(size_t(npatch), -1);
  nslot = 0;
}

WindowExtent window_extent(const Grid& g, const double* x, const double* v, int np) {
  WindowExtent e = {{g.deck_nc[0], g.deck_nc[1], g.deck_nc[2]}, {-1, -1, -1}, 0.0};
  for (int p = 0; p < np; ++p) {
    int idx[3];
    bool in = true;
    for (int a = 0; a < 3; ++a) {
      const double t = (x[3 * p + a] - g.origin[a]) / g.h;
      const double fl = std::floor(t);
      if (!(fl >= 0.0 && fl < double(g.deck_nc[a]))) {
        in = false;
        break;
      }
      idx[a] = int(fl);
    }
    if (!in) continue;
    for (int a = 0; a < 3; ++a) {
      if (idx[a] < e.cmin[a]) e.cmin[a] = idx[a];
      if (idx[a] > e.cmax[a]) e.cmax[a] = idx[a];
    }
    const double* vp = v + 3 * p;
    const double s = (vp[0] * vp[0] + vp[1] * vp[1]) + vp[2] * vp[2];
    if (s > e.vmax2) e.vmax2 = s;
  }
  return e;
}

void window_of_extent(const Grid& g, const WindowExtent& e, int every, double dt, int off[3], int nc[3]) {
  const bool any = e.cmax[0] >= 0;
  const double r = (2.0 * ((double(every) * std::sqrt(e.vmax2)) * dt)) / g.h;
  const int m = 1 + (r < 1.0e6 ? int(std::ceil(r)) : 1000000);
  for (int a = 0; a < 3; ++a) {
    int lo = 0, hi = g.deck_nc[a];
    if (any) {
      lo = e.cmin[a] - m;
      if (lo < 0) lo = 0;
      lo = (lo / g.patch_cells) * g.patch_cells;
      if (g.fix[2 * a] != 0) lo = 0;
      hi = e.cmax[a] + 1 + m;
      if (hi > g.deck_nc[a]) hi = g.deck_nc[a];
      if (g.fix[2 * a + 1] != 0) hi = g.deck_nc[a];
    }
    off[a] = lo;
    nc[a] = hi - lo;
  }
}

void adaptive_window(const Grid& g, const double* x, const double* v, int np, int every, double dt,
                     int off[3], int nc[3]) {
  window_of_extent(g, window_extent(g, x, v, np), every, dt, off, nc);
}

int count_escaped(const Grid& g, const double* x, const int* cell, int np) {
  int n = 0;
  for (int p = 0; p < np; ++p) {
    if (cell[p] >= 0) continue;
    bool in = true;
    for (int a = 0; a < 3 && in; ++a) {
      const double fl = std::floor((x[3 * p + a] - g.origin[a]) / g.h);
      in = fl >= 0.0 && fl < double(g.deck_nc[a]);
    }
    if (in) ++n;
  }
  return n;
}

PatchStats patch_stats(const Grid& g, const int* patch_start, const int* second_start) {
  PatchStats s;
  s.patches = g.npatch;
  long total = 0;
  for (int q = 0; q < g.npatch; ++q) {
    int n = patch_start[q + 1] - patch_start[q];
    if (second_start) n += second_start[q + 1] - second_start[q];
    if (n == 0) continue;
    ++s.nonempty;
    total += n;
    if (n > s.max) s.max = n;
  }
  s.empty = s.patches - s.nonempty;
  if (s.nonempty > 0) {
    s.mean = double(total) / double(s.nonempty);
    s.imbalance = double(s.max) / s.mean;
  }
  return s;
}

}  // namespace mpm3d
