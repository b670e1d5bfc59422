// The g2p stage: particle velocities and positions from the grid (trilinear in the lane
// kernels' patch loop, or 27-node GIMP), and with MUSL the remap of the particle momenta
// to the nodes.
#include <cstddef>

#include "stages/stage_common.hpp"
#include "transfer/transfer_lanes.hpp"
#include "stages/update_step.hpp"

namespace mpm3d {
namespace {

// Trilinear: each thread over its balanced range of patches, 4 particles per vector.
void g2p_trilinear(StepContext* c, bool remap) {
  const bool avx2 = lanes_use_avx2();
  for_patches(c, [&](int q) {
    if (c->patch_slot[q] < 0) return;
    if (avx2)
      g2p_patch_avx2(c, q, remap);
    else
      g2p_patch<VectorLane<kLanes>>(c, CellDecoder(c), q, remap);
  });
}

// GIMP: the 27-node stencils, one particle after the other.
void g2p_gimp(StepContext* c, bool remap) {
  const int Q = c->patch_cells + 1 + 2 * c->patch_halo;
  const int pn = patch_nodes(c);
  const int nn0 = c->nn[0], nn1 = c->nn[1];
  const CellDecoder dec(c);
  const StencilOffsets in_grid(nn0, nn1), in_buffer(Q, Q);
  for_filled_patches(c, [&](int q, const int q3[3], double* buf) {
    if (remap) zero_fields(buf, pn, 1, 3);
    for (int idx = c->patch_start[q]; idx < c->patch_start[q + 1]; ++idx) {
      const int p = c->patch_part[idx];
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

}  // namespace
}  // namespace mpm3d

using namespace mpm3d;

// v_p += dt_int sum_i N_ip f_i / m_i, x_p += dt sum_i N_ip p_i / m_i over the nodes above
// the mass cut-off; MUSL: p_i = sum_p m_p v_p N_ip again (patch buffers, assembly) and the
// boundary conditions on the momenta.
extern "C" void mpm3d_cxx_g2p(StepContext* c) {
  const bool remap = c->scheme == SCHEME_MUSL;
  if (c->sg) {
    sg_g2p(c, remap);
    if (remap) apply_bc(c, c->gmom);
    return;
  }
  if (c->shape != 0)
    g2p_gimp(c, remap);
  else
    g2p_trilinear(c, remap);
  if (remap) {
    assemble(c, 1, 3, c->gmass, c->gmom, c->gforce);
    apply_bc(c, c->gmom);
  }
}
