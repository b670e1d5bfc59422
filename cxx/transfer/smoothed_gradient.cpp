// The current MPM3D-F90's smoothed-gradient MPM ('sgmp', against volumetric locking): the
// particles exchange everything with an auxiliary grid whose nodes are the centres of the
// background cells, and each cell centre exchanges with the eight corners of its cell
// (docs/DECK_FORMAT.md "sgmp"):
//   P2G    particle -> cell centre with the trilinear weights W of the auxiliary cell that
//          holds the particle (the one around its nearest grid node): mass, momentum, body
//          force, sigma V (TLmp: V0 P, with the weights of the reference positions); cell
//          centre -> node: m_i, p_i += m_c / 8, p_c / 8 (cells heavier than the mass
//          cut-off), f_i += f_c / 8 - (sigma V)_c grad N_i(centre c);
//   G2P    node -> cell centre: v_c, a_c = sum_corners v_i / 8, a_i / 8 (the cells on a held
//          face take the velocity of the cell's inner face, edge or corner instead);
//          particle v += dt sum W a_c, x += dt sum W v_c; MUSL remap: p_c = sum W m v,
//          p_i += p_c / 8;
//   stress L_c = sum_corners v_i (x) grad N_i(centre c), particle L = sum W L_c:
// one-point quadrature per cell, so a cell has one volumetric strain rate.
// Per axis the auxiliary cell of a particle spans the centres of cells a and a + 1 around
// its nearest node a + 1, natural coordinate X in [-1, 1]; along an axis whose nearest node
// is held by a fixed or symmetric face (two node layers), X is pushed to -1 or +1 (P2G,
// forces, stress, remap), and G2P takes X from the particle's place in its own cell,
// between the face's velocity and the cell centre's. Centres beyond the grid (a one-cell
// axis, the outer half cells) pass their weight to the nearest centre (rules sg_lower and
// sg_beyond: the current program's auxiliary cells, sg_corner_weights). Both languages:
// fortran_ref/stage_sg.f90, the same operations in the same order.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "core/step_state.hpp"
#include "transfer/smoothed_gradient.hpp"
#include "transfer/stress_loop.hpp"
#include "transfer/transfer.hpp"
#include "transfer/transfer_common.hpp"

