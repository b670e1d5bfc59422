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

// The scatter with the 27-node GIMP stencils (buffers with a halo of one node layer).
// One instance per flag set: constant flags, no test per node.
template <bool kMassMom, bool kForces, bool kBody>
void scatter_p2g_gimp(StepContext* c) {
  const int Q = c->patch.patch_cells + 1 + 2 * c->patch.patch_halo;
  const int pn = patch_nodes(c);
  const CellDecoder dec(c);
  const StencilOffsets in_buffer(Q, Q);
  for_filled_patches(c, [&](int q, const int q3[3], double* buf) {
    std::memset(buf, 0, sizeof(double) * size_t(pn) * kNodeFields);
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
  assemble(c, with_mass_mom ? 0 : 4, with_mass_mom ? (with_forces ? 7 : 4) : 3, c->grid.gmass, c->grid.gmom, c->grid.gforce);
}

// GIMP: the 27-node stencils, one particle after the other.
void g2p_gimp(StepContext* c, bool remap) {
  const int Q = c->patch.patch_cells + 1 + 2 * c->patch.patch_halo;
  const int pn = patch_nodes(c);
  const int nn0 = c->grid.nn[0], nn1 = c->grid.nn[1];
  const CellDecoder dec(c);
  const StencilOffsets in_grid(nn0, nn1), in_buffer(Q, Q);
  for_filled_patches(c, [&](int q, const int q3[3], double* buf) {
    if (remap) zero_fields(buf, pn, 1, 3);
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
  if (remap) assemble(c, 1, 3, c->grid.gmass, c->grid.gmom, c->grid.gforce);
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
void mass_gradient_stencil27(StepContext* c) {
  const int Q = c->patch.patch_cells + 1 + 2 * c->patch.patch_halo;
  const int pn = patch_nodes(c);
  const CellDecoder dec(c);
  const StencilOffsets in_buffer(Q, Q);
  for_filled_patches(c, [&](int q, const int q3[3], double* buf) {
    zero_fields(buf, pn, 4, 3);
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
}

}  // namespace

const Transfer kStencil27Transfer = {p2g_stencil27, g2p_stencil27, stress_stencil27,
                                     mass_gradient_stencil27};

}  // namespace mpm3d
