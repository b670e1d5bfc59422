// The 27-node family (transfer.hpp): uGIMP (shape 1) and the quadratic B-spline (shape 2),
// the stencil of 3 nodes per axis (gimp_stencil, patch_index.hpp), patch buffers with a
// halo of one node layer, one particle after the other.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <vector>

#include "stages/stress_loop.hpp"
#include "transfer/stencil27_lanes.hpp"
#include "transfer/transfer.hpp"

namespace mpm3d {
namespace {

// The buffer nodes the stencils of patch q's particles reach: [lo, hi) per axis, local to
// its buffer, into box[0..6); then fields first..first+count-1 of those nodes zeroed. A
// thin or sparse body touches a fraction of a buffer (a column one cell thick: 3 of its 7
// node layers per side axis), and the assembly reads nothing else (the boxes passed to
// assemble). In a distributed run the ranks send buffer nodes outside any box: the whole
// buffer then, as its box.
void clear_touched(const StepContext* c, const CellDecoder& dec, int q, const int q3[3], double* buf, int first,
                   int count, int* box) {
  const int P = c->patch.patch_cells, H = c->patch.patch_halo, Q = P + 1 + 2 * H;
  if (c->ranks.exchange) {
    for (int a = 0; a < 3; ++a) box[a] = 0, box[3 + a] = Q;
  } else {
    for (int a = 0; a < 3; ++a) box[a] = Q, box[3 + a] = 0;
    for (int idx = c->patch.patch_start[q]; idx < c->patch.patch_start[q + 1]; ++idx) {
      const int p = c->patch.patch_part[idx];
      int ci[3], o[3];
      dec(c->part.cell[p], ci[0], ci[1], ci[2]);
      stencil_offsets(c, ci, c->part.lx + 3 * p, o);
      for (int a = 0; a < 3; ++a) {
        const int lo = ci[a] + o[a] - q3[a] * P + H;
        box[a] = std::min(box[a], lo);
        box[3 + a] = std::max(box[3 + a], lo + 3);
      }
    }
  }
  for (int k = box[2]; k < box[5]; ++k)
    for (int j = box[1]; j < box[4]; ++j) {
      double* row = buf + size_t(box[0] + Q * (j + Q * k)) * kNodeFields;
      const int n = box[3] - box[0];
      if (count == kNodeFields) {
        std::memset(row, 0, sizeof(double) * size_t(n) * kNodeFields);
        continue;
      }
      for (int i = 0; i < n; ++i)
        for (int f = first; f < first + count; ++f) row[size_t(i) * kNodeFields + f] = 0.0;
    }
}

// The stencils of particles part[0 .. n) into s (stencil27_lanes.hpp), in AVX2 lanes where
// the CPU has them.
inline void stencils(const StepContext* c, const CellDecoder& dec, const int* part, int n, bool gradients,
                     Stencil27Block& s) {
  for (int i = 0; i < n; ++i) dec(c->part.cell[part[i]], s.ci[0][i], s.ci[1][i], s.ci[2][i]);
  if (lanes_use_avx2())
    stencil27_block_avx2(c, part, n, gradients, s);
  else
    stencil27_block<VectorLane<kStencilLanes>>(c, part, n, gradients, s);
}

// Node index of lane i's first stencil node (a = b = c = 0): in patch q3's buffer (halo H),
// and in the grid.
inline int block_patch_corner(const StepContext* c, const int q3[3], const Stencil27Block& s, int i) {
  const int P = c->patch.patch_cells, H = c->patch.patch_halo, Q = P + 1 + 2 * H;
  return (s.ci[0][i] + s.o[0][i] - q3[0] * P + H) +
         Q * ((s.ci[1][i] + s.o[1][i] - q3[1] * P + H) + Q * (s.ci[2][i] + s.o[2][i] - q3[2] * P + H));
}

inline int block_grid_corner(const StepContext* c, const Stencil27Block& s, int i) {
  return (s.ci[0][i] + s.o[0][i]) + c->grid.nn[0] * ((s.ci[1][i] + s.o[1][i]) + c->grid.nn[1] * (s.ci[2][i] + s.o[2][i]));
}

// The boxes of the last scatter, or null (whole buffers) in a distributed run.
inline const int* touched_boxes(const StepContext* c) { return c->ranks.exchange ? nullptr : c->patch.patch_box; }

// The scatter with the 27-node GIMP stencils (buffers with a halo of one node layer).
// One instance per flag set: constant flags, no test per node.
template <bool kMassMom, bool kForces, bool kBody>
void scatter_p2g_gimp(StepContext* c) {
  const int Q = c->patch.patch_cells + 1 + 2 * c->patch.patch_halo;
  const CellDecoder dec(c);
  const StencilOffsets in_buffer(Q, Q);
  for_filled_patches(c, [&](int q, const int q3[3], double* buf) {
    clear_touched(c, dec, q, q3, buf, 0, kNodeFields, c->patch.patch_box + 6 * size_t(c->patch.patch_slot[q]));
    const int end = c->patch.patch_start[q + 1];
    Stencil27Block s;
    for (int idx = c->patch.patch_start[q]; idx < end; idx += kStencilLanes) {
      const int n = std::min(kStencilLanes, end - idx);
      stencils(c, dec, c->patch.patch_part + idx, n, true, s);
      for (int i = 0; i < n; ++i) {
        double* corner = buf + size_t(block_patch_corner(c, q3, s, i)) * kNodeFields;
        p2g_particle<27, kStencilLanes>(c, c->patch.patch_part[idx + i], &s.N[0][i], &s.G[0][i], kMassMom, kForces,
                                        kBody, [&](int k) { return corner + size_t(in_buffer.of[k]) * kNodeFields; });
      }
    }
  });
}

void scatter_p2g_gimp(StepContext* c, bool with_mass_mom, bool with_forces) {
  const bool body = c->method.has_body_force != 0;
  if (with_mass_mom && with_forces)
    body ? scatter_p2g_gimp<true, true, true>(c) : scatter_p2g_gimp<true, true, false>(c);
  else if (with_forces)
    body ? scatter_p2g_gimp<false, true, true>(c) : scatter_p2g_gimp<false, true, false>(c);
  else if (with_mass_mom)
    scatter_p2g_gimp<true, false, false>(c);
}

void p2g_stencil27(StepContext* c, bool with_mass_mom, bool with_forces) {
  scatter_p2g_gimp(c, with_mass_mom, with_forces);
  assemble_p2g(c, with_mass_mom, with_forces, touched_boxes(c));
}

// GIMP: the 27-node stencils, one particle after the other.
void g2p_gimp(StepContext* c, bool remap) {
  const int Q = c->patch.patch_cells + 1 + 2 * c->patch.patch_halo;
  const int nn0 = c->grid.nn[0], nn1 = c->grid.nn[1];
  const CellDecoder dec(c);
  const StencilOffsets in_grid(nn0, nn1), in_buffer(Q, Q);
  for_filled_patches(c, [&](int q, const int q3[3], double* buf) {
    if (remap) clear_touched(c, dec, q, q3, buf, 1, 3, c->patch.patch_box + 6 * size_t(c->patch.patch_slot[q]));
    const int end = c->patch.patch_start[q + 1];
    Stencil27Block s;
    for (int idx = c->patch.patch_start[q]; idx < end; idx += kStencilLanes) {
      const int n = std::min(kStencilLanes, end - idx);
      stencils(c, dec, c->patch.patch_part + idx, n, false, s);
      for (int i = 0; i < n; ++i) {
        const int p = c->patch.patch_part[idx + i];
        const int base = block_grid_corner(c, s, i);
        g2p_particle<27, kStencilLanes>(c, p, &s.N[0][i], [&](int k) { return base + in_grid.of[k]; });
        if (remap) {
          double* corner = buf + size_t(block_patch_corner(c, q3, s, i)) * kNodeFields;
          remap_particle<27, kStencilLanes>(c, p, &s.N[0][i],
                                            [&](int k) { return corner + size_t(in_buffer.of[k]) * kNodeFields; });
        }
      }
    }
  });
}

void g2p_stencil27(StepContext* c, bool remap) {
  g2p_gimp(c, remap);
  if (remap) assemble(c, 1, 3, c->grid.gmass, c->grid.gmom, c->grid.gforce, touched_boxes(c));
}

// The velocity gradients L[3a+b] = d v_a / d x_b of the stress stage from the node
// velocities gvel, summed over the 27 stencil nodes in stencil order (the trilinear one:
// gradient_values in transfer_lanes.hpp). One per chunk of particles [first, end): the
// stencils of the next kStencilLanes particles the stress loop takes (stress_run's test)
// at a time.
struct BlockGradient {
  const StepContext* c;
  const StencilOffsets* in_grid;
  const double* gvel;
  int end;
  Stencil27Block s;
  int part[kStencilLanes];
  int n = 0, lane = 0;