namespace mpm3d {

namespace {

// f(cell, i, j, k) for the cells of the active patches (the ones the particles reach).
template <class F>
void for_active_cells(const StepContext* c, F&& f) {
  const int P = c->patch.patch_cells;
  for_patches(c, [&](int q) {
    if (patch_at_rest(c, q) || !owned_nodes(c, q).active) return;
    int q3[3], lo[3], hi[3];
    patch_coords(c, q, q3);
    for (int a = 0; a < 3; ++a) {
      lo[a] = q3[a] * P;
      hi[a] = lo[a] + P < c->grid.nc[a] ? lo[a] + P : c->grid.nc[a];
    }
    for (int k = lo[2]; k < hi[2]; ++k)
      for (int j = lo[1]; j < hi[1]; ++j)
        for (int i = lo[0]; i < hi[0]; ++i) f(i + c->grid.nc[0] * (j + c->grid.nc[1] * k), i, j, k);
  });
}

// The nodes of a cell's corners k = a + 2 b + 4 c: corner 0's index, and each corner's
// offset from it (node_of), once per loop rather than per cell.
struct CornerOffsets {
  int row, layer, of[8];
  explicit CornerOffsets(const StepContext* c) : row(c->grid.nn[0]), layer(c->grid.nn[0] * c->grid.nn[1]) {
    for (int k = 0; k < 8; ++k) of[k] = node_of(c, 0, k);
  }
  int first(int i, int j, int k) const { return i + row * j + layer * k; }
};

// The scatters to the cell centres, in parallel with the bits of one thread. The canonical
// order of every centre's sum is that of one pass over the particles, patches in index
// order, each patch's list in order, corners k = 0..7 (one thread: that pass). A particle
// reaches only the centres of its own cell and its neighbours, so the centres of a run of
// patches receive from the particles of the run and of the patches next to it alone: with
// more threads, each owns the centres of its run of patches (thread_patches) and makes that
// pass over the run and its neighbour patches, keeping the contributions that land on its
// own centres. Only the particles on the runs' borders are visited twice. Both read each
// patch-list entry's weights, which the step's first scatter computes in parallel
// (cache_weights): the later scatters and the stress stage take the particles where the
// bin stage placed them, so with the same weights.

// The centres of patch q: [lo, hi) per axis.
inline void patch_centres(const StepContext* c, int q, int q3[3], int lo[3], int hi[3]) {
  const int P = c->patch.patch_cells;
  patch_coords(c, q, q3);
  for (int a = 0; a < 3; ++a) {
    lo[a] = q3[a] * P;
    hi[a] = lo[a] + P < c->grid.nc[a] ? lo[a] + P : c->grid.nc[a];
  }
}

// Every patch-list entry's weights (both rules) and centres into c->sgmp.sg_w, sg_cell; with
// kReach also which neighbour patches its corners fall in, into c->sg_reach (the scatters
// of several threads); kRules: under the rules that move weights (sg_rules_move_weights).
template <bool kReach, bool kRules>
void cache_weights(const StepContext* c) {
  const CellDecoder dec(c);
  for_patches(c, [&](int q) {
    if (rest_around(c, q)) return;  // no stage reads these entries' weights
    int q3[3], lo[3], hi[3];
    patch_centres(c, q, q3, lo, hi);
    const SgGeometry g(c);
    const CellDecoder d = dec;  // local copies (SgGeometry)
    const int* part_cell = c->part.cell;
    const double* part_lx = c->part.lx;
    int* corner_cells = c->sgmp.sg_cell;
    for (int e = c->patch.patch_start[q]; e < c->patch.patch_start[q + 1]; ++e) {
      int r[6];  // the corners' cells per axis: lo[3], hi[3]
      const int p = c->patch.patch_part[e];
      sg_corner_weights<kRules>(g, d, part_cell[p], part_lx + 3 * p, r, r + 3, sg_p2g_weights(c, e),
                                sg_g2p_weights(c, e));
      for (int k = 0; k < 8; ++k) corner_cells[8 * size_t(e) + k] = sg_corner_cell(g, r, r + 3, k);
      if (!kReach) continue;
      unsigned reach = 0;
      for (int a = 0; a < 3; ++a) reach |= (r[a] < lo[a] ? 1u : 0u) << (2 * a) | (r[3 + a] >= hi[a] ? 2u : 0u) << (2 * a);
      c->sgmp.sg_reach[e] = static_cast<uint16_t>(reach);
    }
  });
}

// For each reach value (sg_reach) and corner k: the patch the corner's centre lies in, as
// the neighbour number (dx + 1) + 3 (dy + 1) + 9 (dz + 1) from the entry's own patch. The
// corner's low side along axis a (bit a of k clear) is in the patch below when reach bit
// 2a is set, its high side in the patch above when bit 2a + 1 is.
struct CornerPatches {
  unsigned char of[64][8];
  CornerPatches() {
    for (unsigned reach = 0; reach < 64; ++reach)
      for (int k = 0; k < 8; ++k) {
        int n = 0, scale = 1;
        for (int a = 0; a < 3; ++a, scale *= 3) {
          const int d = (k >> a & 1) ? int(reach >> (2 * a + 1) & 1u) : -int(reach >> (2 * a) & 1u);
          n += (d + 1) * scale;
        }
        of[reach][k] = static_cast<unsigned char>(n);
      }
  }
};

// Fields first..first+count-1 of the centres of patches [lo, hi) set to zero.
void zero_centres(const StepContext* c, int lo, int hi, int first, int count) {
  for (int q = lo; q < hi; ++q) {
    if (patch_at_rest(c, q)) continue;  // its centres keep their sums
    int q3[3], clo[3], chi[3];
    patch_centres(c, q, q3, clo, chi);
    for (int k = clo[2]; k < chi[2]; ++k)
      for (int j = clo[1]; j < chi[1]; ++j)
        for (int i = clo[0]; i < chi[0]; ++i) {
          double* a = aux_cell(c, i + c->grid.nc[0] * (j + c->grid.nc[1] * k));
          for (int f = first; f < first + count; ++f) a[f] = 0.0;
        }
  }
}

// f(p, cell[8], w[8], mask & the corners of nonzero weight) for patch-list entry e, with a
// local copy of its P2G weights: the centres' sums cannot alias it.
template <class F>
__attribute__((always_inline)) inline void visit_entry(const StepContext* c, int e, unsigned mask, F& f) {
  double w[8];
  for (int k = 0; k < 8; ++k) w[k] = sg_p2g_weights(c, e)[k];
  f(c->patch.patch_part[e], c->sgmp.sg_cell + 8 * size_t(e), w, mask & nonzero_corners(w));
}

// Fields first..first+count-1 of this thread's centres set to zero (no other thread adds
// to them), then f(p, cell[8], w[8], mask) for every particle that reaches them, mask bit
// k set where its corner k is one of them and its weight is not zero (nonzero_corners):
// each centre's contributions in the canonical order when f adds corners k = 0..7
// (cache_weights with the reach first). The centres of patches at rest are neither zeroed nor
// added to.
template <class F>
void for_contributions_in_order(const StepContext* c, int first_field, int nfield, F&& f) {
  static const CornerPatches corners;
  team_region([&] {
    int t, T, lo, hi;
    team_position(t, T);
    thread_patches(c, t, T, lo, hi);
    zero_centres(c, lo, hi, first_field, nfield);
    // The run and every patch next to one of its patches lie within one layer of patches
    // (and one row and one patch) of it in index order.
    const int layer = 1 + c->patch.npd[0] + c->patch.npd[0] * c->patch.npd[1];
    const int first = lo - layer > 0 ? lo - layer : 0;
    const int last = hi + layer < c->patch.npatch ? hi + layer : c->patch.npatch;
    for (int r = lo < hi ? first : last; r < last; ++r) {
      if (c->patch.patch_start[r] == c->patch.patch_start[r + 1]) continue;
      uint32_t mine = 0;  // bit k: neighbour k of r is one of this thread's patches
      for_patches_around(c, r, [&](int n, int k) {
        if (n >= lo && n < hi && !patch_at_rest(c, n)) mine |= 1u << k;
      });
      if (mine == 0) continue;
      const bool own = (mine >> 13 & 1u) != 0;  // r itself is this thread's
      for (int e = c->patch.patch_start[r]; e < c->patch.patch_start[r + 1]; ++e) {
        const unsigned reach = c->sgmp.sg_reach[e];
        unsigned mask = 0;
        if (reach == 0) {
          if (!own) continue;
          mask = 0xFFu;  // every corner in r
        } else {
          for (int k = 0; k < 8; ++k) mask |= (mine >> corners.of[reach][k] & 1u) << k;
          if (mask == 0) continue;
        }
        visit_entry(c, e, mask, f);
      }
    }
  });
}

// Fields first..first+count-1 of every centre set to zero, then add(p, cell[8], w[8], mask)
// (mask: the corners of nonzero weight) in the canonical order of every centre's sum: one
// pass on one thread, the owners' passes on more.
template <class F>
void scatter_in_order(StepContext* c, int first_field, int nfield, F&& add) {
  const int threads = omp_threads();
  const bool masked = threads > 1 || c->rest.at_rest;  // one thread's pass skips no centre
  sg_ensure_weights(c, masked);
  if (masked) {
    for_contributions_in_order(c, first_field, nfield, add);
    return;
  }
  zero_centres(c, 0, c->patch.npatch, first_field, nfield);
  const int total = c->patch.patch_start[c->patch.npatch];
  for (int e = 0; e < total; ++e) visit_entry(c, e, 0xFFu, add);
}

// The particles' scatter to the cell centres: mass and momentum, and/or body force and
// sigma V (kNs = 6; TLmp: V0 P, the 9 entries of the first Piola-Kirchhoff stress times
// the reference volume, kNs = 9: the smoothed-gradient total Lagrangian MPM). One instance
// per field set, so that each corner's runs of fields are fixed-length loops in vector
// lanes (each field's own sum, in the same order: the same bits).
template <bool kMassMom, bool kForces, int kNs>
void scatter_fields(StepContext* c) {
  static_assert(AUX_P == AUX_M + 1 && AUX_FB == AUX_M + 4 && AUX_S == AUX_FB + 3, "one run of fields");
  const bool with_body = c->method.has_body_force != 0;
  // The fields summed: mass and momentum (4), body force and stress (12), or both.
  scatter_in_order(c, kMassMom ? AUX_M : AUX_FB, (kMassMom ? 4 : 0) + (kForces ? 12 : 0), [&](int p, const int* cell, const double* w, unsigned mask) {
    const double mp = c->part.mass[p];
    const double* vp = c->part.v + 3 * p;
    const double vx = vp[0], vy = vp[1], vz = vp[2];  // (an array built here and read in
                                                      // vector lanes stalls the loads)
    double vs[kNs > 0 ? kNs : 1], fb[3] = {0, 0, 0};
    if (kForces) {
      if (kNs == 9) {
        for (int s = 0; s < 9; ++s) vs[s] = c->part.pk1[9 * size_t(p) + size_t(s)];
      } else {
        const double volp = c->part.vol[p];
        for (int s = 0; s < kNs; ++s) vs[s] = c->part.sig[6 * p + s] * volp;
      }
      if (with_body) particle_body_force(c, p, fb);
    }
    for (unsigned left = mask; left != 0; left &= left - 1) {  // corners in ascending order
      const int k = __builtin_ctz(left);
      double* a = aux_cell(c, cell[k]);
      const double wk = w[k];
      if (kMassMom) {
        const double mn = mp * wk;  // the mass and momentum m w (1, v)
        a[AUX_M] += mn;
        a[AUX_P + 0] += mn * vx;
        a[AUX_P + 1] += mn * vy;
        a[AUX_P + 2] += mn * vz;
      }
      if (kForces) {
        if (with_body)
          for (int d = 0; d < 3; ++d) a[AUX_FB + d] += wk * fb[d];
#pragma omp simd
        for (int s = 0; s < kNs; ++s) a[AUX_S + s] += wk * vs[s];
      }
    }
  });
}

void scatter_to_centres(StepContext* c, bool with_mass_mom, bool with_forces) {
  const bool pk1 = c->part.pk1 != nullptr;
  if (with_mass_mom && with_forces)
    pk1 ? scatter_fields<true, true, 9>(c) : scatter_fields<true, true, 6>(c);
  else if (with_forces)
    pk1 ? scatter_fields<false, true, 9>(c) : scatter_fields<false, true, 6>(c);
  else if (with_mass_mom)
    scatter_fields<true, false, 0>(c);
}

// The cell centres' share of each node of the active patches, over the node's cells in
// ascending cell order: mass and momentum (cells above the mass cut-off), forces, or the
// remapped momentum.
enum GatherWhat { GATHER_MASS_MOM = 1, GATHER_FORCES = 2, GATHER_REMAP = 4 };

// One cell's share of a node: mass and momentum (above the mass cut-off), the remapped
// momentum, and the force with the node's gradient (gx, gy, gz) at the cell's centre, each
// +-1/(4h) (+ where the node is the cell's upper corner).
template <int what, bool pk1>
__attribute__((always_inline)) inline void add_cell_share(const double* a, double cutoff, double gx, double gy,
                                                          double gz, double& m, double pm[3], double f[3]) {
  if ((what & GATHER_MASS_MOM) && a[AUX_M] > cutoff) {
    m += 0.125 * a[AUX_M];
    for (int d = 0; d < 3; ++d) pm[d] += 0.125 * a[AUX_P + d];
  }
  if (what & GATHER_REMAP)
    for (int d = 0; d < 3; ++d) pm[d] += 0.125 * a[AUX_RP + d];
  if (what & GATHER_FORCES) {
    double fx, fy, fz;
    internal_force<pk1>(a + AUX_S, gx, gy, gz, fx, fy, fz);
    f[0] += 0.125 * a[AUX_FB + 0] + fx;
    f[1] += 0.125 * a[AUX_FB + 1] + fy;
    f[2] += 0.125 * a[AUX_FB + 2] + fz;
  }
}

// Node n's sums into the node arrays.
template <int what>
__attribute__((always_inline)) inline void store_node(StepContext* c, int n, double m, const double pm[3],
                                                      const double f[3]) {
  if (what & GATHER_MASS_MOM) c->grid.gmass[n] = m;
  if (what & (GATHER_MASS_MOM | GATHER_REMAP))
    for (int d = 0; d < 3; ++d) c->grid.gmom[3 * n + d] = pm[d];
  if (what & GATHER_FORCES)
    for (int d = 0; d < 3; ++d) c->grid.gforce[3 * n + d] = f[d];
}

// One instance per field set and stress layout (the per-cell tests then fold away). A grid
// one cell thick along z (the current decks' plane models) has two node layers that gather
// the same cells in the same order, with opposite z gradients: both are summed in one pass
// over the cells, each node with its own operations (the same bits as two passes).
template <int what, bool pk1>
void gather_to_nodes(StepContext* c) {
  const double cutoff = c->grid.mass_cutoff, gs = 0.25 * c->grid.inv_h;
  for_patches(c, [&](int q) {
    if (patch_at_rest(c, q)) return;
    const OwnedNodes o = owned_nodes(c, q);
    if (!o.active) return;
    if (c->grid.nc[2] == 1 && o.lo[2] == 0 && o.hi[2] == 2) {
      const int layer = c->grid.nn[0] * c->grid.nn[1];
      for (int j = o.lo[1]; j < o.hi[1]; ++j)
        for (int i = o.lo[0]; i < o.hi[0]; ++i) {
          // Node (i, j, 0) is the lower corner of cell z = 0 (gz = -gs), node (i, j, 1) its
          // upper corner (gz = +gs).
          double m0 = 0.0, pm0[3] = {0, 0, 0}, f0[3] = {0, 0, 0};
          double m1 = 0.0, pm1[3] = {0, 0, 0}, f1[3] = {0, 0, 0};
          for (int cy = j - 1; cy <= j; ++cy) {
            if (cy < 0 || cy >= c->grid.nc[1]) continue;
            for (int cx = i - 1; cx <= i; ++cx) {
              if (cx < 0 || cx >= c->grid.nc[0]) continue;
              const double* a = aux_cell(c, cx + c->grid.nc[0] * cy);
              const double gx = cx == i - 1 ? gs : -gs, gy = cy == j - 1 ? gs : -gs;
              add_cell_share<what, pk1>(a, cutoff, gx, gy, -gs, m0, pm0, f0);
              add_cell_share<what, pk1>(a, cutoff, gx, gy, gs, m1, pm1, f1);
            }
          }
          const int n = i + c->grid.nn[0] * j;
          store_node<what>(c, n, m0, pm0, f0);
          store_node<what>(c, n + layer, m1, pm1, f1);
        }
      return;
    }
    for (int k = o.lo[2]; k < o.hi[2]; ++k)
      for (int j = o.lo[1]; j < o.hi[1]; ++j)
        for (int i = o.lo[0]; i < o.hi[0]; ++i) {
          double m = 0.0, pm[3] = {0, 0, 0}, f[3] = {0, 0, 0};
          for (int cz = k - 1; cz <= k; ++cz) {
            if (cz < 0 || cz >= c->grid.nc[2]) continue;
            for (int cy = j - 1; cy <= j; ++cy) {
              if (cy < 0 || cy >= c->grid.nc[1]) continue;
              for (int cx = i - 1; cx <= i; ++cx) {
                if (cx < 0 || cx >= c->grid.nc[0]) continue;
                const double* a = aux_cell(c, cx + c->grid.nc[0] * (cy + c->grid.nc[1] * cz));
                const double gx = cx == i - 1 ? gs : -gs, gy = cy == j - 1 ? gs : -gs, gz = cz == k - 1 ? gs : -gs;
                add_cell_share<what, pk1>(a, cutoff, gx, gy, gz, m, pm, f);
              }
            }
          }
          store_node<what>(c, i + c->grid.nn[0] * (j + c->grid.nn[1] * k), m, pm, f);
        }
  });
}

}  // namespace

void sg_ensure_weights(StepContext* c, bool with_reach) {
  const int need = with_reach ? 2 : 1;
  if (c->sgmp.sg_cached >= need) return;
  const bool rules = sg_rules_move_weights(c);
  if (with_reach)
    rules ? cache_weights<true, true>(c) : cache_weights<true, false>(c);
  else
    rules ? cache_weights<false, true>(c) : cache_weights<false, false>(c);
  c->sgmp.sg_cached = need;
}

void sg_p2g(StepContext* c, bool with_mass_mom, bool with_forces) {
  scatter_to_centres(c, with_mass_mom, with_forces);
  const bool pk1 = c->part.pk1 != nullptr;
  if (with_mass_mom && with_forces)
    pk1 ? gather_to_nodes<GATHER_MASS_MOM | GATHER_FORCES, true>(c)
        : gather_to_nodes<GATHER_MASS_MOM | GATHER_FORCES, false>(c);
  else if (with_forces)
    pk1 ? gather_to_nodes<GATHER_FORCES, true>(c) : gather_to_nodes<GATHER_FORCES, false>(c);
  else if (with_mass_mom)
    gather_to_nodes<GATHER_MASS_MOM, false>(c);
}

void sg_g2p(StepContext* c, bool remap) {
  const double cutoff = c->grid.mass_cutoff;
  // Cell centres: the corners' velocities and accelerations, each 1/8 (a cell on a held
  // face: the weights of the cell's point at natural coordinates cxx).
  const CornerOffsets off(c);
  const double *gmass = c->grid.gmass, *gmom = c->grid.gmom, *gforce = c->grid.gforce;
  for_active_cells(c, [&](int cell, int i, int j, int k) {
    const int ijk[3] = {i, j, k};
    bool face = false;
    for (int a = 0; a < 3; ++a)
      face = face || (c->grid.nc[a] > 1 && ((ijk[a] == 0 && c->grid.fix[2 * a] != 0) ||
                                            (ijk[a] == c->grid.nc[a] - 1 && c->grid.fix[2 * a + 1] != 0)));
    double v[3] = {0, 0, 0}, acc[3] = {0, 0, 0};
    const int n0 = off.first(i, j, k);
    auto add_corner = [&](int n, double w) __attribute__((always_inline)) {
      const double m = gmass[n];
      if (!(m > cutoff)) return;
      const double r = w / m;
      for (int d = 0; d < 3; ++d) {
        v[d] += gmom[3 * n + d] * r;
        acc[d] += gforce[3 * n + d] * r;
      }
    };
    if (face) {
      double cxx[3] = {0, 0, 0};
      for (int a = 0; a < 3; ++a) {
        if (c->grid.nc[a] == 1) continue;
        if (ijk[a] == 0) cxx[a] = 1.0;
        if (ijk[a] == c->grid.nc[a] - 1) cxx[a] = -1.0;
      }
      for (int corner = 0; corner < 8; ++corner) {
        double w = 1.0;
        for (int a = 0; a < 3; ++a) w = w * (0.5 * (1.0 + (((corner >> a) & 1) ? cxx[a] : -cxx[a])));
        add_corner(n0 + off.of[corner], w);
      }
    } else {
#pragma GCC unroll 8
      for (int corner = 0; corner < 8; ++corner) add_corner(n0 + off.of[corner], 0.125);
    }
    double* a = aux_cell(c, cell);
    for (int d = 0; d < 3; ++d) {
      a[AUX_V + d] = v[d];
      a[AUX_A + d] = acc[d];
    }
  });
  // Particles: each its own update, with its entry's weights of this step.
  sg_ensure_weights(c, false);
  auto update = [&](int e) __attribute__((always_inline)) {  // inlined in both loops below
    const int* cell = c->sgmp.sg_cell + 8 * size_t(e);
    const double* w = sg_g2p_weights(c, e);
    double ax = 0.0, ay = 0.0, az = 0.0, ux = 0.0, uy = 0.0, uz = 0.0;
    for (int k = 0; k < 8; ++k) {
      const double* a = aux_cell(c, cell[k]);
      ax += w[k] * a[AUX_A + 0];
      ay += w[k] * a[AUX_A + 1];
      az += w[k] * a[AUX_A + 2];
      ux += w[k] * a[AUX_V + 0];
      uy += w[k] * a[AUX_V + 1];
      uz += w[k] * a[AUX_V + 2];
    }
    return advance_particle(c, c->patch.patch_part[e], ax, ay, az, ux, uy, uz);
  };
  if (c->rest.still) {
    // The patches not at rest, each particle's still bit 1 set when x and v kept every bit.
    for_patches(c, [&](int q) {
      if (patch_at_rest(c, q)) return;
      for (int e = c->patch.patch_start[q]; e < c->patch.patch_start[q + 1]; ++e) {
        const int p = c->patch.patch_part[e];
        const bool same = update(e);
        c->rest.still[p] = static_cast<unsigned char>((c->rest.still[p] & 1u) | (same ? 2u : 0u));
      }
    });
  } else {
    for_list_chunks(c, [&](int first, int count) {
      for (int e = first; e < first + count; ++e) update(e);
    });
  }
  if (!remap) return;
  // MUSL: the new particle momenta to the cell centres, then the nodes (no mass cut-off,
  // as the current program).
  scatter_in_order(c, AUX_RP, 3, [&](int p, const int* cell, const double* w, unsigned mask) {
    const double mp = c->part.mass[p];
    const double* vp = c->part.v + 3 * p;
    for (unsigned left = mask; left != 0; left &= left - 1) {  // corners in ascending order
      const int k = __builtin_ctz(left);
      double* a = aux_cell(c, cell[k]);
      const double mn = mp * w[k];
      a[AUX_RP + 0] += mn * vp[0];
      a[AUX_RP + 1] += mn * vp[1];
      a[AUX_RP + 2] += mn * vp[2];
    }
  });
  gather_to_nodes<GATHER_REMAP, false>(c);
}

void sg_cell_gradients(StepContext* c, const double* gvel) {
  const double cutoff = c->grid.mass_cutoff, gs = 0.25 * c->grid.inv_h;
  const CornerOffsets off(c);
  const double* gmass = c->grid.gmass;
  for_active_cells(c, [&](int cell, int i, int j, int k) {
    double L[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    const int n0 = off.first(i, j, k);
#pragma GCC unroll 8
    for (int corner = 0; corner < 8; ++corner) {
      const int n = n0 + off.of[corner];
      if (!(gmass[n] > cutoff)) continue;
      const double g[3] = {(corner & 1) ? gs : -gs, ((corner >> 1) & 1) ? gs : -gs, ((corner >> 2) & 1) ? gs : -gs};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) L[3 * a + b] += gvel[3 * n + a] * g[b];
    }
    double* a = aux_cell(c, cell);
    for (int r = 0; r < 9; ++r) a[AUX_L + r] = L[r];
  });
}

namespace {

// sgmp: the patch lists in chunks, each entry's gradient from its weights of this step
// (sg_ensure_weights).
void stress_sg(StepContext* c) {
  sg_ensure_weights(c, false);
  const CellDecoder dec(c);
  const StressBlockArgs args = stress_args(c);
  auto gradient = [&](const CellDecoder&, int e, int, double* L) {
    sg_velocity_gradient(c, c->sgmp.sg_cell + 8 * size_t(e), sg_p2g_weights(c, e), L);
  };
  for_stress_lists(c, [&](int first, int count) { stress_run(c, dec, args, c->patch.patch_part, first, count, gradient); });
}

void stress_smoothed_gradient(StepContext* c, const double* gvel) {
  sg_cell_gradients(c, gvel);
  stress_sg(c);
}

}  // namespace

const Transfer kSmoothedGradientTransfer = {sg_p2g, sg_g2p, stress_smoothed_gradient, mass_gradient_trilinear};

}  // namespace mpm3d
