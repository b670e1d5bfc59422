// The 27-node family (transfer.hpp): uGIMP (shape 1) and the quadratic B-spline (shape 2),
// the stencil of 3 nodes per axis (gimp_stencil, patch_index.hpp), patch buffers with a
// halo of one node layer, one particle after the other.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <vector>

#include "stages/stress_loop.hpp"
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
    for (int idx = c->patch.patch_start[q]; idx < c->patch.patch_start[q + 1]; ++idx) {
      const int p = c->patch.patch_part[idx];
      GimpStencil st;
      gimp_stencil(c, dec, p, st);
      double* corner = buf + size_t(gimp_patch_corner(c, q3, st)) * kNodeFields;
      p2g_particle<27>(c, p, st.N, st.G, kMassMom, kForces, kBody,
                       [&](int k) { return corner + size_t(in_buffer.of[k]) * kNodeFields; });
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
    for (int idx = c->patch.patch_start[q]; idx < c->patch.patch_start[q + 1]; ++idx) {
      const int p = c->patch.patch_part[idx];
      GimpStencil st;
      gimp_stencil(c, dec, p, st, false);
      const int base = gimp_corner(c, st);
      g2p_particle<27>(c, p, st.N, [&](int k) { return base + in_grid.of[k]; });
      if (remap) {
        double* corner = buf + size_t(gimp_patch_corner(c, q3, st)) * kNodeFields;
        remap_particle<27>(c, p, st.N, [&](int k) { return corner + size_t(in_buffer.of[k]) * kNodeFields; });
      }
    }
  });
}

void g2p_stencil27(StepContext* c, bool remap) {
  g2p_gimp(c, remap);
  if (remap) assemble(c, 1, 3, c->grid.gmass, c->grid.gmom, c->grid.gforce, touched_boxes(c));
}

// Velocity gradient L[3a+b] = d v_a / d x_b of particle p from the node velocities gvel,
// summed over the 27 GIMP stencil nodes in stencil order (the trilinear one:
// gradient_values in transfer_lanes.hpp).
inline void velocity_gradient_gimp(const StepContext* c, const CellDecoder& dec, const StencilOffsets& in_grid, int p,
                                   const double* gvel, double L[9]) {
  double l0 = 0, l1 = 0, l2 = 0, l3 = 0, l4 = 0, l5 = 0, l6 = 0, l7 = 0, l8 = 0;
  GimpStencil st;
  gimp_stencil(c, dec, p, st);
  const int base = gimp_corner(c, st);
  for (int k = 0; k < 27; ++k) {
    const int n = base + in_grid.of[k];
    if (!(c->grid.gmass[n] > c->grid.mass_cutoff)) continue;
    const double vx = gvel[3 * n], vy = gvel[3 * n + 1], vz = gvel[3 * n + 2];
    const double gx = st.G[3 * k], gy = st.G[3 * k + 1], gz = st.G[3 * k + 2];
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

void stress_stencil27(StepContext* c, const double* gvel) {
  const StencilOffsets in_grid(c->grid.nn[0], c->grid.nn[1]);
  stress_particles(c, [&](const CellDecoder& dec, int, int p, double* L) {
    velocity_gradient_gimp(c, dec, in_grid, p, gvel, L);
  });
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
