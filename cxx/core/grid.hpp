// GridData: the background grid, its patch decomposition and the shape functions.
#pragma once
#include <cmath>
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

  // Patch decomposition (docs/DESIGN.md section 4): cubes of patch_cells^3 cells; it depends
  // on the grid only, never on the number of threads.
  int patch_cells = 4;
  int npd[3] = {0, 0, 0};  // patches per axis
  int npatch = 0;
  int patch_halo = 0;      // node layers a buffer holds beyond its cells' nodes, each side:
                           // 0 trilinear, 1 GIMP (27-node stencils reach one node further)
  int patch_nodes = 0;     // (patch_cells + 1 + 2 patch_halo)^3 nodes in one patch buffer
  std::vector<int> patch_start;  // (npatch + 1) offsets into patch_part
  std::vector<int> patch_part;   // particle indices, ascending within each patch
  std::vector<int> patch_slot;   // (npatch) buffer slot of a non-empty patch, -1 if empty
  int nslot = 0;                 // non-empty patches (buffers in use)
  std::vector<double> patch_buf; // (kNodeFields, patch_nodes, nslot): only non-empty patches
  std::vector<int> patch_box;     // (6, slots of patch_buf): the nodes a 27-node scatter touched

  int nnode() const { return nn[0] * nn[1] * nn[2]; }
  // define() and set_window() over the whole box.
  void setup(const double lo[3], const double hi[3], double cell, int patch_cells_, int halo = 0);
  // The deck's box and lattice (no allocation); halo: node layers a patch buffer holds
  // beyond its cells (1 with GIMP).
  void define(const double lo[3], const double hi[3], double cell, int patch_cells_, int halo = 0);
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
// Same operations as grid_adaptive_window in fortran_ref/grid.f90. In two parts, so that
// several ranks can merge their particles' extents (min and max: exact) before the window:
// the extent of particles x, v inside the box, and the window of an extent.
struct WindowExtent {
  int cmin[3], cmax[3];  // occupied cells per axis (cmax[0] < 0: no particle inside)
  double vmax2;          // largest |v|^2
};
WindowExtent window_extent(const Grid& g, const double* x, const double* v, int np);
void window_of_extent(const Grid& g, const WindowExtent& e, int every, double dt, int off[3], int nc[3]);
void adaptive_window(const Grid& g, const double* x, const double* v, int np, int every, double dt,
                     int off[3], int nc[3]);
// Particles outside the window (cell < 0) but inside the deck's box.
int count_escaped(const Grid& g, const double* x, const int* cell, int np);
// Particles per patch over the non-empty patches of the last binning; with contact, both
// components' lists (second_start: component 2's, on the same patches; else null).
struct PatchStats {
  int patches = 0, nonempty = 0, empty = 0, max = 0;
  double mean = 0.0, imbalance = 0.0;  // mean over the non-empty patches; max / mean
};
PatchStats patch_stats(const Grid& g, const int* patch_start, const int* second_start = nullptr);

// Trilinear shape functions of the 8 nodes of a cell at local coordinates lx in [0,1)^3.
// Local node k = a + 2 b + 4 c has offset (a, b, c). Explicit operation order (bit-for-bit
// with fortran_ref/grid.f90): N = (wx * wy) * wz, dN/dx = (gx * wy) * wz, ...
// Written for a lane type T (lanes.hpp): double, or a vector of particles; internal
// linkage, so units built for another instruction set keep their own copy.
namespace {
template <class T>
inline void shape_linear_lanes(const T lx[3], double inv_h, T N[8], T G[24]) {
  const T wx[2] = {1.0 - lx[0], lx[0]};
  const T wy[2] = {1.0 - lx[1], lx[1]};
  const T wz[2] = {1.0 - lx[2], lx[2]};
  const double g[2] = {-inv_h, inv_h};
  for (int k = 0; k < 8; ++k) {
    const int a = k & 1, b = (k >> 1) & 1, c = (k >> 2) & 1;
    N[k] = (wx[a] * wy[b]) * wz[c];
    G[3 * k + 0] = (g[a] * wy[b]) * wz[c];
    G[3 * k + 1] = (wx[a] * g[b]) * wz[c];
    G[3 * k + 2] = (wx[a] * wy[b]) * g[c];
  }
}
}  // namespace

