// The trilinear particle loops of P2G, G2P and the stress stage. G2P and the stress stage
// are written once for a lane type (lanes.hpp): runs of kLanes consecutive particles of a
// patch list (or of a chunk, for the stress stage) go through the vector code, the rest
// one at a time through the same code with T = double. (P2G stays one particle at a time:
// its cost is the read-modify-write of 56 buffer values per particle, which must stay in
// particle order; staging its values in lanes measured slower.) A lane performs its particle's scalar operations in the
// scalar order, so the results are the scalar kernels' bits:
// - sums over the 8 nodes skip a light node by adding +0.0 in its place (a sum that
//   starts at +0.0 never holds -0.0 under round-to-nearest, so x + 0.0 == x);
// - scatters into the patch buffers stay one particle after the other, in list order,
//   so every node sums its contributions in the canonical order.
// The trilinear family (trilinear.cpp) and the bin stage (stage_bin.cpp) instantiate these for
// the baseline instruction set, transfer_lanes_avx2.cpp for AVX2 (the *_avx2 functions
// declared at the end); each unit has its own copies (internal linkage).
#pragma once
#include <cstring>
#include "core/lanes.hpp"
#include "materials/constitution.hpp"
#include "materials/constitution_lanes.hpp"
#include "transfer/transfer_common.hpp"

