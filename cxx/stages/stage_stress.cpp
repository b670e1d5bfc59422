// The stress stage: node velocities, each particle's velocity gradient (trilinear in lanes,
// or 27-node GIMP), and the constitutive update of strain and spin increments, volume,
// stress and internal energy (stress_block, constitution.cpp).
#include <algorithm>

#include "materials/constitution.hpp"
#include "stages/stage_common.hpp"
#include "stages/stage_sg.hpp"
#include "transfer/transfer_lanes.hpp"
#include "stages/update_step.hpp"

namespace mpm3d {
namespace {

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
    if (!(c->gmass[n] > c->mass_cutoff)) continue;
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

// What the constitutive update takes from the context besides the particles.
inline StressBlockArgs stress_args(const StepContext* c) {
  return StressBlockArgs{c->dt, c->temp != nullptr, c->qv != nullptr, c->bulk_q1, c->bulk_q2, c->h, c->uvf != 0,
                         c->tl != 0};
}

// The particle loop with the trilinear shape functions: chunks of the patch lists, each
// thread over its balanced range; the velocity gradients (gradient_values) and the update
// of kLanes consecutive particles of one material at a time (stress_list,
// transfer_lanes.hpp). Each particle's update is its own, so the chunks cross patch ends.
void stress_trilinear(StepContext* c, const double* gvel) {
  const CellDecoder dec(c);
  const StressBlockArgs args = stress_args(c);
  const bool avx2 = lanes_use_avx2();
  for_list_chunks(c, [&](int first, int count) {
    const int* list = c->patch_part + first;
    if (avx2)
      stress_list_avx2(c, list, count, gvel, args);
    else
      stress_list<VectorLane<kLanes>>(c, dec, list, count, gvel, args);
  });
}

// The constitutive update of the particles list[i] (i where list is null), i in
// [first, first + count): velocity gradients one particle at a time (gradient(dec, i, p, L)), the update
// of kStressLanes consecutive particles of one material at a time (stress_block; a shorter
// run lane by lane, which gives the same bits).
template <class Gradient>
void stress_run(StepContext* c, const CellDecoder& dec, const StressBlockArgs& args, const int* list, int first,
                int count, Gradient& gradient) {
  const bool filter = c->only_comp > 0;
  StressBlock b;
  int part[kStressLanes];
  int n = 0, mat = -1;
  auto flush = [&]() {
    const MaterialParams& mp = c->mats[mat];
    if (n == kStressLanes)
      stress_block(mp, b, args);
    else
      for (int i = 0; i < n; ++i) stress_block_lane(mp, b, i, args);
    if (c->sg_still) {
      // Still bit 0: the update changed no bit of the stress state (and an explosive is
      // unlit, so that the next step's burn fraction is the same zero).
      const bool unlit_or_inert = mp.type != MAT_HIEX;
      for (int i = 0; i < n; ++i) {
        const bool same = stress_state_same(c, part[i], i, b) && (unlit_or_inert || b.burn[i] == 0.0);
        c->sg_still[part[i]] = static_cast<unsigned char>((c->sg_still[part[i]] & 2u) | (same ? 1u : 0u));
      }
    }
    for (int i = 0; i < n; ++i) stress_block_store(c, part[i], i, b);
    n = 0;
  };
  for (int i = first; i < first + count; ++i) {
    const int p = list ? list[i] : i;
    if (c->cell[p] < 0) continue;
    if (filter && other_component(c, p)) continue;
    if (n > 0 && c->mat[p] != mat) flush();
    mat = c->mat[p];
    double L[9];
    gradient(dec, i, p, L);
    for (int r = 0; r < 9; ++r) b.L[r][n] = L[r];
    stress_block_load(c, c->mats[mat], p, n, b);
    part[n++] = p;
    if (n == kStressLanes) flush();
  }
  if (n > 0) flush();
}

// The particle loop of the 27-node stencils: fixed chunks of the particles.
template <class Gradient>
void stress_particles(StepContext* c, Gradient&& gradient) {
  const CellDecoder dec(c);
  const StressBlockArgs args = stress_args(c);
  constexpr int kChunk = 256;
  const int nchunk = (c->np + kChunk - 1) / kChunk;
#pragma omp parallel for schedule(dynamic, 1)
  for (int ch = 0; ch < nchunk; ++ch)
    stress_run(c, dec, args, nullptr, ch * kChunk, std::min(c->np, (ch + 1) * kChunk) - ch * kChunk, gradient);
}

// sgmp: the patch lists in chunks, each entry's gradient from its weights of this step
// (sg_ensure_weights).
void stress_sg(StepContext* c) {
  sg_ensure_weights(c, false);
  const CellDecoder dec(c);
  const StressBlockArgs args = stress_args(c);
  auto gradient = [&](const CellDecoder&, int e, int, double* L) {
    sg_velocity_gradient(c, c->sg_cell + 8 * size_t(e), sg_p2g_weights(c, e), L);
  };
  if (c->sg_rest) {  // the patches not at rest, shared by their work
    for_patches(c, [&](int q) {
      if (patch_at_rest(c, q)) return;
      const int first = c->patch_start[q];
      stress_run(c, dec, args, c->patch_part, first, c->patch_start[q + 1] - first, gradient);
    });
    return;
  }
  for_list_chunks(c, [&](int first, int count) { stress_run(c, dec, args, c->patch_part, first, count, gradient); });
}

// Node velocities v_i = p_i / m_i at the nodes above the mass cut-off, once per node (the
// same division as per particle, so the same bits). They are kept in the force array,
// which no stage reads again before the next p2g or forces stage overwrites it (USF:
// stress runs before forces).
double* node_velocities(StepContext* c) {
  const double cutoff = c->mass_cutoff;
  double* gvel = c->gforce;
  for_patches(c, [&](int q) {
    if (patch_at_rest(c, q)) return;
    const OwnedNodes o = owned_nodes(c, q);
    if (!o.active) return;
    for_owned_nodes(c, o, [&](int n) {
      const double m = c->gmass[n];
      if (!(m > cutoff)) return;
      for (int a = 0; a < 3; ++a) gvel[3 * n + a] = c->gmom[3 * n + a] / m;
    });
  });
  return gvel;
}

}  // namespace
}  // namespace mpm3d

using namespace mpm3d;

// Node velocities; per particle L = sum_i v_i (x) G_ip over the nodes above the mass
// cut-off, then the constitutive update: strain and spin increments, volume, Jaumann
// rotation, stress return, EOS, bulk viscosity, internal energy.
extern "C" void mpm3d_cxx_stress(StepContext* c) {
  const double* gvel = node_velocities(c);
  if (c->sg) {
    sg_cell_gradients(c, gvel);
    stress_sg(c);
  } else if (c->shape != 0) {
    const StencilOffsets in_grid(c->nn[0], c->nn[1]);
    stress_particles(c, [&](const CellDecoder& dec, int, int p, double* L) {
      velocity_gradient_gimp(c, dec, in_grid, p, gvel, L);
    });
  } else {
    stress_trilinear(c, gvel);
  }
}
