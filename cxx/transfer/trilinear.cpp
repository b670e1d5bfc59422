// The trilinear family (transfer.hpp): 8 nodes per particle, the patch buffers without a
// halo, the hot loops in vector lanes (transfer_lanes.hpp, with their AVX2 build).
#include <cstddef>

#include "transfer/transfer.hpp"
#include "transfer/transfer_common.hpp"
#include "transfer/transfer_lanes.hpp"

namespace mpm3d {
namespace {

// Scatter of mass, momentum and (optionally) forces of every particle into its patch
// buffer, one particle after the other in list order (the canonical order of each node's
// sum): each thread over its balanced range of patches; then the assembly.
void p2g_trilinear(StepContext* c, bool with_mass_mom, bool with_forces) {
  const bool avx2 = lanes_use_avx2();
  for_patches(c, [&](int q) {
    if (c->patch.patch_slot[q] < 0 || rest_around(c, q)) return;  // empty, or read by no assembly
    if (avx2)
      p2g_patch_avx2(c, q, with_mass_mom, with_forces);
    else
      p2g_patch<VectorLane<kLanes>>(c, CellDecoder(c), q, with_mass_mom, with_forces);
  });
  assemble_p2g(c, with_mass_mom, with_forces);
}

// Trilinear: each thread over its balanced range of patches, 4 particles per vector. A
// patch at rest whose remapped momenta no assembly reads (rest_around) is left as it is.
void g2p_trilinear_particles(StepContext* c, bool remap) {
  const bool avx2 = lanes_use_avx2();
  for_patches(c, [&](int q) {
    if (c->patch.patch_slot[q] < 0 || rest_around(c, q)) return;
    if (avx2)
      g2p_patch_avx2(c, q, remap);
    else
      g2p_patch<VectorLane<kLanes>>(c, CellDecoder(c), q, remap);
  });
}

void g2p_trilinear(StepContext* c, bool remap) {
  g2p_trilinear_particles(c, remap);
  if (remap) assemble(c, 1, 3, c->grid.gmass, c->grid.gmom, c->grid.gforce);
}

// The particle loop with the trilinear shape functions: chunks of the patch lists, each
// thread over its balanced range; the velocity gradients (gradient_values) and the update
// of kLanes consecutive particles of one material at a time (stress_list,
// transfer_lanes.hpp). Each particle's update is its own, so the chunks cross patch ends.
void stress_trilinear(StepContext* c, const double* gvel) {
  const CellDecoder dec(c);
  const StressBlockArgs args = stress_args(c);
  const bool avx2 = lanes_use_avx2();
  auto run = [&](int first, int count) {
    const int* list = c->patch.patch_part + first;
    if (avx2)
      stress_list_avx2(c, list, count, gvel, args);
    else
      stress_list<VectorLane<kLanes>>(c, dec, list, count, gvel, args);
  };
  for_stress_lists(c, run);
}

}  // namespace

// Contact: the mass gradients with the trilinear shape functions (transfer.hpp).
const int* mass_gradient_trilinear(StepContext* c) {
  const int P = c->patch.patch_cells;
  const CellDecoder dec(c);
  for_filled_patches(c, [&](int q, const int q3[3], double* buf) {
    zero_fields_in_grid(c, q3, buf, 4, 3);
    for (int idx = c->patch.patch_start[q]; idx < c->patch.patch_start[q + 1]; ++idx) {
      const int p = c->patch.patch_part[idx];
      const double mp = c->part.mass[p];
      double N[8], G[24];
      shape_linear(c->part.lx + 3 * p, c->grid.inv_h, N, G);
      const int base = patch_base(c, dec, q3, c->part.cell[p]);
      for (int k = 0; k < 8; ++k) {
        double* b = buf + size_t(base + patch_local(P, k)) * kNodeFields;
        const double* g = G + 3 * k;
        b[4] += mp * g[0];
        b[5] += mp * g[1];
        b[6] += mp * g[2];
      }
    }
  });
  return nullptr;
}

const Transfer kTrilinearTransfer = {p2g_trilinear, g2p_trilinear, stress_trilinear,
                                     mass_gradient_trilinear};

}  // namespace mpm3d
