// GridData: the background grid, its patch decomposition and the shape functions.
#pragma once
#include <vector>

namespace mpm3d {

// Fields of one node in a patch buffer: mass, momentum (3), force (3).
constexpr int kNodeFields = 7;

// The grid is a window of the deck's box: cells off[a] .. off[a] + nc[a] - 1 of the deck's
// lattice (node k of the window lies at origin + (off + k) h). Without the adaptive grid the
// window is the whole box (off = 0, nc = deck_nc).
struct Grid {
  double origin[3] = {0, 0, 0};  // lower corner of the deck's box: the lattice origin
  double h = 0.0;                // cubic cell size
  int deck_nc[3] = {0, 0, 0};    // cells per axis of the deck's box
  int off[3] = {0, 0, 0};        // first cell of the window on the deck's lattice
  int nc[3] = {0, 0, 0};         // cells per axis of the window
  int nn[3] = {0, 0, 0};         // nodes per axis (nc + 1)
  int fix[6] = {0, 0, 0, 0, 0, 0};  // faces x0 xn y0 yn z0 zn: 0 free, 1 fixed, 2 symmetry
  double mass_cutoff = 0.0;      // nodes lighter than this form no velocity

  std::vector<double> mass, mom, force;  // (nnode) (3,nnode) (3,nnode)

  // Patch decomposition (DESIGN.md section 4): cubes of patch_cells^3 cells; it depends
  // on the grid only, never on the number of threads.
  int patch_cells = 8;
  int npd[3] = {0, 0, 0};  // patches per axis
  int npatch = 0;
  int patch_nodes = 0;     // (patch_cells + 1)^3 nodes in one patch buffer
  std::vector<int> patch_start;  // (npatch + 1) offsets into patch_part
  std::vector<int> patch_part;   // particle indices, ascending within each patch
  std::vector<int> patch_slot;   // (npatch) buffer slot of a non-empty patch, -1 if empty
  int nslot = 0;                 // non-empty patches (buffers in use)
  std::vector<double> patch_buf; // (kNodeFields, patch_nodes, nslot): only non-empty patches

  int nnode() const { return nn[0] * nn[1] * nn[2]; }
  // define() and set_window() over the whole box.
  void setup(const double lo[3], const double hi[3], double cell, int patch_cells_);
  // The deck's box and lattice (no allocation).
  void define(const double lo[3], const double hi[3], double cell, int patch_cells_);
  // Makes cells off_[a] .. off_[a] + nc_[a] - 1 the window: counts, patches, node arrays
  // (allocated afresh at the window's size, zero).
  void set_window(const int off_[3], const int nc_[3]);
  bool window_is_box() const {
    return off[0] == 0 && off[1] == 0 && off[2] == 0 && nc[0] == deck_nc[0] && nc[1] == deck_nc[1] &&
           nc[2] == deck_nc[2];
  }
};

// The adaptive background grid (the paper's load balance; docs/PERFORMANCE.md). The window
// for the particles x (3,np), velocities v (3,np): per axis, the cells the particles inside
// the deck's box occupy, widened by a margin of m = 1 + ceil(2 every |v|max dt / h) cells
// (room for `every` steps of motion at twice the fastest particle's speed), the lower end
// rounded down to a whole patch of the deck's lattice (so the patches of the window are
// those of the box, and every node sum keeps its bits), clipped to the box; a face with a
// boundary condition (fix != 0) stays at the box face. No particle inside: the whole box.
// Same operations as grid_adaptive_window in fortran_ref/grid.f90.
void adaptive_window(const Grid& g, const double* x, const double* v, int np, int every, double dt,
                     int off[3], int nc[3]);
// Particles outside the window (cell < 0) but inside the deck's box.
int count_escaped(const Grid& g, const double* x, const int* cell, int np);
// Particles per patch over the non-empty patches of the last binning.
struct PatchStats {
  int patches = 0, nonempty = 0, empty = 0, max = 0;
  double mean = 0.0, imbalance = 0.0;  // mean over the non-empty patches; max / mean
};
PatchStats patch_stats(const Grid& g, const int* patch_start);

// Trilinear shape functions of the 8 nodes of a cell at local coordinates lx in [0,1)^3.
// Local node k = a + 2 b + 4 c has offset (a, b, c). Explicit operation order (bit-for-bit
// with fortran_ref/grid.f90): N = (wx * wy) * wz, dN/dx = (gx * wy) * wz, ...
inline void shape_linear(const double* lx, double inv_h, double* N, double* G) {
  const double wx[2] = {1.0 - lx[0], lx[0]};
  const double wy[2] = {1.0 - lx[1], lx[1]};
  const double wz[2] = {1.0 - lx[2], lx[2]};
  const double g[2] = {-inv_h, inv_h};
  for (int k = 0; k < 8; ++k) {
    const int a = k & 1, b = (k >> 1) & 1, c = (k >> 2) & 1;
    N[k] = (wx[a] * wy[b]) * wz[c];
    G[3 * k + 0] = (g[a] * wy[b]) * wz[c];
    G[3 * k + 1] = (wx[a] * g[b]) * wz[c];
    G[3 * k + 2] = (wx[a] * wy[b]) * g[c];
  }
}

}  // namespace mpm3d