inline void shape_linear(const double* lx, double inv_h, double* N, double* G) {
  shape_linear_lanes<double>(lx, inv_h, N, G);
}

// uGIMP (uniform generalized interpolation material point, Bardenhagen & Kober 2004) weights
// of the three nodes at offsets o, o+1, o+2 (o = -1 or 0) from the base node of the
// particle's cell along one axis: lx in [0,1) is the local coordinate in the cell, l = lp/h
// the particle half-size in cells (0 < l <= 1/2), r = lx - (o + k) = (x_p - x_k)/h:
//   |r| < l            S = 1 - (r^2 + l^2)/(2 l)   dS/dr = -r/l
//   l <= |r| <= 1 - l  S = 1 - |r|                 dS/dr = -sign(r)
//   1 - l < |r| < 1+l  S = (1 + l - |r|)^2/(4 l)   dS/dr = -sign(r) (1 + l - |r|)/(2 l)
// and 0 beyond; g = dS/dr / h. Operation order as fortran_ref/grid.f90 (gimp_1d).
inline void gimp_1d(double lx, int o, double l, double inv_h, double* w, double* g) {
  for (int k = 0; k < 3; ++k) {
    const double r = lx - double(o + k);
    const double a = std::fabs(r);
    double s = 0.0, d = 0.0;
    if (a < l) {
      s = 1.0 - ((r * r) + (l * l)) / (2.0 * l);
      d = -(r / l);
    } else if (a <= 1.0 - l) {
      s = 1.0 - a;
      d = r > 0.0 ? -1.0 : 1.0;
    } else if (a < 1.0 + l) {
      const double t = (1.0 + l) - a;
      s = (t * t) / (4.0 * l);
      d = r > 0.0 ? -(t / (2.0 * l)) : t / (2.0 * l);
    }
    w[k] = s;
    g[k] = d * inv_h;
  }
}

// The quadratic B-spline weights of the current MPM3D-F90 ('bimp') of the three nodes at
// offsets o, o+1, o+2 from the base node of the particle's cell, lx = s in [0,1) the local
// coordinate in the cell. The current program's stencil is always the nodes base-1, base,
// base+1 with the uniform quadratic B-spline blending functions
//   N(base-1) = (1-s)^2 / 2,   N(base) = 1/2 + s - s^2,   N(base+1) = s^2 / 2,
// i.e. node i carries the quadratic B-spline centred half a cell above it (at the centre
// of cell i, docs/DECK_FORMAT.md "bimp"). o = -1 inside the grid; in the first cell
// (no node base-1) o = 0 and the weight of base-1 is dropped. g = dN/dx.
inline void bspline_1d(double s, int o, double inv_h, double* w, double* g) {
  for (int k = 0; k < 3; ++k) {
    const int m = o + k;
    double n = 0.0, d = 0.0;
    if (m == -1) {
      const double t = 1.0 - s;
      n = 0.5 * (t * t);
      d = -t;
    } else if (m == 0) {
      n = (0.5 + s) - s * s;
      d = 1.0 - 2.0 * s;
    } else if (m == 1) {
      n = 0.5 * (s * s);
      d = s;
    }
    w[k] = n;
    g[k] = d * inv_h;
  }
}

// Stencil offset of one axis with B-splines: the nodes base-1 .. base+1, or base .. base+2
// in the grid's first cell (cell index i).
inline int bspline_offset(int i) { return i > 0 ? -1 : 0; }