  void operator()(const CellDecoder& dec, int, int p, double* L) {
    if (lane == n || part[lane] != p) {
      n = 0;
      lane = 0;
      for (int q = p; q < end && n < kStencilLanes; ++q)
        if (c->part.cell[q] >= 0 && !other_component(c, q)) part[n++] = q;
      stencils(c, dec, part, n, true, s);
    }
    const int i = lane++;
    double l0 = 0, l1 = 0, l2 = 0, l3 = 0, l4 = 0, l5 = 0, l6 = 0, l7 = 0, l8 = 0;
    const int base = block_grid_corner(c, s, i);
    for (int k = 0; k < 27; ++k) {
      const int nd = base + in_grid->of[k];
      if (!(c->grid.gmass[nd] > c->grid.mass_cutoff)) continue;
      const double vx = gvel[3 * nd], vy = gvel[3 * nd + 1], vz = gvel[3 * nd + 2];
      const double gx = s.G[3 * k][i], gy = s.G[3 * k + 1][i], gz = s.G[3 * k + 2][i];
      l0 += vx * gx;
      l1 += vx * gy;
      l2 += vx * gz;
      l3 += vy * gx;
      l4 += vy * gy;
      l5 += vy * gz;
      l6 += vz * gx;
      l7 += vz * gy;
      l8 += vz * gz;
    }
    L[0] = l0, L[1] = l1, L[2] = l2, L[3] = l3, L[4] = l4, L[5] = l5, L[6] = l6, L[7] = l7, L[8] = l8;
  }
};

void stress_stencil27(StepContext* c, const double* gvel) {
  const StencilOffsets in_grid(c->grid.nn[0], c->grid.nn[1]);
  stress_particles(c, [&](int, int end) { return BlockGradient{c, &in_grid, gvel, end, {}, {}}; });
}

// Contact: the mass gradients with the 27-node stencils.
const int* mass_gradient_stencil27(StepContext* c) {
  const int Q = c->patch.patch_cells + 1 + 2 * c->patch.patch_halo;
  const CellDecoder dec(c);
  const StencilOffsets in_buffer(Q, Q);
  for_filled_patches(c, [&](int q, const int q3[3], double* buf) {
    clear_touched(c, dec, q, q3, buf, 4, 3, c->patch.patch_box + 6 * size_t(c->patch.patch_slot[q]));
    for (int idx = c->patch.patch_start[q]; idx < c->patch.patch_start[q + 1]; ++idx) {
      const int p = c->patch.patch_part[idx];
      const double mp = c->part.mass[p];
      GimpStencil st;
      gimp_stencil(c, dec, p, st);
      double* corner = buf + size_t(gimp_patch_corner(c, q3, st)) * kNodeFields;
      for (int k = 0; k < 27; ++k) {
        double* b = corner + size_t(in_buffer.of[k]) * kNodeFields;
        const double* g = st.G + 3 * k;
        b[4] += mp * g[0];
        b[5] += mp * g[1];
        b[6] += mp * g[2];
      }
    }
  });
  return touched_boxes(c);
}

}  // namespace

const Transfer kStencil27Transfer = {p2g_stencil27, g2p_stencil27, stress_stencil27,
                                     mass_gradient_stencil27};

}  // namespace mpm3d
