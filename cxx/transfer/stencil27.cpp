// The 27-node family (transfer.hpp): uGIMP (shape 1) and the quadratic B-spline (shape 2),
// the stencil of 3 nodes per axis (gimp_stencil, patch_index.hpp), patch buffers with a
// halo of one node layer, one particle after the other.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <vector>

#include "transfer/stencil27_lanes.hpp"
#include "transfer/stress_loop.hpp"
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

// The block kernels of stencil27_lanes.hpp, in AVX2 lanes where the CPU has them: the
// stencils of particles part[0 .. n) into s; their G2P (node k of a stencil at its first
// node + of[k]); their velocity gradients from the node velocities gvel into L.
inline void stencils(const StepContext* c, const CellDecoder& dec, const int* part, int n, bool gradients,
                     Stencil27Block& s) {
  for (int i = 0; i < n; ++i) dec(c->part.cell[part[i]], s.ci[0][i], s.ci[1][i], s.ci[2][i]);
  if (lanes_use_avx2())
    stencil27_block_avx2(c, part, n, gradients, s);
  else
    stencil27_block<VectorLane<kStencilLanes>>(c, part, n, gradients, s);
}

inline void g2p_stencils(StepContext* c, const Stencil27Block& s, const int* part, int n, const int* of) {
  if (lanes_use_avx2())
    g2p27_block_avx2(c, s, part, n, of);
  else
    g2p27_block<VectorLane<kStencilLanes>>(c, s, part, n, of);
}

inline void gradients_of_stencils(const StepContext* c, const Stencil27Block& s, int n, const double* gvel,
                                  const int* of, double L[9][kStencilLanes]) {
  if (lanes_use_avx2())
    gradient27_block_avx2(c, s, n, gvel, of, L);
  else
    gradient27_block<VectorLane<kStencilLanes>>(c, s, n, gvel, of, L);
}

// Buffer node index, in patch q3's buffer (halo H), of lane i's first stencil node.
inline int block_patch_corner(const StepContext* c, const int q3[3], const Stencil27Block& s, int i) {
  const int P = c->patch.patch_cells, H = c->patch.patch_halo, Q = P + 1 + 2 * H;
  return (s.ci[0][i] + s.o[0][i] - q3[0] * P + H) +
         Q * ((s.ci[1][i] + s.o[1][i] - q3[1] * P + H) + Q * (s.ci[2][i] + s.o[2][i] - q3[2] * P + H));
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

// G2P with the 27-node stencils, four particles at a time; the MUSL remap one particle after
// the other, in list order.
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
      const int* part = c->patch.patch_part + idx;
      stencils(c, dec, part, n, false, s);
      g2p_stencils(c, s, part, n, in_grid.of);
      if (remap)
        for (int i = 0; i < n; ++i) {
          double* corner = buf + size_t(block_patch_corner(c, q3, s, i)) * kNodeFields;
          remap_particle<27, kStencilLanes>(c, part[i], &s.N[0][i],
                                            [&](int k) { return corner + size_t(in_buffer.of[k]) * kNodeFields; });
        }
    }
  });
}

void g2p_stencil27(StepContext* c, bool remap) {
  g2p_gimp(c, remap);
  if (remap) assemble(c, 1, 3, c->grid.gmass, c->grid.gmom, c->grid.gforce, touched_boxes(c));
}

// The velocity gradients of the stress stage from the node velocities gvel
// (gradient27_lanes, stencil27_lanes.hpp). One per run of entries [first, end) of a list
// (null: the particles themselves): the stencils and gradients of the next kStencilLanes
// particles the stress loop takes (stress_run's test) at a time, handed out one particle
// after the other.
struct BlockGradient {
  const StepContext* c;
  const StencilOffsets* in_grid;
  const double* gvel;
  const int* list;
  int end;
  Stencil27Block s;
  double L[9][kStencilLanes];
  int part[kStencilLanes];
  int n = 0, lane = 0;

  void operator()(const CellDecoder& dec, int e, int p, double* Lp) {
    if (lane == n || part[lane] != p) {
      n = 0;
      lane = 0;
      for (int j = e; j < end && n < kStencilLanes; ++j) {
        const int q = list ? list[j] : j;
        if (c->part.cell[q] >= 0 && !other_component(c, q)) part[n++] = q;
      }
      stencils(c, dec, part, n, true, s);
      gradients_of_stencils(c, s, n, gvel, in_grid->of, L);
    }
    const int i = lane++;
    for (int r = 0; r < 9; ++r) Lp[r] = L[r][i];
  }
};

void stress_stencil27(StepContext* c, const double* gvel) {
  const StencilOffsets in_grid(c->grid.nn[0], c->grid.nn[1]);
  stress_particles(c, [&](const int* list, int end) { return BlockGradient{c, &in_grid, gvel, list, end, {}, {}, {}}; });
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
