// What the transfer families share with each other and with the stages above them: the
// scalar P2G and G2P of one particle, the patch and buffer loops, and the canonical
// assembly (assembly.cpp) that ends every scatter.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "core/grid.hpp"
#include "core/lanes.hpp"
#include "core/patch_index.hpp"
#include "core/patch_loops.hpp"
#include "core/step_state.hpp"
#include "materials/constitution.hpp"

namespace mpm3d {

// Canonical assembly (docs/DESIGN.md section 4): each node's value is 0.0 plus the values of
// the non-empty patches holding it, in ascending patch index (x fastest, then y, z).
// Fields first..first+count-1 of the buffers go to dst_mass (field 0), dst_mom (1-3)
// and dst_force (4-6). Every node is written by exactly one owner patch, so owners run in
// parallel (for_patches). assembly.cpp.
// boxes (buffers with a halo): per slot the nodes [lo, hi) per axis, buffer-local, that the
// scatter wrote (every other node of the buffer is taken as zero: a sum that starts at
// +0.0 is the same without +0.0 terms); null: whole buffers.
void assemble(const StepContext* c, int first, int count, double* dst_mass, double* dst_mom,
              double* dst_force, const int* boxes = nullptr);

// The assembly that ends a P2G scatter of mass and momentum (with_mass_mom) and/or forces:
// fields 0-6, 0-3 or 4-6 into the node arrays.
inline void assemble_p2g(const StepContext* c, bool with_mass_mom, bool with_forces, const int* boxes = nullptr) {
  assemble(c, with_mass_mom ? 0 : 4, with_mass_mom ? (with_forces ? 7 : 4) : 3, c->grid.gmass, c->grid.gmom,
           c->grid.gforce, boxes);
}

// What the constitutive update takes from the context besides the particles.
inline StressBlockArgs stress_args(const StepContext* c) {
  return StressBlockArgs{c->clock.dt,        c->part.temp != nullptr, c->part.qv != nullptr,
                         c->method.bulk_q1,  c->method.bulk_q2,       c->grid.h,
                         c->method.uvf != 0, c->method.tl != 0,       c->rules};
}

namespace {

// True when particle p belongs to another component than the context's (contact).
inline bool other_component(const StepContext* c, int p) {
  return c->contact.only_comp > 0 && c->contact.body_comp[c->part.body[p]] != c->contact.only_comp;
}

// Fields first..first+count-1 of the pn nodes of a patch buffer set to zero.
inline void zero_fields(double* buf, int pn, int first, int count) {
  for (int ln = 0; ln < pn; ++ln)
    for (int f = first; f < first + count; ++f) buf[size_t(ln) * kNodeFields + f] = 0.0;
}

// Fields first..first+count-1 of the nodes of patch q3's buffer (no halo) that lie in the
// grid set to zero. The nodes beyond the grid's last layer are never written nor read (a
// column one cell thick uses 2 of 5 node layers a side axis), so they are not cleared.
inline void zero_fields_in_grid(const StepContext* c, const int q3[3], double* buf, int first, int count) {
  const int P = c->patch.patch_cells, Q = P + 1;
  int hi[3];
  for (int a = 0; a < 3; ++a) hi[a] = c->grid.nn[a] - q3[a] * P < Q ? c->grid.nn[a] - q3[a] * P : Q;
  for (int k = 0; k < hi[2]; ++k)
    for (int j = 0; j < hi[1]; ++j) {
      double* row = buf + size_t(Q * (j + Q * k)) * kNodeFields;
      if (count == kNodeFields)
        for (int i = 0; i < hi[0] * kNodeFields; ++i) row[i] = 0.0;
      else
        zero_fields(row, hi[0], first, count);
    }
}

// Buffer field f of node n in the grid arrays: 0 mass, 1-3 momentum, 4-6 force.
__attribute__((always_inline)) inline double& node_field(int f, size_t n, double* dst_mass, double* dst_mom,
                                                         double* dst_force) {
  return f == 0 ? dst_mass[n] : (f <= 3 ? dst_mom[3 * n + size_t(f - 1)] : dst_force[3 * n + size_t(f - 4)]);
}

// The node sums sum[0..count) of fields first.. into node n of the grid arrays: the last
// step of every assembly and reduction.
__attribute__((always_inline)) inline void store_node_fields(int first, int count, const double* sum, int n,
                                                             double* dst_mass, double* dst_mom, double* dst_force) {
  for (int f = 0; f < count; ++f) node_field(first + f, size_t(n), dst_mass, dst_mom, dst_force) = sum[f];
}

// f(n, k) for patch q and each patch n next to it, k = (dx + 1) + 3 (dy + 1) + 9 (dz + 1)
// its place among the 27 (13: q itself).
template <class F>
inline void for_patches_around(const StepContext* c, int q, F&& f) {
  int q3[3];
  patch_coords(c, q, q3);
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = q3[0] + dx, y = q3[1] + dy, z = q3[2] + dz;
        if (x < 0 || y < 0 || z < 0 || x >= c->patch.npd[0] || y >= c->patch.npd[1] || z >= c->patch.npd[2]) continue;
        f(x + c->patch.npd[0] * (y + c->patch.npd[1] * z), (dx + 1) + 3 * (dy + 1) + 9 * (dz + 1));
      }
}

// Patch q and its neighbours are at rest (StepContext::at_rest): no stage reads what q's
// particles would scatter (its buffer, its cell centres), so the scatters skip them.
inline bool rest_around(const StepContext* c, int q) {
  if (!patch_at_rest(c, q)) return false;
  bool all = true;
  for_patches_around(c, q, [&](int n, int) { all = all && patch_at_rest(c, n); });
  return all;
}

// f(q, q3, buf) for every non-empty patch q (coordinates q3, buffer buf) whose buffer some
// patch not at rest assembles (rest_around), each thread over its run of patches
// (for_patches): the 27-node stages and the contact's mass gradients.
template <class F>
inline void for_filled_patches(const StepContext* c, F&& f) {
  for_patches(c, [&](int q) {
    const int slot = c->patch.patch_slot[q];
    if (slot < 0 || rest_around(c, q)) return;
    int q3[3];
    patch_coords(c, q, q3);
    f(q, q3, patch_buffer(c, slot));
  });
}

// The body force of particle p: the point load (ramped with QuLo), the damping (Damp),
// gravity, in the current version's order when either of the first two is on.
__attribute__((always_inline)) inline void particle_body_force(const StepContext* c, int p, double fb[3]) {
  const double mp = c->part.mass[p];
  const double* vp = c->part.v + 3 * p;
  const double* g = c->part.gravity + 3 * c->part.body[p];
  if (c->method.load_ramp_time > 0.0 || c->method.damping > 0.0) {
    // Quasi-static loading, in the current version's order: the load (ramped until
    // load_ramp_time, c->clock.time being the end of this step), the damping, gravity.
    const bool ramp = c->method.load_ramp_time > 0.0 && c->clock.time < c->method.load_ramp_time;
    for (int a = 0; a < 3; ++a) {
      double f = 0.0;
      if (c->part.fext) f = ramp ? (c->part.fext[3 * p + a] / c->method.load_ramp_time) * c->clock.time : c->part.fext[3 * p + a];
      if (c->method.damping > 0.0) f = f - (c->method.damping * mp) * vp[a];
      fb[a] = f + mp * g[a];
    }
  } else {
    for (int a = 0; a < 3; ++a) {
      fb[a] = mp * g[a];
      if (c->part.fext) fb[a] = fb[a] + c->part.fext[3 * p + a];
    }
  }
}

// The internal force -(sigma V) g of one node with gradient g (sigma V in Voigt order xx yy
// zz yz xz xy), or under TLmp -(V0 P) g (kPk1: V0 P row-major, row a giving component a):
// the sgmp centres' gather; the particles' scatter takes the same operations in lanes
// (force_columns). One form for both costs: the gather building columns per cell ran the
// sgmp free soft beam 1.38 times as long (docs/PERFORMANCE.md).
template <bool kPk1>
__attribute__((always_inline)) inline void internal_force(const double* s, double gx, double gy, double gz,
                                                          double& fx, double& fy, double& fz) {
  if (kPk1) {
    fx = -((s[0] * gx + s[1] * gy) + s[2] * gz);
    fy = -((s[3] * gx + s[4] * gy) + s[5] * gz);
    fz = -((s[6] * gx + s[7] * gy) + s[8] * gz);
  } else {
    fx = -((s[0] * gx + s[5] * gy) + s[4] * gz);
    fy = -((s[5] * gx + s[1] * gy) + s[3] * gz);
    fz = -((s[4] * gx + s[3] * gy) + s[2] * gz);
  }
}

// internal_force's operations for all three components at once: columns col[0..2] with
// -((col[0] gx + col[1] gy) + col[2] gz) giving component a in lane a (lane 3: +0.0 terms).
template <bool kPk1>
__attribute__((always_inline)) inline void force_columns(const double* s, LaneTypes<4>::D col[3]) {
  typedef LaneTypes<4>::D D4;
  if (kPk1) {
    col[0] = D4{s[0], s[3], s[6], 0.0};
    col[1] = D4{s[1], s[4], s[7], 0.0};
    col[2] = D4{s[2], s[5], s[8], 0.0};
  } else {
    col[0] = D4{s[0], s[5], s[4], 0.0};
    col[1] = D4{s[5], s[1], s[3], 0.0};
    col[2] = D4{s[4], s[3], s[2], 0.0};
  }
}

// P2G contributions of particle p (weights N, gradients G) added to its kNodes nodes (8
// trilinear, 27 GIMP), node(k) the 7 fields of stencil node k: mass and momentum
// (with_mass_mom) and the force -V sigma G + N (m g + f_ext) (with_forces; body forces with
// has_body_force). Used by the trilinear patch scatter (constant flags, so the loop
// unrolls) and the GIMP scatter. Node k's weight is N[k S], its gradient G[(3 k + d) S]
// (S = kStride: 1, or the lane count of a block of stencils).
template <int kNodes, int kStride = 1, class NodeOf>
__attribute__((always_inline)) inline void p2g_particle(const StepContext* c, int p, const double* N,
                                                        const double* G, bool with_mass_mom, bool with_forces,
                                                        bool with_body, NodeOf node) {
  typedef LaneTypes<4>::D D4;
  const double mp = c->part.mass[p];
  const double* vp = c->part.v + 3 * p;
  // (1, v): m N (1, v) is the node's mass and momentum share in one vector (m N 1.0 == m N).
  const D4 one_v = {1.0, vp[0], vp[1], vp[2]};
  // The force -(sigma V) g (TLmp: -(V0 P) g) as columns (force_columns), and the body force.
  D4 col[3] = {}, fb4 = {};
  if (with_forces) {
    if (c->part.pk1) {
      force_columns<true>(c->part.pk1 + 9 * size_t(p), col);
    } else {
      const double volp = c->part.vol[p];
      double vs[6];
      for (int s = 0; s < 6; ++s) vs[s] = c->part.sig[6 * p + s] * volp;
      force_columns<false>(vs, col);
    }
    if (with_body) {
      double fb[3];
      particle_body_force(c, p, fb);
      fb4 = D4{fb[0], fb[1], fb[2], 0.0};
    }
  }
  for (int k = 0; k < kNodes; ++k) {
    double* b = node(k);
    if (with_mass_mom) {
      D4 mm;
      std::memcpy(&mm, b, sizeof mm);
      mm = mm + (mp * N[k * kStride]) * one_v;
      std::memcpy(b, &mm, sizeof mm);
    }
    if (with_forces) {
      const double gx = G[(3 * k) * kStride], gy = G[(3 * k + 1) * kStride], gz = G[(3 * k + 2) * kStride];
      D4 f = -((col[0] * gx + col[1] * gy) + col[2] * gz);
      if (with_body) f = N[k * kStride] * fb4 + f;
      b[4] += f[0];
      b[5] += f[1];
      b[6] += f[2];
    }
  }
}

// The bits in which a and the double at b differ (0: the same bits, -0.0 and +0.0 differ).
__attribute__((always_inline)) inline uint64_t bits_changed(double a, const double* b) {
  uint64_t x, y;
  std::memcpy(&x, &a, 8);
  std::memcpy(&y, b, 8);
  return x ^ y;
}

// The end of every G2P: v_p += dt_int a, x_p += dt u with a and u the particle's
// interpolated acceleration and grid velocity. Returns whether v_p and x_p kept every bit
// (the still bits; a caller that ignores it computes nothing for it).
__attribute__((always_inline)) inline bool advance_particle(StepContext* c, int p, double ax, double ay, double az,
                                                            double ux, double uy, double uz) {
  const double dt = c->clock.dt, dt_int = c->clock.dt_int;
  double* vp = c->part.v + 3 * p;
  double* xp = c->part.x + 3 * p;
  const double v[3] = {vp[0] + ax * dt_int, vp[1] + ay * dt_int, vp[2] + az * dt_int};
  const double x[3] = {xp[0] + ux * dt, xp[1] + uy * dt, xp[2] + uz * dt};
  uint64_t changed = 0;
  for (int d = 0; d < 3; ++d) {
    changed |= bits_changed(v[d], vp + d) | bits_changed(x[d], xp + d);
    vp[d] = v[d];
    xp[d] = x[d];
  }
  return changed == 0;
}

// MUSL remap of particle p: its momentum m_p N_k v_p added to fields 1-3 of node(k).
// Weights N[k kStride].
template <int kNodes, int kStride = 1, class NodeOf>
__attribute__((always_inline)) inline void remap_particle(const StepContext* c, int p, const double* N,
                                                          NodeOf node) {
  const double mp = c->part.mass[p];
  const double* vp = c->part.v + 3 * p;
  for (int k = 0; k < kNodes; ++k) {
    double* b = node(k);
    const double mn = mp * N[k * kStride];
    b[1] += mn * vp[0];
    b[2] += mn * vp[1];
    b[3] += mn * vp[2];
  }
}

}  // namespace
}  // namespace mpm3d