// Tensor products of the 27 nodes of a stencil from the 1-D weights w and derivatives g:
// local node k = a + 3 b + 9 c sits at offset (o[0] + a, o[1] + b, o[2] + c) from the base
// node of the particle's cell. Same products as shape_linear: N = (wx * wy) * wz,
// dN/dx = (gx * wy) * wz.
inline void shape_27(const double* wx, const double* wy, const double* wz, const double* gx, const double* gy,
                     const double* gz, double* N, double* G) {
  for (int c = 0; c < 3; ++c)
    for (int b = 0; b < 3; ++b)
      for (int a = 0; a < 3; ++a) {
        const int k = a + 3 * b + 9 * c;
        N[k] = (wx[a] * wy[b]) * wz[c];
        G[3 * k + 0] = (gx[a] * wy[b]) * wz[c];
        G[3 * k + 1] = (wx[a] * gy[b]) * wz[c];
        G[3 * k + 2] = (wx[a] * wy[b]) * gz[c];
      }
}

// The values alone (G null): the same N, without the gradients' products.
inline void shape_27_or_values(const double* wx, const double* wy, const double* wz, const double* gx,
                               const double* gy, const double* gz, double* N, double* G) {
  if (G) {
    shape_27(wx, wy, wz, gx, gy, gz, N, G);
    return;
  }
  for (int c = 0; c < 3; ++c)
    for (int b = 0; b < 3; ++b)
      for (int a = 0; a < 3; ++a) N[a + 3 * b + 9 * c] = (wx[a] * wy[b]) * wz[c];
}

// uGIMP shape functions of the 27 nodes of a particle's stencil (shape_27; G null: the
// values only).
inline void shape_gimp(const double* lx, const int* o, double l, double inv_h, double* N, double* G) {
  double wx[3], wy[3], wz[3], gx[3], gy[3], gz[3];
  gimp_1d(lx[0], o[0], l, inv_h, wx, gx);
  gimp_1d(lx[1], o[1], l, inv_h, wy, gy);
  gimp_1d(lx[2], o[2], l, inv_h, wz, gz);
  shape_27_or_values(wx, wy, wz, gx, gy, gz, N, G);
}

// The current version's quadratic B-spline shape functions of the 27 nodes (shape_27; G
// null: the values only).
inline void shape_bspline(const double* lx, const int* o, double inv_h, double* N, double* G) {
  double wx[3], wy[3], wz[3], gx[3], gy[3], gz[3];
  bspline_1d(lx[0], o[0], inv_h, wx, gx);
  bspline_1d(lx[1], o[1], inv_h, wy, gy);
  bspline_1d(lx[2], o[2], inv_h, wz, gz);
  shape_27_or_values(wx, wy, wz, gx, gy, gz, N, G);
}

// Stencil offset of one axis: the three nodes nearest the particle (o = -1 in the lower
// half of the cell, 0 in the upper half), shifted inwards at the ends of the grid so that
// all three exist (cell index i of nc cells, nc >= 2); the weight that would fall on a
// node beyond the box is dropped there.
inline int gimp_offset(double lx, int i, int nc) {
  int o = lx < 0.5 ? -1 : 0;
  if (i + o < 0) o = 0;
  if (i + o + 2 > nc) o = -1;
  return o;
}

// The 27-node shape functions, one place for each: shape 1 uGIMP (particle half-size
// lp_cells, in cells), 2 quadratic B-spline. The offsets o of the stencil of a particle in
// cell ci (of nc per axis) at local coordinates lx, then its weights N and, unless G is
// null, gradients G. A new 27-node shape function is a branch here and its deck keyword.
inline void stencil_27_offsets(int shape, const int ci[3], const double* lx, const int nc[3], int o[3]) {
  if (shape == 2)
    for (int a = 0; a < 3; ++a) o[a] = bspline_offset(ci[a]);
  else
    for (int a = 0; a < 3; ++a) o[a] = gimp_offset(lx[a], ci[a], nc[a]);
}

inline void stencil_27(int shape, const int ci[3], const double* lx, const int nc[3], double lp_cells, double inv_h,
                       int o[3], double* N, double* G) {
  stencil_27_offsets(shape, ci, lx, nc, o);
  if (shape == 2)
    shape_bspline(lx, o, inv_h, N, G);
  else
    shape_gimp(lx, o, lp_cells, inv_h, N, G);
}

}  // namespace mpm3d