namespace mpm3d {
namespace {

constexpr int kLanes = kStressLanes;

// Binning of the particles [lo, hi): cell on the deck's lattice, then in the window (the
// same bits for any window), local coordinates, patch (patch_of, -1 outside or of the
// other contact component). Returns the number outside the window. The divisions and
// floors in lanes; the rest one lane after the other, with the scalar code's side effects
// (an outside particle keeps the local coordinates of the axes tested before the one it
// fails on). Rule tl_shape=centre: local coordinates 0.5 (trilinear TLmp).
template <class VL>
int bin_range(const StepContext* c, int lo, int hi, int* patch_of) {
  typedef decltype(VL::splat(0.0)) T;
  const bool filter = c->contact.only_comp > 0;
  const FastDiv divP{uint32_t(c->patch.patch_cells)};
  int outside = 0;
  auto finish = [&](int p, const double* t, const double* fl) {
    if (filter && other_component(c, p)) {
      patch_of[p] = -1;
      return;
    }
    int idx[3];
    for (int a = 0; a < 3; ++a) {
      const double f0 = double(c->grid.cell_off[a]);
      if (!(fl[a] >= f0 && fl[a] < f0 + double(c->grid.nc[a]))) {  // also catches NaN
        c->part.cell[p] = -1;
        patch_of[p] = -1;
        ++outside;
        return;
      }
      idx[a] = int(fl[a]) - c->grid.cell_off[a];
      c->part.lx[3 * p + a] = t[a] - fl[a];
    }
    c->part.cell[p] = idx[0] + c->grid.nc[0] * (idx[1] + c->grid.nc[1] * idx[2]);
    patch_of[p] = int(divP(uint32_t(idx[0]))) +
                  c->patch.npd[0] * (int(divP(uint32_t(idx[1]))) + c->patch.npd[1] * int(divP(uint32_t(idx[2]))));
  };
  int p = lo;
  for (; p + kLanes <= hi; p += kLanes) {
    int i3[kLanes];
    for (int i = 0; i < kLanes; ++i) i3[i] = 3 * (p + i);
    double t[3][kLanes], fl[3][kLanes];
    for (int a = 0; a < 3; ++a) {
      const T ta = (VL::gather(c->part.xbin + a, i3) - c->grid.origin[a]) / c->grid.h;
      VL::store(t[a], ta);
      VL::store(fl[a], VL::floor(ta));
    }
    for (int i = 0; i < kLanes; ++i) {
      const double ti[3] = {t[0][i], t[1][i], t[2][i]}, fi[3] = {fl[0][i], fl[1][i], fl[2][i]};
      finish(p + i, ti, fi);
    }
  }
  for (; p < hi; ++p) {
    double ti[3], fi[3];
    for (int a = 0; a < 3; ++a) {
      ti[a] = (c->part.xbin[3 * p + a] - c->grid.origin[a]) / c->grid.h;
      fi[a] = std::floor(ti[a]);
    }
    finish(p, ti, fi);
  }
  // Rule tl_shape=centre, trilinear TLmp: every particle at the centre of its reference cell,
  // as in the current program, which never sets those natural coordinates (its allocation
  // leaves them 0).
  if (c->method.tl && c->rules.tl_shape && c->method.family == TRANSFER_TRILINEAR)
    for (p = lo; p < hi; ++p)
      if (patch_of[p] >= 0)
        for (int a = 0; a < 3; ++a) c->part.lx[3 * p + a] = 0.5;
  return outside;
}

template <class TL>
inline void load_lx(const StepContext* c, const int* part, decltype(TL::splat(0.0)) lx[3]) {
  int i3[kLanes];
  for (int i = 0; i < TL::W; ++i) i3[i] = 3 * part[i];
  for (int d = 0; d < 3; ++d) lx[d] = TL::gather(c->part.lx + d, i3);
}

// P2G of patch q into its buffer (zeroed here): mass and momentum and/or forces, one
// particle after the other in list order (the canonical order of every node's sum). The
// cases are compile-time flags so the 8-node loop unrolls with nothing left to test.
template <bool kMassMom, bool kForces, bool kBody>
void p2g_patch_fields(const StepContext* c, const CellDecoder& dec, int q) {
  const int P = c->patch.patch_cells;
  int q3[3];
  patch_coords(c, q, q3);
  double* buf = patch_buffer(c, c->patch.patch_slot[q]);
  zero_fields_in_grid(c, q3, buf, 0, kNodeFields);
  int local[8];
  for (int k = 0; k < 8; ++k) local[k] = patch_local(P, k) * kNodeFields;
  for (int idx = c->patch.patch_start[q]; idx < c->patch.patch_start[q + 1]; ++idx) {
    const int p = c->patch.patch_part[idx];
    double N[8], G[24];
    shape_linear_lanes<double>(c->part.lx + 3 * p, c->grid.inv_h, N, G);
    double* pb = buf + size_t(patch_base(c, dec, q3, c->part.cell[p])) * kNodeFields;
    p2g_particle<8>(c, p, N, G, kMassMom, kForces, kBody, [&](int k) { return pb + local[k]; });
  }
}

template <class VL>
void p2g_patch(const StepContext* c, const CellDecoder& dec, int q, bool with_mass_mom, bool with_forces) {
  const bool body = c->method.has_body_force != 0;
  if (with_mass_mom && with_forces)
    body ? p2g_patch_fields<true, true, true>(c, dec, q) : p2g_patch_fields<true, true, false>(c, dec, q);
  else if (with_mass_mom)
    p2g_patch_fields<true, false, false>(c, dec, q);
  else
    body ? p2g_patch_fields<false, true, true>(c, dec, q) : p2g_patch_fields<false, true, false>(c, dec, q);
}

// One node's share of a G2P in lanes (grid nodes n1, their vector entries n3 = 3 n1, the
// lanes' weights w): acc[0..2] += w f / m, acc[3..5] += w p / m where the node is above the
// mass cut-off; a light node adds +0.0, which leaves a sum started at +0.0 unchanged.
template <class TL, class T>
__attribute__((always_inline)) inline void g2p_node_lanes(const StepContext* c, const int* n1, const int* n3, T w,
                                                          T acc[6]) {
  const T zero = TL::splat(0.0);
  const T m = TL::gather(c->grid.gmass, n1);
  const auto heavy = m > c->grid.mass_cutoff;
  const T r = w / m;
  for (int d = 0; d < 3; ++d) acc[d] = acc[d] + TL::select(heavy, TL::gather(c->grid.gforce + d, n3) * r, zero);
  for (int d = 0; d < 3; ++d) acc[3 + d] = acc[3 + d] + TL::select(heavy, TL::gather(c->grid.gmom + d, n3) * r, zero);
}

// The end of a G2P in lanes (advance_particle's operations): v += acc[0..2] dt_int,
// x += acc[3..5] dt for the particles part with vector entries i3 = 3 part; the new
// velocities in v. While the still bits are kept (StepContext::still), bit 1 of each
// particle's says whether v and x kept every bit.
template <class TL, class T>
__attribute__((always_inline)) inline void advance_lanes(StepContext* c, const int* part, const int* i3,
                                                         const T acc[6], T v[3]) {
  const double dt = c->clock.dt, dt_int = c->clock.dt_int;
  T x[3];
  for (int d = 0; d < 3; ++d) {
    v[d] = TL::gather(c->part.v + d, i3) + acc[d] * dt_int;
    x[d] = TL::gather(c->part.x + d, i3) + acc[3 + d] * dt;
  }
  unsigned char* still = c->rest.still;
  for (int i = 0; i < TL::W; ++i) {
    uint64_t changed = 0;
    for (int d = 0; d < 3; ++d) {
      const double vn = TL::get(v[d], i), xn = TL::get(x[d], i);
      if (still) changed |= bits_changed(vn, c->part.v + i3[i] + d) | bits_changed(xn, c->part.x + i3[i] + d);
      c->part.v[i3[i] + d] = vn;
      c->part.x[i3[i] + d] = xn;
    }
    if (still) still[part[i]] = static_cast<unsigned char>((still[part[i]] & 1u) | (changed == 0 ? 2u : 0u));
  }
}

// G2P of TL::W particles: v += a dt_int, x += u dt from the grid (a = f/m, u = p/m summed
// with the weights); with the MUSL remap their momenta m_p N_k v_p per node into rm.
template <class TL>
void g2p_values(StepContext* c, const CellDecoder& dec, const int* part, bool remap,
                double rm[3][8][kLanes], int first) {
  typedef decltype(TL::splat(0.0)) T;
  T lx[3], N[8], G[24];
  load_lx<TL>(c, part, lx);
  shape_linear_lanes(lx, c->grid.inv_h, N, G);
  int base[kLanes], i3[kLanes], n1[kLanes], n3[kLanes];
  for (int i = 0; i < TL::W; ++i) base[i] = base_node(c, dec, c->part.cell[part[i]]), i3[i] = 3 * part[i];
  T acc[6];
  for (int d = 0; d < 6; ++d) acc[d] = TL::splat(0.0);
  for (int k = 0; k < 8; ++k) {
    const int off = node_of(c, 0, k);  // local node k from the base node
    for (int i = 0; i < TL::W; ++i) n1[i] = base[i] + off, n3[i] = 3 * n1[i];
    g2p_node_lanes<TL>(c, n1, n3, N[k], acc);
  }
  T v[3];
  advance_lanes<TL>(c, part, i3, acc, v);
  if (!remap) return;
  const T mp = TL::gather(c->part.mass, part);
  for (int k = 0; k < 8; ++k) {
    const T mn = mp * N[k];
    for (int d = 0; d < 3; ++d) TL::store(rm[d][k] + first, mn * v[d]);
  }
}

// G2P of the particles of patch q; MUSL: their remapped momenta into the patch buffer.
template <class VL>
void g2p_patch(StepContext* c, const CellDecoder& dec, int q, bool remap) {
  const int P = c->patch.patch_cells;
  int q3[3];
  patch_coords(c, q, q3);
  double* buf = patch_buffer(c, c->patch.patch_slot[q]);
  if (remap) zero_fields_in_grid(c, q3, buf, 1, 3);
  int local[8];
  for (int k = 0; k < 8; ++k) local[k] = patch_local(P, k);
  double rm[3][8][kLanes];
  const int* list = c->patch.patch_part;
  for (int idx = c->patch.patch_start[q]; idx < c->patch.patch_start[q + 1];) {
    const int n = c->patch.patch_start[q + 1] - idx >= kLanes ? kLanes : 1;
    if (n == kLanes)
      g2p_values<VL>(c, dec, list + idx, remap, rm, 0);
    else
      g2p_values<ScalarLane>(c, dec, list + idx, remap, rm, 0);
    if (remap)
      for (int i = 0; i < n; ++i) {
        const int base = patch_base(c, dec, q3, c->part.cell[list[idx + i]]);
        for (int k = 0; k < 8; ++k) {
          // Fields 0-3 as one vector: field 0 (the mass, never -0.0, read by no remap) adds +0.0.
          double* b = buf + size_t(base + local[k]) * kNodeFields;
          typename LaneTypes<4>::D mm;
          std::memcpy(&mm, b, sizeof mm);
          mm = mm + typename LaneTypes<4>::D{0.0, rm[0][k][i], rm[1][k][i], rm[2][k][i]};
          std::memcpy(b, &mm, sizeof mm);
        }
      }
    idx += n;
  }
}

// Velocity gradients L[3a+b] = d v_a / d x_b of TL::W particles from the node velocities
// gvel, into b.L[.][first + i].
template <class TL>
void gradient_values(const StepContext* c, const CellDecoder& dec, const int* part, const double* gvel,
                     StressBlock& blk, int first) {
  typedef decltype(TL::splat(0.0)) T;
  T lx[3], N[8], G[24];
  load_lx<TL>(c, part, lx);
  shape_linear_lanes(lx, c->grid.inv_h, N, G);
  int base[kLanes], n1[kLanes], n3[kLanes];
  for (int i = 0; i < TL::W; ++i) base[i] = base_node(c, dec, c->part.cell[part[i]]);
  const double cutoff = c->grid.mass_cutoff;
  const T zero = TL::splat(0.0);
  T l[9];
  for (int r = 0; r < 9; ++r) l[r] = zero;
  for (int k = 0; k < 8; ++k) {
    const int off = node_of(c, 0, k);  // local node k from the base node
    for (int i = 0; i < TL::W; ++i) n1[i] = base[i] + off, n3[i] = 3 * n1[i];
    const auto heavy = TL::gather(c->grid.gmass, n1) > cutoff;
    const T v[3] = {TL::gather(gvel, n3), TL::gather(gvel + 1, n3), TL::gather(gvel + 2, n3)};
    for (int a = 0; a < 3; ++a)
      for (int d = 0; d < 3; ++d) l[3 * a + d] = l[3 * a + d] + TL::select(heavy, v[a] * G[3 * k + d], zero);
  }
  for (int r = 0; r < 9; ++r) TL::store(blk.L[r] + first, l[r]);
}

// Particle p's state into lane i of a stress batch, and back.
inline void stress_block_load(const StepContext* c, const MaterialParams& mp, int p, int i, StressBlock& b) {
  b.mass[i] = c->part.mass[p];
  b.vol[i] = c->part.vol[p];
  for (int s = 0; s < 6; ++s) b.sig[s][i] = c->part.sig[6 * p + s];
  b.epeff[i] = c->part.epeff[p];
  b.ie[i] = c->part.ie[p];
  b.temp[i] = c->part.temp ? c->part.temp[p] : 0.0;
  b.qv[i] = c->part.qv ? c->part.qv[p] : 0.0;
  b.burn[i] = c->part.tlight ? burn_fraction(mp, c->part.tlight[p], c->clock.time, c->rules.burn != 0) : 1.0;
  if (c->part.defgrad)
    for (int r = 0; r < 9; ++r) b.H[r][i] = c->part.defgrad[9 * size_t(p) + size_t(r)];
  if (c->part.pk1)
    for (int r = 0; r < 9; ++r) b.pk1[r][i] = c->part.pk1[9 * size_t(p) + size_t(r)];
}

// The stress state of lane i of b is that of particle p, bit for bit.
inline bool stress_state_same(const StepContext* c, int p, int i, const StressBlock& b) {
  auto same = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  bool s = same(c->part.vol[p], b.vol[i]) && same(c->part.epeff[p], b.epeff[i]) && same(c->part.ie[p], b.ie[i]);
  for (int k = 0; k < 6; ++k) s = s && same(c->part.sig[6 * p + k], b.sig[k][i]);
  if (c->part.temp) s = s && same(c->part.temp[p], b.temp[i]);
  if (c->part.qv) s = s && same(c->part.qv[p], b.qv[i]);
  if (c->part.defgrad)
    for (int r = 0; r < 9; ++r) s = s && same(c->part.defgrad[9 * size_t(p) + size_t(r)], b.H[r][i]);
  if (c->part.pk1)
    for (int r = 0; r < 9; ++r) s = s && same(c->part.pk1[9 * size_t(p) + size_t(r)], b.pk1[r][i]);
  return s;
}

// Still bit 0 of the particles part[0 .. n), lanes 0 .. n of b before they are stored: the
// update changed no bit of the stress state (and an explosive is unlit, so that the next
// step's burn fraction is the same zero).
inline void mark_stress_still(StepContext* c, const MaterialParams& mp, const int* part, int n, const StressBlock& b) {
  const bool unlit_or_inert = mp.type != MAT_HIEX;
  for (int i = 0; i < n; ++i) {
    const bool same = stress_state_same(c, part[i], i, b) && (unlit_or_inert || b.burn[i] == 0.0);
    c->rest.still[part[i]] = static_cast<unsigned char>((c->rest.still[part[i]] & 2u) | (same ? 1u : 0u));
  }
}

inline void stress_block_store(StepContext* c, int p, int i, const StressBlock& b) {
  c->part.vol[p] = b.vol[i];
  for (int s = 0; s < 6; ++s) c->part.sig[6 * p + s] = b.sig[s][i];
  c->part.epeff[p] = b.epeff[i];
  c->part.ie[p] = b.ie[i];
  if (c->part.temp) c->part.temp[p] = b.temp[i];
  if (c->part.qv) c->part.qv[p] = b.qv[i];
  if (c->part.defgrad)
    for (int r = 0; r < 9; ++r) c->part.defgrad[9 * size_t(p) + size_t(r)] = b.H[r][i];
  if (c->part.pk1)
    for (int r = 0; r < 9; ++r) c->part.pk1[9 * size_t(p) + size_t(r)] = b.pk1[r][i];
}

// The stress stage of the particles list[0..count) (trilinear): velocity gradients and the
// stress update, kLanes consecutive active particles of one material at a time.
template <class VL>
void stress_list(StepContext* c, const CellDecoder& dec, const int* list, int count, const double* gvel,
                 const StressBlockArgs& args) {
  const bool filter = c->contact.only_comp > 0;
  StressBlock b;
  int part[kLanes];
  int n = 0, mat = -1;
  auto flush = [&]() {
    const MaterialParams& mp = c->part.mats[mat];
    if (n == kLanes) {
      gradient_values<VL>(c, dec, part, gvel, b, 0);
    } else {
      for (int i = 0; i < n; ++i) gradient_values<ScalarLane>(c, dec, part + i, gvel, b, i);
    }
    for (int i = 0; i < n; ++i) stress_block_load(c, mp, part[i], i, b);
    if (n == kLanes)
      stress_block_lanes<VL>(mp, b, 0, args);
    else
      for (int i = 0; i < n; ++i) stress_block_lanes<ScalarLane>(mp, b, i, args);
    if (c->rest.still) mark_stress_still(c, mp, part, n, b);
    for (int i = 0; i < n; ++i) stress_block_store(c, part[i], i, b);
    n = 0;
  };
  for (int j = 0; j < count; ++j) {
    const int p = list[j];
    if (c->part.cell[p] < 0) continue;
    if (filter && other_component(c, p)) continue;
    if (n > 0 && c->part.mat[p] != mat) flush();
    mat = c->part.mat[p];
    part[n++] = p;
    if (n == kLanes) flush();
  }
  if (n > 0) flush();
}

}  // namespace

// transfer_lanes_avx2.cpp: the kernels above compiled for AVX2, for the CPUs where
// lanes_use_avx2() (constitution.cpp) says so.
int bin_range_avx2(const StepContext* c, int lo, int hi, int* patch_of);
void p2g_patch_avx2(const StepContext* c, int q, bool with_mass_mom, bool with_forces);
void g2p_patch_avx2(StepContext* c, int q, bool remap);
void stress_list_avx2(StepContext* c, const int* list, int count, const double* gvel,
                      const StressBlockArgs& args);

}  // namespace mpm3d
