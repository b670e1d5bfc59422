// GridData: the background grid, its patch decomposition and the shape functions.
#pragma once
#include <vector>

namespace mpm3d {

// Fields of one node in a patch buffer: mass, momentum (3), force (3).
constexpr int kNodeFields = 7;

struct Grid {
  double origin[3] = {0, 0, 0};  // lower corner of the computational box
  double h = 0.0;                // cubic cell size
  int nc[3] = {0, 0, 0};         // cells per axis
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
  // Sets counts and allocates the node arrays and the patch buffers.
  void setup(const double lo[3], const double hi[3], double cell, int patch_cells_);
};

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
