#include "update_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "constitution.hpp"
#include "grid.hpp"
#include "transfer_lanes.hpp"
#include "update_step_detail.hpp"

namespace mpm3d {

// update_step_avx2.cpp: the lane kernels of transfer_lanes.hpp compiled for AVX2.
void p2g_patch_avx2(const StepContext* c, int q, bool with_mass_mom, bool with_forces);
void g2p_patch_avx2(StepContext* c, int q, bool remap);
int bin_range_avx2(const StepContext* c, int lo, int hi, int* patch_of);
void stress_list_avx2(StepContext* c, const int* list, int count, const double* gvel,
                      const StressBlockArgs& args);

const char* const kStageNames[ST_COUNT] = {"bin", "p2g", "forces", "integrate",
                                           "g2p", "stress", "energy", "contact", "recontact"};

StageTable cxx_stages() {
  return StageTable{{mpm3d_cxx_bin, mpm3d_cxx_p2g, mpm3d_cxx_forces, mpm3d_cxx_integrate,
                     mpm3d_cxx_g2p, mpm3d_cxx_stress, mpm3d_cxx_energy, mpm3d_cxx_contact,
                     mpm3d_cxx_recontact}};
}

bool have_fortran_stages() {
#ifdef MPM3D_HAVE_FORTRAN
  return true;
#else
  return false;
#endif
}

StageTable fortran_stages() {
#ifdef MPM3D_HAVE_FORTRAN
  return StageTable{{mpm3d_f_bin, mpm3d_f_p2g, mpm3d_f_forces, mpm3d_f_integrate, mpm3d_f_g2p,
                     mpm3d_f_stress, mpm3d_f_energy, mpm3d_f_contact, mpm3d_f_recontact}};
#else
  throw std::runtime_error("this build has no Fortran reference kernels");
#endif
}

void select_stages(StageTable& t, const std::string& spec, bool per_stage) {
  auto table_for = [](const std::string& lang) {
    if (lang == "cxx") return cxx_stages();
    if (lang == "fortran") return fortran_stages();
    throw std::invalid_argument("unknown kernel language '" + lang + "' (cxx or fortran)");
  };
  if (!per_stage) {
    t = table_for(spec);
    return;
  }
  size_t pos = 0;
  while (pos <= spec.size()) {
    size_t end = spec.find(',', pos);
    if (end == std::string::npos) end = spec.size();
    const std::string item = spec.substr(pos, end - pos);
    const size_t eq = item.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("expected STAGE=LANG, got '" + item + "'");
    const std::string stage = item.substr(0, eq), lang = item.substr(eq + 1);
    int s = -1;
    for (int i = 0; i < ST_COUNT; ++i)
      if (stage == kStageNames[i]) s = i;
    if (s < 0) throw std::invalid_argument("unknown stage '" + stage + "' (see --list-stages)");
    t.fn[s] = table_for(lang).fn[s];
    pos = end + 1;
  }
}

namespace {

// Nodes owned by patch q: [lo, hi) per axis; the last patch of an axis also owns the
// grid's last node layer. A patch is active when it or one of its seven lower neighbours
// holds particles (GIMP, halo 1: one of its 26 neighbours); nodes of inactive patches are
// never read by any stage, so node loops skip them (their values are left as they were).
struct OwnedNodes {
  int lo[3], hi[3];
  bool active;
};

inline OwnedNodes owned_nodes(const StepContext* c, int q) {
  OwnedNodes o;
  const int P = c->patch_cells;
  int q3[3] = {q % c->npd[0], (q / c->npd[0]) % c->npd[1], q / (c->npd[0] * c->npd[1])};
  for (int a = 0; a < 3; ++a) {
    o.lo[a] = q3[a] * P;
    o.hi[a] = q3[a] == c->npd[a] - 1 ? c->nn[a] : o.lo[a] + P;
  }
  o.active = false;
  const int ne = 2 + c->patch_halo;
  for (int cz = 0; cz < ne && !o.active; ++cz)
    for (int cy = 0; cy < ne && !o.active; ++cy)
      for (int cx = 0; cx < ne && !o.active; ++cx) {
        const int px = q3[0] - 1 + cx, py = q3[1] - 1 + cy, pz = q3[2] - 1 + cz;
        if (px >= 0 && py >= 0 && pz >= 0 && px < c->npd[0] && py < c->npd[1] && pz < c->npd[2] &&
            c->patch_slot[px + c->npd[0] * (py + c->npd[1] * pz)] >= 0)
          o.active = true;
      }
  return o;
}

// Canonical assembly (DESIGN.md section 4): each node's value is 0.0 plus the values of
// the non-empty patches holding it, in ascending patch index (x fastest, then y, z).
// Fields first..first+count-1 of the buffers go to dst_mass (field 0), dst_mom (1-3)
// and dst_force (4-6). Every node is written by exactly one owner patch (the patch whose
// lower corner region holds it), so owners run in parallel.
void assemble_wide(const StepContext* c, int first, int count, double* dst_mass, double* dst_mom,
                   double* dst_force);

// The field range is a compile-time constant, so the per-node loops unroll.
template <int first, int count>
void assemble_fields(const StepContext* c, PatchLoop loop, double* dst_mass, double* dst_mom, double* dst_force) {
  const int P = c->patch_cells, Q = P + 1;
  const int npd0 = c->npd[0], npd1 = c->npd[1], npd2 = c->npd[2];
  const int pn = Q * Q * Q;
  for_thread_patches(c, loop, [&](int q) {
    const int qx = q % npd0, qy = (q / npd0) % npd1, qz = q / (npd0 * npd1);
    // Slots of the patch and its lower neighbours: nb[cz][cy][cx], c = 0 lower, 1 self.
    const double* nb[2][2][2];
    bool any = false;
    for (int cz = 0; cz < 2; ++cz)
      for (int cy = 0; cy < 2; ++cy)
        for (int cx = 0; cx < 2; ++cx) {
          const int px = qx - 1 + cx, py = qy - 1 + cy, pz = qz - 1 + cz;
          const double* b = nullptr;
          if (px >= 0 && py >= 0 && pz >= 0) {
            const int slot = c->patch_slot[px + npd0 * (py + npd1 * pz)];
            if (slot >= 0) b = c->patch_buf + size_t(slot) * size_t(pn) * kNodeFields;
          }
          nb[cz][cy][cx] = b;
          any = any || b;
        }
    if (!any) return;  // inactive: no stage reads these nodes
    const int i0 = qx * P, j0 = qy * P, k0 = qz * P;
    const int i1 = qx == npd0 - 1 ? c->nn[0] : i0 + P;
    const int j1 = qy == npd1 - 1 ? c->nn[1] : j0 + P;
    const int k1 = qz == npd2 - 1 ? c->nn[2] : k0 + P;
    for (int k = k0; k < k1; ++k)
      for (int j = j0; j < j1; ++j) {
        // Row pointers of the contributing buffers, in ascending patch order: (cz, cy)
        // ascending, and within each the lower x patch (cx = 0) before the own one.
        const double* row[8];
        int cxs[8], nrow = 0;
        const int czlo = (k == k0 && qz > 0) ? 0 : 1;
        const int cylo = (j == j0 && qy > 0) ? 0 : 1;
        for (int cz = czlo; cz < 2; ++cz)
          for (int cy = cylo; cy < 2; ++cy)
            for (int cx = 0; cx < 2; ++cx) {
              const double* b = nb[cz][cy][cx];
              if (!b) continue;
              const int lj = j - (qy - 1 + cy) * P, lk = k - (qz - 1 + cz) * P;
              // Buffer node of x index i is at (i - (qx - 1 + cx) P) + Q (lj + Q lk).
              row[nrow] = b + std::ptrdiff_t(Q * (lj + Q * lk) - (qx - 1 + cx) * P) * kNodeFields;
              cxs[nrow++] = cx;
            }
        const int nbase = c->nn[0] * (j + c->nn[1] * k);
        for (int i = i0; i < i1; ++i) {
          const bool lower_x = (i == i0 && qx > 0);
          double sum[kNodeFields] = {0, 0, 0, 0, 0, 0, 0};
          for (int r = 0; r < nrow; ++r) {
            if (cxs[r] == 0 && !lower_x) continue;
            const double* v = row[r] + size_t(i) * kNodeFields + first;
            for (int f = 0; f < count; ++f) sum[f] += v[f];
          }
          const int n = i + nbase;
          for (int f = 0; f < count; ++f) {
            const int field = first + f;
            if (field == 0) dst_mass[n] = sum[f];
            else if (field <= 3) dst_mom[3 * n + field - 1] = sum[f];
            else dst_force[3 * n + field - 4] = sum[f];
          }
        }
      }
  });
}

void assemble(const StepContext* c, PatchLoop loop, int first, int count, double* dst_mass, double* dst_mom,
              double* dst_force) {
  if (c->patch_halo > 0)
    assemble_wide(c, first, count, dst_mass, dst_mom, dst_force);
  else if (first == 0 && count == 7)
    assemble_fields<0, 7>(c, loop, dst_mass, dst_mom, dst_force);
  else if (first == 0 && count == 4)
    assemble_fields<0, 4>(c, loop, dst_mass, dst_mom, dst_force);
  else if (first == 1 && count == 3)
    assemble_fields<1, 3>(c, loop, dst_mass, dst_mom, dst_force);
  else if (first == 4 && count == 3)
    assemble_fields<4, 3>(c, loop, dst_mass, dst_mom, dst_force);
  else
    throw std::logic_error("assemble: unexpected field range");
}

// Patches whose buffers (halo H) hold node n along one axis: [lo, hi].
inline void patch_range(int n, int P, int H, int npd, int& lo, int& hi) {
  const int t = n - P - H;
  lo = t <= 0 ? 0 : (t + P - 1) / P;
  hi = (n + H) / P;
  if (hi > npd - 1) hi = npd - 1;
}

// The canonical assembly for buffers with a halo (GIMP): each node's value is 0.0 plus the
// values of the non-empty patches holding it, in ascending patch index, as assemble; the
// owner patch of each node gathers them (owners run in parallel).
void assemble_wide(const StepContext* c, int first, int count, double* dst_mass, double* dst_mom,
                   double* dst_force) {
  const int P = c->patch_cells, H = c->patch_halo, Q = P + 1 + 2 * H;
  const size_t pn = size_t(Q) * size_t(Q) * size_t(Q);
#pragma omp parallel for schedule(dynamic, 1)
  for (int q = 0; q < c->npatch; ++q) {
    const OwnedNodes o = owned_nodes(c, q);
    if (!o.active) continue;
    for (int k = o.lo[2]; k < o.hi[2]; ++k) {
      int zlo, zhi;
      patch_range(k, P, H, c->npd[2], zlo, zhi);
      for (int j = o.lo[1]; j < o.hi[1]; ++j) {
        int ylo, yhi;
        patch_range(j, P, H, c->npd[1], ylo, yhi);
        for (int i = o.lo[0]; i < o.hi[0]; ++i) {
          int xlo, xhi;
          patch_range(i, P, H, c->npd[0], xlo, xhi);
          double sum[kNodeFields] = {0, 0, 0, 0, 0, 0, 0};
          for (int qz = zlo; qz <= zhi; ++qz)
            for (int qy = ylo; qy <= yhi; ++qy)
              for (int qx = xlo; qx <= xhi; ++qx) {
                const int slot = c->patch_slot[qx + c->npd[0] * (qy + c->npd[1] * qz)];
                if (slot < 0) continue;
                const int ln = (i - qx * P + H) + Q * ((j - qy * P + H) + Q * (k - qz * P + H));
                const double* v = c->patch_buf + (size_t(slot) * pn + size_t(ln)) * kNodeFields + first;
                for (int f = 0; f < count; ++f) sum[f] += v[f];
              }
          const int n = i + c->nn[0] * (j + c->nn[1] * k);
          for (int f = 0; f < count; ++f) {
            const int field = first + f;
            if (field == 0) dst_mass[n] = sum[f];
            else if (field <= 3) dst_mom[3 * n + field - 1] = sum[f];
            else dst_force[3 * n + field - 4] = sum[f];
          }
        }
      }
    }
  }
}

// GIMP stencil of one particle: its cell (i, j, k), the stencil offsets o and the 27
// weights and gradients; node (a, b, c) of the stencil is grid node
// (i + o0 + a, j + o1 + b, k + o2 + c).
struct GimpStencil {
  int ci[3], o[3];
  double N[27], G[81];
};

inline void gimp_stencil(const StepContext* c, const CellDecoder& dec, int p, GimpStencil& s) {
  dec(c->cell[p], s.ci[0], s.ci[1], s.ci[2]);
  const double* lx = c->lx + 3 * p;
  for (int a = 0; a < 3; ++a) s.o[a] = gimp_offset(lx[a], s.ci[a], c->nc[a]);
  shape_gimp(lx, s.o, c->psize[p] * c->inv_h, c->inv_h, s.N, s.G);
}

// Global node index of the stencil's first node (a = b = c = 0).
inline int gimp_corner(const StepContext* c, const GimpStencil& s) {
  return (s.ci[0] + s.o[0]) + c->nn[0] * ((s.ci[1] + s.o[1]) + c->nn[1] * (s.ci[2] + s.o[2]));
}

// Buffer node index, in the buffer of patch q3 (halo 1), of the stencil's first node.
inline int gimp_patch_corner(const StepContext* c, const int q3[3], const GimpStencil& s) {
  const int P = c->patch_cells, H = c->patch_halo, Q = P + 1 + 2 * H;
  return (s.ci[0] + s.o[0] - q3[0] * P + H) +
         Q * ((s.ci[1] + s.o[1] - q3[1] * P + H) + Q * (s.ci[2] + s.o[2] - q3[2] * P + H));
}

// Offset of stencil node k = a + 3 b + 9 c from the stencil's first node, in an array of
// row length r0 and plane size r0 r1.
inline int stencil_offset(int k, int r0, int r1) {
  const int a = k % 3, b = (k / 3) % 3, cc = k / 9;
  return a + r0 * (b + r1 * cc);
}

// Boundary conditions of the box faces on a nodal vector field (3,nnode):
// 1 fixed (all components zero), 2 symmetry (normal component zero).
void apply_bc(const StepContext* c, double* a) {
  for (int face = 0; face < 6; ++face) {
    const int kind = c->fix[face];
    if (kind == 0) continue;
    const int axis = face / 2;
    const int fixed_index = (face % 2 == 0) ? 0 : c->nn[axis] - 1;
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    for (int jw = 0; jw < c->nn[w]; ++jw)
      for (int ju = 0; ju < c->nn[u]; ++ju) {
        int idx[3];
        idx[axis] = fixed_index;
        idx[u] = ju;
        idx[w] = jw;
        const int n = idx[0] + c->nn[0] * (idx[1] + c->nn[1] * idx[2]);
        if (kind == 1) {
          a[3 * n + 0] = 0.0;
          a[3 * n + 1] = 0.0;
          a[3 * n + 2] = 0.0;
        } else {
          a[3 * n + axis] = 0.0;
        }
      }
  }
}

void scatter_p2g_gimp(StepContext* c, bool with_mass_mom, bool with_forces);

// Scatter of mass, momentum and (optionally) forces of every particle into its patch buffer.
void scatter_p2g(StepContext* c, bool with_mass_mom, bool with_forces) {
  if (c->shape == 1) {
    scatter_p2g_gimp(c, with_mass_mom, with_forces);
    return;
  }
  const bool avx2 = lanes_use_avx2();
  for_thread_patches(c, with_mass_mom ? LOOP_P2G : LOOP_FORCES, [&](int q) {
    if (c->patch_slot[q] < 0) return;
    if (avx2)
      p2g_patch_avx2(c, q, with_mass_mom, with_forces);
    else
      p2g_patch<VectorLane<kLanes>>(c, CellDecoder(c), q, with_mass_mom, with_forces);
  });
}

// The same with the 27-node GIMP stencils (buffers with a halo of one node layer).
void scatter_p2g_gimp(StepContext* c, bool with_mass_mom, bool with_forces) {
  const int Q = c->patch_cells + 1 + 2 * c->patch_halo;
  const int pn = patch_nodes(c);
  const CellDecoder dec(c);
#pragma omp parallel for schedule(dynamic, 1)
  for (int q = 0; q < c->npatch; ++q) {
    const int slot = c->patch_slot[q];
    if (slot < 0) continue;
    int q3[3];
    patch_coords(c, q, q3);
    double* buf = patch_buffer(c, slot);
    std::memset(buf, 0, sizeof(double) * size_t(pn) * kNodeFields);
    for (int idx = c->patch_start[q]; idx < c->patch_start[q + 1]; ++idx) {
      const int p = c->patch_part[idx];
      GimpStencil st;
      gimp_stencil(c, dec, p, st);
      const int base = gimp_patch_corner(c, q3, st);
      p2g_particle<27>(c, p, st.N, st.G, with_mass_mom, with_forces, c->has_body_force != 0,
                       [&](int k) { return buf + size_t(base + stencil_offset(k, Q, Q)) * kNodeFields; });
    }
  }
}

// G2P with the GIMP stencils: as mpm3d_cxx_g2p.
void g2p_gimp(StepContext* c) {
  const bool remap = c->scheme == SCHEME_MUSL;
  const int Q = c->patch_cells + 1 + 2 * c->patch_halo;
  const int pn = patch_nodes(c);
  const double cutoff = c->mass_cutoff, dt = c->dt, dt_int = c->dt_int;
  const int nn0 = c->nn[0], nn1 = c->nn[1];
  const CellDecoder dec(c);
#pragma omp parallel for schedule(dynamic, 1)
  for (int q = 0; q < c->npatch; ++q) {
    const int slot = c->patch_slot[q];
    if (slot < 0) continue;
    int q3[3];
    patch_coords(c, q, q3);
    double* buf = patch_buffer(c, slot);
    if (remap)
      for (int ln = 0; ln < pn; ++ln)
        for (int f = 1; f <= 3; ++f) buf[size_t(ln) * kNodeFields + f] = 0.0;
    for (int idx = c->patch_start[q]; idx < c->patch_start[q + 1]; ++idx) {
      const int p = c->patch_part[idx];
      GimpStencil st;
      gimp_stencil(c, dec, p, st);
      const int base = gimp_corner(c, st);
      double ax = 0.0, ay = 0.0, az = 0.0, ux = 0.0, uy = 0.0, uz = 0.0;
      for (int k = 0; k < 27; ++k) {
        const int n = base + stencil_offset(k, nn0, nn1);
        const double m = c->gmass[n];
        if (!(m > cutoff)) continue;
        const double r = st.N[k] / m;
        const double* f = c->gforce + 3 * n;
        const double* pm = c->gmom + 3 * n;
        ax += f[0] * r;
        ay += f[1] * r;
        az += f[2] * r;
        ux += pm[0] * r;
        uy += pm[1] * r;
        uz += pm[2] * r;
      }
      double* vp = c->v + 3 * p;
      double* xp = c->x + 3 * p;
      vp[0] = vp[0] + ax * dt_int;
      vp[1] = vp[1] + ay * dt_int;
      vp[2] = vp[2] + az * dt_int;
      xp[0] = xp[0] + ux * dt;
      xp[1] = xp[1] + uy * dt;
      xp[2] = xp[2] + uz * dt;
      if (remap) {
        const int pbase = gimp_patch_corner(c, q3, st);
        const double mp = c->mass[p];
        for (int k = 0; k < 27; ++k) {
          double* b = buf + size_t(pbase + stencil_offset(k, Q, Q)) * kNodeFields;
          const double mn = mp * st.N[k];
          b[1] += mn * vp[0];
          b[2] += mn * vp[1];
          b[3] += mn * vp[2];
        }
      }
    }
  }
  if (remap) {
    assemble(c, LOOP_REMAP_ASSEMBLY, 1, 3, c->gmass, c->gmom, c->gforce);
    apply_bc(c, c->gmom);
  }
}

// Velocity gradient L[3a+b] = d v_a / d x_b of particle p from the node velocities gvel,
// summed over the 27 GIMP stencil nodes in stencil order (the trilinear one:
// gradient_values in transfer_lanes.hpp).
inline void velocity_gradient_gimp(const StepContext* c, const CellDecoder& dec, int p, const double* gvel,
                                   double L[9]) {
  double l0 = 0, l1 = 0, l2 = 0, l3 = 0, l4 = 0, l5 = 0, l6 = 0, l7 = 0, l8 = 0;
  GimpStencil st;
  gimp_stencil(c, dec, p, st);
  const int base = gimp_corner(c, st);
  for (int k = 0; k < 27; ++k) {
    const int n = base + stencil_offset(k, c->nn[0], c->nn[1]);
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

// The particle loop of the stress stage: velocity gradients from the node velocities
// gvel, then strain and spin increments, volume and stress update, consecutive particles
// of one material kStressLanes at a time (stress_block; a shorter run lane by lane).
// Trilinear: chunks of the patch lists, gradients in lanes too (stress_list, transfer_lanes.hpp);
// GIMP: in fixed particle chunks.
void stress_particles(StepContext* c, const double* gvel) {
  const CellDecoder dec(c);
  const StressBlockArgs args{c->dt, c->temp != nullptr, c->qv != nullptr, c->bulk_q1, c->bulk_q2, c->h};
  if (c->shape != 1) {
    const bool avx2 = lanes_use_avx2();
    // Each particle's update is its own, so the lists go in chunks across patch ends.
    for_thread_list_chunks(c, LOOP_STRESS, [&](int first, int count) {
      const int* list = c->patch_part + first;
      if (avx2)
        stress_list_avx2(c, list, count, gvel, args);
      else
        stress_list<VectorLane<kLanes>>(c, dec, list, count, gvel, args);
    });
    return;
  }
  const bool filter = c->only_comp > 0;
  constexpr int kChunk = 256;
  const int nchunk = (c->np + kChunk - 1) / kChunk;
#pragma omp parallel for schedule(dynamic, 1)
  for (int ch = 0; ch < nchunk; ++ch) {
    StressBlock b;
    int part[kStressLanes];
    int n = 0, mat = -1;
    auto flush = [&]() {
      const MaterialParams& mp = c->mats[mat];
      if (n == kStressLanes)
        stress_block(mp, b, args);
      else
        for (int i = 0; i < n; ++i) stress_block_lane(mp, b, i, args);
      for (int i = 0; i < n; ++i) stress_block_store(c, part[i], i, b);
      n = 0;
    };
    const int hi = std::min(c->np, (ch + 1) * kChunk);
    for (int p = ch * kChunk; p < hi; ++p) {
      if (c->cell[p] < 0) continue;
      if (filter && other_component(c, p)) continue;
      if (n > 0 && c->mat[p] != mat) flush();
      mat = c->mat[p];
      double L[9];
      velocity_gradient_gimp(c, dec, p, gvel, L);
      for (int r = 0; r < 9; ++r) b.L[r][n] = L[r];
      stress_block_load(c, c->mats[mat], p, n, b);
      part[n++] = p;
      if (n == kStressLanes) flush();
    }
    if (n > 0) flush();
  }
}

// Contact: g_i = sum_p m_p grad N_i(x_p) of the context's particles (the outward normal
// direction of its body at node i) into gnormal,
// through the force fields (4-6) of the patch buffers, which no stage reads after the
// force assembly.
void scatter_mass_gradient(StepContext* c) {
  const int P = c->patch_cells, Q = P + 1 + 2 * c->patch_halo;
  const int pn = patch_nodes(c);
  const CellDecoder dec(c);
#pragma omp parallel for schedule(dynamic, 1)
  for (int q = 0; q < c->npatch; ++q) {
    const int slot = c->patch_slot[q];
    if (slot < 0) continue;
    int q3[3];
    patch_coords(c, q, q3);
    double* buf = patch_buffer(c, slot);
    for (int ln = 0; ln < pn; ++ln)
      for (int f = 4; f <= 6; ++f) buf[size_t(ln) * kNodeFields + f] = 0.0;
    for (int idx = c->patch_start[q]; idx < c->patch_start[q + 1]; ++idx) {
      const int p = c->patch_part[idx];
      const double mp = c->mass[p];
      if (c->shape == 1) {
        GimpStencil st;
        gimp_stencil(c, dec, p, st);
        const int base = gimp_patch_corner(c, q3, st);
        for (int k = 0; k < 27; ++k) {
          double* b = buf + size_t(base + stencil_offset(k, Q, Q)) * kNodeFields;
          b[4] += mp * st.G[3 * k];
          b[5] += mp * st.G[3 * k + 1];
          b[6] += mp * st.G[3 * k + 2];
        }
      } else {
        double N[8], G[24];
        shape_linear(c->lx + 3 * p, c->inv_h, N, G);
        const int base = patch_base(c, dec, q3, c->cell[p]);
        for (int k = 0; k < 8; ++k) {
          double* b = buf + size_t(base + patch_local(P, k)) * kNodeFields;
          b[4] += mp * G[3 * k];
          b[5] += mp * G[3 * k + 1];
          b[6] += mp * G[3 * k + 2];
        }
      }
    }
  }
  assemble(c, LOOP_NORMAL_ASSEMBLY, 4, 3, c->gmass, c->gmom, c->gnormal);
}

}  // namespace

// The load balance of the patch stages, before the patch lists change, loop by loop
// (PatchLoop): each thread's speed in a loop (the particles it did there per busy second
// since the last binning: thread_done, else those of its range) gives its share of that
// loop in the next step, taken halfway to damp the jumps of the patch granularity. A thread that had no particles counts at the
// mean speed, and no share falls below a tenth of an equal one. On this project's virtual
// machines one core can run 1.5x slower than the other for minutes; equal ranges then
// leave the fast thread waiting a third of each step. A loop that did not run keeps its
// shares. The shares start equal, and again whenever the number of threads changes.
void rebalance_threads(StepContext* c) {
  if (!c->thread_share) return;
  int T = 1;
#ifdef _OPENMP
  T = omp_get_max_threads();
#endif
  if (T > kMaxBalancedThreads) {
    c->nshare = 0;
    return;
  }
  if (T != c->nshare) {
    c->nshare = T;
    for (int loop = 0; loop < LOOP_COUNT; ++loop)
      for (int t = 0; t < T; ++t) {
        c->thread_share[balance_index(loop, t)] = 1.0 / T;
        c->thread_busy[balance_index(loop, t)] = 0.0;
        if (c->thread_done) c->thread_done[balance_index(loop, t)] = 0.0;
      }
    return;
  }
  std::vector<double> rate(size_t(T), 0.0);
  for (int loop = 0; loop < LOOP_COUNT; ++loop) {
    double* share = c->thread_share + balance_index(loop, 0);
    double* busy = c->thread_busy + balance_index(loop, 0);
    double* done = c->thread_done ? c->thread_done + balance_index(loop, 0) : nullptr;
    double sum = 0.0;
    int known = 0;
    for (int t = 0; t < T && T > 1; ++t) {
      int lo, hi;
      double n;
      if (loop == LOOP_BIN) {
        thread_particles(c, t, T, lo, hi);
        n = hi - lo;
      } else if (done) {
        n = done[t];  // its own range and what it took from others
      } else if (loop == LOOP_STRESS) {
        thread_list_chunks(c, LOOP_STRESS, t, T, lo, hi);
        n = list_chunk_entries(c, lo, hi);
      } else {
        thread_patches(c, PatchLoop(loop), t, T, lo, hi);
        n = c->patch_start[hi] - c->patch_start[lo];
      }
      rate[size_t(t)] = 0.0;
      if (n > 0 && busy[t] > 0.0) {
        rate[size_t(t)] = n / busy[t];
        sum += rate[size_t(t)];
        ++known;
      }
    }
    if (known > 0) {
      const double mean = sum / known;
      for (int t = 0; t < T; ++t)
        if (!(rate[size_t(t)] > 0.0)) rate[size_t(t)] = mean, sum += mean;
      double total = 0.0;
      for (int t = 0; t < T; ++t) {
        share[t] = std::max(0.1 / T, 0.5 * share[t] + 0.5 * rate[size_t(t)] / sum);
        total += share[t];
      }
      for (int t = 0; t < T; ++t) share[t] /= total;
    }
    for (int t = 0; t < T; ++t) {
      busy[t] = 0.0;
      if (done) done[t] = 0.0;
    }
  }
}

}  // namespace mpm3d

using namespace mpm3d;

extern "C" void mpm3d_cxx_bin(StepContext* c) {
  rebalance_threads(c);
  const int npatch = c->npatch;
  int* patch_of = c->pscratch;  // patch of each particle, -1 outside
  int outside = 0, nslot = 0;
  int team = 1;
#ifdef _OPENMP
  team = omp_get_max_threads();
#endif
  // One row of patch counts per thread, each zeroed by its thread.
  std::unique_ptr<int[]> counts(new int[size_t(team) * size_t(npatch)]);
  // Particles and non-empty patches of each thread's run of patches (own cache lines).
  struct alignas(64) RunSums {
    int particles, nonempty;
  };
  std::vector<RunSums> run_sums(static_cast<size_t>(team), RunSums{0, 0});
  const bool avx2 = lanes_use_avx2();
  // One team for the whole stage: each thread bins a run of particles sized by its share
  // (in the block storage order (order_by_blocks) about the particles its patch range
  // holds) and counts them by patch; then a stable counting sort with those runs as its
  // chunks. The runs are consecutive and ascending, so each patch lists its particles in
  // ascending index whatever the number of threads: the lists do not depend on it.
#pragma omp parallel num_threads(team) reduction(+ : outside)
  {
    int t, T, lo, hi;
    team_position(t, T);
    thread_particles(c, t, T, lo, hi);
    const bool timed = balance_timed(c, T);
    const double t0 = timed ? busy_clock() : 0.0;
    int* cnt = counts.get() + size_t(t) * size_t(npatch);
    std::fill(cnt, cnt + npatch, 0);
    // Cells, local coordinates, patches (transfer_lanes.hpp).
    outside += avx2 ? bin_range_avx2(c, lo, hi, patch_of) : bin_range<VectorLane<kLanes>>(c, lo, hi, patch_of);
    for (int p = lo; p < hi; ++p)
      if (patch_of[p] >= 0) ++cnt[patch_of[p]];
    if (timed) add_busy(c, LOOP_BIN, t, t0);
#pragma omp barrier
    // Patch starts, buffer slots, and each run's fill pointer into every patch's list: a
    // prefix sum over the patches in two passes, each thread over an equal run of patches
    // (a serial pass would cost T x npatch steps on one thread, about 1 % of a step of the
    // fine model at 16 threads): the run's particle and non-empty patch totals, then,
    // once every run has its totals, the run's own entries.
    const int q0 = int(int64_t(npatch) * t / T), q1 = int(int64_t(npatch) * (t + 1) / T);
    auto count_of = [&](int u, int q) -> int& { return counts[size_t(u) * size_t(npatch) + size_t(q)]; };
    {
      int particles = 0, nonempty = 0;
      for (int q = q0; q < q1; ++q) {
        int total = 0;
        for (int u = 0; u < T; ++u) total += count_of(u, q);
        particles += total;
        nonempty += total > 0;
      }
      run_sums[size_t(t)] = {particles, nonempty};
    }
#pragma omp barrier
    {
      int offset = 0, slot = 0;
      for (int u = 0; u < t; ++u) {
        offset += run_sums[size_t(u)].particles;
        slot += run_sums[size_t(u)].nonempty;
      }
      for (int q = q0; q < q1; ++q) {
        c->patch_start[q] = offset;
        int total = 0;
        for (int u = 0; u < T; ++u) {
          int& n = count_of(u, q);
          const int here = n;
          n = offset + total;
          total += here;
        }
        c->patch_slot[q] = total > 0 ? slot++ : -1;
        offset += total;
      }
      if (t == T - 1) {
        c->patch_start[npatch] = offset;
        nslot = slot;
      }
    }
#pragma omp barrier
    for (int p = lo; p < hi; ++p)
      if (patch_of[p] >= 0) c->patch_part[cnt[patch_of[p]]++] = p;
  }
  c->nslot = nslot;
  c->noutside = outside;
}

extern "C" void mpm3d_cxx_p2g(StepContext* c) {
  const bool forces = c->scheme != SCHEME_USF;
  scatter_p2g(c, true, forces);
  assemble(c, LOOP_P2G_ASSEMBLY, 0, forces ? 7 : 4, c->gmass, c->gmom, c->gforce);
  apply_bc(c, c->gmom);
}

extern "C" void mpm3d_cxx_forces(StepContext* c) {
  scatter_p2g(c, false, true);
  assemble(c, LOOP_FORCES_ASSEMBLY, 4, 3, c->gmass, c->gmom, c->gforce);
}

extern "C" void mpm3d_cxx_integrate(StepContext* c) {
  const double dt = c->dt_int;
  double* mom = c->gmom;
  const double* f = c->gforce;
  for_thread_patches(c, LOOP_INTEGRATE, [&](int q) {
    const OwnedNodes o = owned_nodes(c, q);
    if (!o.active) return;
    for (int k = o.lo[2]; k < o.hi[2]; ++k)
      for (int j = o.lo[1]; j < o.hi[1]; ++j) {
        const int row = 3 * (c->nn[0] * (j + c->nn[1] * k));
        for (int i = row + 3 * o.lo[0]; i < row + 3 * o.hi[0]; ++i) mom[i] = mom[i] + f[i] * dt;
      }
  });
  apply_bc(c, c->gmom);
  apply_bc(c, c->gforce);
}

extern "C" void mpm3d_cxx_g2p(StepContext* c) {
  if (c->shape == 1) {
    g2p_gimp(c);
    return;
  }
  const bool remap = c->scheme == SCHEME_MUSL;
  const bool avx2 = lanes_use_avx2();
  for_thread_patches(c, LOOP_G2P, [&](int q) {
    if (c->patch_slot[q] < 0) return;
    if (avx2)
      g2p_patch_avx2(c, q, remap);
    else
      g2p_patch<VectorLane<kLanes>>(c, CellDecoder(c), q, remap);
  });
  if (remap) {
    assemble(c, LOOP_REMAP_ASSEMBLY, 1, 3, c->gmass, c->gmom, c->gforce);
    apply_bc(c, c->gmom);
  }
}

extern "C" void mpm3d_cxx_stress(StepContext* c) {
  const double cutoff = c->mass_cutoff;
  // Node velocities once per node (the same division p/m as per particle, so the same bits).
  // They are kept in the force array, which no stage reads again before the next p2g or
  // forces stage overwrites it (USF: stress runs before forces).
  double* gvel = c->gforce;
  for_thread_patches(c, LOOP_NODE_VELOCITY, [&](int q) {
    const OwnedNodes o = owned_nodes(c, q);
    if (!o.active) return;
    for (int k = o.lo[2]; k < o.hi[2]; ++k)
      for (int j = o.lo[1]; j < o.hi[1]; ++j)
        for (int i = o.lo[0]; i < o.hi[0]; ++i) {
          const int n = i + c->nn[0] * (j + c->nn[1] * k);
          const double m = c->gmass[n];
          if (!(m > cutoff)) continue;
          for (int a = 0; a < 3; ++a) gvel[3 * n + a] = c->gmom[3 * n + a] / m;
        }
  });
  stress_particles(c, gvel);
}

extern "C" void mpm3d_cxx_energy(StepContext* c) {
  const int B = c->reduce_block;
  const int nblock = (c->np + B - 1) / B;
#pragma omp parallel for schedule(static)
  for (int blk = 0; blk < nblock; ++blk) {
    double part[kReduceFields] = {0, 0, 0, 0, 0};
    const int end = (blk + 1) * B < c->np ? (blk + 1) * B : c->np;
    for (int p = blk * B; p < end; ++p) {
      const double m = c->mass[p];
      const double* vp = c->v + 3 * p;
      part[0] += (0.5 * m) * ((vp[0] * vp[0] + vp[1] * vp[1]) + vp[2] * vp[2]);
      part[1] += c->ie[p];
      part[2] += m * vp[0];
      part[3] += m * vp[1];
      part[4] += m * vp[2];
    }
    for (int f = 0; f < kReduceFields; ++f) c->partials[kReduceFields * blk + f] = part[f];
  }
  // Fixed-order fold of the block partials: the same sums for any thread count.
  for (int f = 0; f < kReduceFields; ++f) {
    double s = 0.0;
    for (int blk = 0; blk < nblock; ++blk) s += c->partials[kReduceFields * blk + f];
    c->result[f] = s;
  }
}

// Multi-velocity contact (Bardenhagen et al. 2000, 2001; Huang et al. 2011) between
// component 1 (this context) and component 2 (c->other). At a node where both components
// have mass above the cut-off:
// - the unit normal n points from component 1 into component 2; it is g1 (normbody 1),
//   -g2 (2) or g1 - g2 (0), normalised, where g_k = sum_p m_p grad N_i(x_p) over the
//   particles of component k points out of body k;
// - q = (m2 p1 - m1 p2)/(m1 + m2) is the momentum component 1 gives up to reach the common
//   velocity; component 1's momentum changes by d = -(q.n n + f t), t = q - q.n n the
//   tangential part, f = 1 (stick) or mu |q.n| / |t| when |t| exceeds mu |q.n| (Coulomb
//   slip), and component 2's by -d.
// Stage `contact` (after both integrates): the nodes where the components approach
// (q.n > 0) are corrected, their forces change by d/dt_int (so that G2P's accelerations
// agree with the corrected momenta), and the unit normal of each corrected node is kept in
// this context's gnormal (zero at the other nodes of the loop), marking the node as in
// contact for this step. The contact force on component 1, the sum of d/dt_int over the
// nodes, goes to result[5..7]: per-patch partials (owned nodes in k, j, i order) folded in
// patch order.
// Stage `recontact`: the momenta of the nodes marked in contact are corrected again with
// the kept normals, for either sign of q.n, so that the strain rates see the same normal
// velocity for both bodies at these nodes as the position update did. MUSL runs it after
// both G2P remaps of the step, USF after both P2Gs of the next step (before the stresses;
// the marks of the previous step, which is why with USF the `contact` stage also clears
// the nodes of patches outside its loop). Without it the velocities that the strain rates
// read separate at nodes whose corrected velocities did not, and the stresses of the
// rebounding bodies release more work than the bodies did (the spheres deck gained
// 9-67% of its energy per impact, more with larger steps).
// Both stages apply the boundary conditions again.
namespace {

template <bool kRemap>
void contact_correct(StepContext* c) {
  StepContext* c2 = c->other;
  const double cutoff = c->mass_cutoff, mu = c->contact_mu, dt_int = c->dt_int;
  const int nb = c->contact_normbody;
  int count = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : count)
  for (int q = 0; q < c->npatch; ++q) {
    double part[3] = {0.0, 0.0, 0.0};
    const OwnedNodes o = owned_nodes(c, q);
    if (o.active && owned_nodes(c2, q).active) {
      for (int k = o.lo[2]; k < o.hi[2]; ++k)
        for (int j = o.lo[1]; j < o.hi[1]; ++j)
          for (int i = o.lo[0]; i < o.hi[0]; ++i) {
            const int n = i + c->nn[0] * (j + c->nn[1] * k);
            const double m1 = c->gmass[n], m2 = c2->gmass[n];
            double* g1 = c->gnormal + 3 * n;
            if (!(m1 > cutoff) || !(m2 > cutoff)) {
              if (!kRemap) g1[0] = g1[1] = g1[2] = 0.0;
              continue;
            }
            double un[3], qv[3];
            if (kRemap) {
              if (g1[0] == 0.0 && g1[1] == 0.0 && g1[2] == 0.0) continue;  // not in contact
              for (int a = 0; a < 3; ++a) un[a] = g1[a];
            } else {
              const double* g2 = c2->gnormal + 3 * n;
              double nv[3];
              for (int a = 0; a < 3; ++a) nv[a] = nb == 1 ? g1[a] : (nb == 2 ? -g2[a] : g1[a] - g2[a]);
              for (int a = 0; a < 3; ++a) g1[a] = 0.0;
              const double len = std::sqrt((nv[0] * nv[0] + nv[1] * nv[1]) + nv[2] * nv[2]);
              if (!(len > 0.0)) continue;
              for (int a = 0; a < 3; ++a) un[a] = nv[a] / len;
            }
            double* p1 = c->gmom + 3 * n;
            double* p2 = c2->gmom + 3 * n;
            const double mt = m1 + m2;
            for (int a = 0; a < 3; ++a) qv[a] = (m2 * p1[a] - m1 * p2[a]) / mt;
            const double qn = (qv[0] * un[0] + qv[1] * un[1]) + qv[2] * un[2];
            if (!kRemap) {
              if (!(qn > 0.0)) continue;
              for (int a = 0; a < 3; ++a) g1[a] = un[a];  // in contact this step
            }
            double t[3];
            for (int a = 0; a < 3; ++a) t[a] = qv[a] - qn * un[a];
            const double tl = std::sqrt((t[0] * t[0] + t[1] * t[1]) + t[2] * t[2]);
            const double fr = mu * std::fabs(qn);
            const double ft = tl > fr ? fr / tl : 1.0;
            double* f1 = c->gforce + 3 * n;
            double* f2 = c2->gforce + 3 * n;
            for (int a = 0; a < 3; ++a) {
              const double d = -(qn * un[a] + ft * t[a]);
              p1[a] = p1[a] + d;
              p2[a] = p2[a] - d;
              if (!kRemap) {
                const double fc = d / dt_int;
                f1[a] = f1[a] + fc;
                f2[a] = f2[a] - fc;
                part[a] += fc;
              }
            }
            ++count;
          }
    } else if (!kRemap && c->scheme == SCHEME_USF) {
      // USF reads the marks again in the next step (recontact before the stresses): no
      // node outside this loop keeps a mark or a mass gradient.
      for (int k = o.lo[2]; k < o.hi[2]; ++k)
        for (int j = o.lo[1]; j < o.hi[1]; ++j)
          for (int i = o.lo[0]; i < o.hi[0]; ++i) {
            double* g1 = c->gnormal + 3 * (i + c->nn[0] * (j + c->nn[1] * k));
            g1[0] = g1[1] = g1[2] = 0.0;
          }
    }
    if (!kRemap)
      for (int a = 0; a < 3; ++a) c->cpartials[3 * q + a] = part[a];
  }
  apply_bc(c, c->gmom);
  apply_bc(c2, c2->gmom);
  if (kRemap) return;
  for (int a = 0; a < 3; ++a) {
    double s = 0.0;
    for (int q = 0; q < c->npatch; ++q) s += c->cpartials[3 * q + a];
    c->result[5 + a] = s;
  }
  c->ncontact = count;
  apply_bc(c, c->gforce);
  apply_bc(c2, c2->gforce);
}

}  // namespace

extern "C" void mpm3d_cxx_contact(StepContext* c) {
  if (!c->other) return;
  scatter_mass_gradient(c);
  scatter_mass_gradient(c->other);
  contact_correct<false>(c);
}

extern "C" void mpm3d_cxx_recontact(StepContext* c) {
  if (!c->other) return;
  contact_correct<true>(c);
}
