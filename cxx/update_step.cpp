#include "update_step.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "constitution.hpp"
#include "grid.hpp"

namespace mpm3d {

const char* const kStageNames[ST_COUNT] = {"bin", "p2g", "forces", "integrate",
                                           "g2p", "stress", "energy"};

StageTable cxx_stages() {
  return StageTable{{mpm3d_cxx_bin, mpm3d_cxx_p2g, mpm3d_cxx_forces, mpm3d_cxx_integrate,
                     mpm3d_cxx_g2p, mpm3d_cxx_stress, mpm3d_cxx_energy}};
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
                     mpm3d_f_stress, mpm3d_f_energy}};
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

// Global node index of the base node of a cell.
inline int base_node(const StepContext* c, int cell) {
  const int i = cell % c->nc[0];
  const int j = (cell / c->nc[0]) % c->nc[1];
  const int k = cell / (c->nc[0] * c->nc[1]);
  return i + c->nn[0] * (j + c->nn[1] * k);
}

// Global node index of local node k (offsets a, b, c) relative to a base node.
inline int node_of(const StepContext* c, int base, int k) {
  return base + (k & 1) + c->nn[0] * (((k >> 1) & 1) + c->nn[1] * ((k >> 2) & 1));
}

inline double* patch_buffer(const StepContext* c, int slot) {
  const int pn = (c->patch_cells + 1) * (c->patch_cells + 1) * (c->patch_cells + 1);
  return c->patch_buf + size_t(slot) * size_t(pn) * kNodeFields;
}

// Local node index, in its patch buffer, of the base node of particle p's cell.
inline int patch_base(const StepContext* c, int q, int cell) {
  const int P = c->patch_cells, Q = P + 1;
  const int qx = q % c->npd[0], qy = (q / c->npd[0]) % c->npd[1], qz = q / (c->npd[0] * c->npd[1]);
  const int i = cell % c->nc[0] - qx * P;
  const int j = (cell / c->nc[0]) % c->nc[1] - qy * P;
  const int k = cell / (c->nc[0] * c->nc[1]) - qz * P;
  return i + Q * (j + Q * k);
}

inline int patch_local(int P, int k) {
  const int Q = P + 1;
  return (k & 1) + Q * (((k >> 1) & 1) + Q * ((k >> 2) & 1));
}

// Canonical assembly (DESIGN.md section 4): each node's value is 0.0 plus the values of
// the non-empty patches holding it, in ascending patch index (x fastest, then y, z).
// Fields first..first+count-1 of the buffers go to dst_mass (field 0), dst_mom (1-3)
// and dst_force (4-6).
void assemble(const StepContext* c, int first, int count, double* dst_mass, double* dst_mom,
              double* dst_force) {
  const int P = c->patch_cells, Q = P + 1;
  for (int k = 0; k < c->nn[2]; ++k) {
    int qz_lo = (k > 0 && k % P == 0) ? k / P - 1 : k / P;
    int qz_hi = k / P;
    if (qz_hi > c->npd[2] - 1) qz_hi = c->npd[2] - 1;
    if (qz_lo > qz_hi) qz_lo = qz_hi;
    for (int j = 0; j < c->nn[1]; ++j) {
      int qy_lo = (j > 0 && j % P == 0) ? j / P - 1 : j / P;
      int qy_hi = j / P;
      if (qy_hi > c->npd[1] - 1) qy_hi = c->npd[1] - 1;
      if (qy_lo > qy_hi) qy_lo = qy_hi;
      for (int i = 0; i < c->nn[0]; ++i) {
        int qx_lo = (i > 0 && i % P == 0) ? i / P - 1 : i / P;
        int qx_hi = i / P;
        if (qx_hi > c->npd[0] - 1) qx_hi = c->npd[0] - 1;
        if (qx_lo > qx_hi) qx_lo = qx_hi;
        double sum[kNodeFields];
        for (int f = 0; f < count; ++f) sum[f] = 0.0;
        for (int qz = qz_lo; qz <= qz_hi; ++qz)
          for (int qy = qy_lo; qy <= qy_hi; ++qy)
            for (int qx = qx_lo; qx <= qx_hi; ++qx) {
              const int q = qx + c->npd[0] * (qy + c->npd[1] * qz);
              const int slot = c->patch_slot[q];
              if (slot < 0) continue;
              const int ln = (i - qx * P) + Q * ((j - qy * P) + Q * (k - qz * P));
              const double* b = patch_buffer(c, slot) + size_t(ln) * kNodeFields + first;
              for (int f = 0; f < count; ++f) sum[f] += b[f];
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

// Scatter of mass, momentum and (optionally) forces of every particle into its patch buffer.
void scatter_p2g(StepContext* c, bool with_mass_mom, bool with_forces) {
  const int P = c->patch_cells;
  const int pn = (P + 1) * (P + 1) * (P + 1);
  for (int q = 0; q < c->npatch; ++q) {
    const int slot = c->patch_slot[q];
    if (slot < 0) continue;
    double* buf = patch_buffer(c, slot);
    std::memset(buf, 0, sizeof(double) * size_t(pn) * kNodeFields);
    for (int idx = c->patch_start[q]; idx < c->patch_start[q + 1]; ++idx) {
      const int p = c->patch_part[idx];
      double N[8], G[24];
      shape_linear(c->lx + 3 * p, c->inv_h, N, G);
      const int base = patch_base(c, q, c->cell[p]);
      const double mp = c->mass[p];
      const double* vp = c->v + 3 * p;
      double vs[6] = {0, 0, 0, 0, 0, 0}, fb[3] = {0, 0, 0};
      if (with_forces) {
        const double volp = c->vol[p];
        for (int s = 0; s < 6; ++s) vs[s] = c->sig[6 * p + s] * volp;
        if (c->has_body_force) {
          const double* g = c->gravity + 3 * c->body[p];
          for (int a = 0; a < 3; ++a) {
            fb[a] = mp * g[a];
            if (c->fext) fb[a] = fb[a] + c->fext[3 * p + a];
          }
        }
      }
      for (int k = 0; k < 8; ++k) {
        double* b = buf + size_t(base + patch_local(P, k)) * kNodeFields;
        if (with_mass_mom) {
          const double mn = mp * N[k];
          b[0] += mn;
          b[1] += mn * vp[0];
          b[2] += mn * vp[1];
          b[3] += mn * vp[2];
        }
        if (with_forces) {
          const double gx = G[3 * k], gy = G[3 * k + 1], gz = G[3 * k + 2];
          double fx = -((vs[0] * gx + vs[5] * gy) + vs[4] * gz);
          double fy = -((vs[5] * gx + vs[1] * gy) + vs[3] * gz);
          double fz = -((vs[4] * gx + vs[3] * gy) + vs[2] * gz);
          if (c->has_body_force) {
            fx = N[k] * fb[0] + fx;
            fy = N[k] * fb[1] + fy;
            fz = N[k] * fb[2] + fz;
          }
          b[4] += fx;
          b[5] += fy;
          b[6] += fz;
        }
      }
    }
  }
}

}  // namespace
}  // namespace mpm3d

using namespace mpm3d;

extern "C" void mpm3d_cxx_bin(StepContext* c) {
  const int P = c->patch_cells;
  int* start = c->patch_start;
  for (int q = 0; q <= c->npatch; ++q) start[q] = 0;
  int outside = 0;
  for (int p = 0; p < c->np; ++p) {
    int idx[3];
    bool in = true;
    for (int a = 0; a < 3; ++a) {
      const double t = (c->x[3 * p + a] - c->origin[a]) / c->h;
      const double fl = std::floor(t);
      if (!(fl >= 0.0 && fl < double(c->nc[a]))) {  // also catches NaN
        in = false;
        break;
      }
      idx[a] = int(fl);
      c->lx[3 * p + a] = t - fl;
    }
    if (!in) {
      c->cell[p] = -1;
      ++outside;
      continue;
    }
    c->cell[p] = idx[0] + c->nc[0] * (idx[1] + c->nc[1] * idx[2]);
    const int q = idx[0] / P + c->npd[0] * (idx[1] / P + c->npd[1] * (idx[2] / P));
    ++start[q + 1];
  }
  int nslot = 0;
  for (int q = 0; q < c->npatch; ++q) {
    c->patch_slot[q] = start[q + 1] > 0 ? nslot++ : -1;
    start[q + 1] += start[q];
  }
  c->nslot = nslot;
  c->noutside = outside;
  // Second pass: particles in ascending index within each patch (a stable counting sort).
  // The end offsets are rebuilt as fill pointers and restored afterwards.
  for (int q = c->npatch; q > 0; --q) start[q] = start[q - 1];
  start[0] = 0;
  for (int p = 0; p < c->np; ++p) {
    const int cell = c->cell[p];
    if (cell < 0) continue;
    const int i = cell % c->nc[0], j = (cell / c->nc[0]) % c->nc[1], k = cell / (c->nc[0] * c->nc[1]);
    const int q = i / P + c->npd[0] * (j / P + c->npd[1] * (k / P));
    c->patch_part[start[q + 1]++] = p;
  }
}

extern "C" void mpm3d_cxx_p2g(StepContext* c) {
  const bool forces = c->scheme != SCHEME_USF;
  scatter_p2g(c, true, forces);
  assemble(c, 0, forces ? 7 : 4, c->gmass, c->gmom, c->gforce);
  apply_bc(c, c->gmom);
}

extern "C" void mpm3d_cxx_forces(StepContext* c) {
  scatter_p2g(c, false, true);
  assemble(c, 4, 3, c->gmass, c->gmom, c->gforce);
}

extern "C" void mpm3d_cxx_integrate(StepContext* c) {
  const double dt = c->dt_int;
  for (int n = 0; n < c->nnode; ++n)
    for (int a = 0; a < 3; ++a) c->gmom[3 * n + a] = c->gmom[3 * n + a] + c->gforce[3 * n + a] * dt;
  apply_bc(c, c->gmom);
  apply_bc(c, c->gforce);
}

extern "C" void mpm3d_cxx_g2p(StepContext* c) {
  const bool remap = c->scheme == SCHEME_MUSL;
  const int P = c->patch_cells;
  const int pn = (P + 1) * (P + 1) * (P + 1);
  for (int q = 0; q < c->npatch; ++q) {
    const int slot = c->patch_slot[q];
    if (slot < 0) continue;
    double* buf = patch_buffer(c, slot);
    if (remap)
      for (int ln = 0; ln < pn; ++ln)
        for (int f = 1; f <= 3; ++f) buf[size_t(ln) * kNodeFields + f] = 0.0;
    for (int idx = c->patch_start[q]; idx < c->patch_start[q + 1]; ++idx) {
      const int p = c->patch_part[idx];
      double N[8], G[24];
      shape_linear(c->lx + 3 * p, c->inv_h, N, G);
      const int base = base_node(c, c->cell[p]);
      double acc[3] = {0.0, 0.0, 0.0}, vel[3] = {0.0, 0.0, 0.0};
      for (int k = 0; k < 8; ++k) {
        const int n = node_of(c, base, k);
        const double m = c->gmass[n];
        if (!(m > c->mass_cutoff)) continue;
        const double r = N[k] / m;
        for (int a = 0; a < 3; ++a) {
          acc[a] += c->gforce[3 * n + a] * r;
          vel[a] += c->gmom[3 * n + a] * r;
        }
      }
      double* vp = c->v + 3 * p;
      double* xp = c->x + 3 * p;
      for (int a = 0; a < 3; ++a) {
        vp[a] = vp[a] + acc[a] * c->dt_int;
        xp[a] = xp[a] + vel[a] * c->dt;
      }
      if (remap) {
        const int pbase = patch_base(c, q, c->cell[p]);
        const double mp = c->mass[p];
        for (int k = 0; k < 8; ++k) {
          double* b = buf + size_t(pbase + patch_local(P, k)) * kNodeFields;
          const double mn = mp * N[k];
          b[1] += mn * vp[0];
          b[2] += mn * vp[1];
          b[3] += mn * vp[2];
        }
      }
    }
  }
  if (remap) {
    assemble(c, 1, 3, c->gmass, c->gmom, c->gforce);
    apply_bc(c, c->gmom);
  }
}

extern "C" void mpm3d_cxx_stress(StepContext* c) {
  const double dt = c->dt;
  for (int p = 0; p < c->np; ++p) {
    const int cell = c->cell[p];
    if (cell < 0) continue;
    double N[8], G[24];
    shape_linear(c->lx + 3 * p, c->inv_h, N, G);
    const int base = base_node(c, cell);
    double L[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};  // L[3a+b] = d v_a / d x_b
    for (int k = 0; k < 8; ++k) {
      const int n = node_of(c, base, k);
      const double m = c->gmass[n];
      if (!(m > c->mass_cutoff)) continue;
      for (int a = 0; a < 3; ++a) {
        const double va = c->gmom[3 * n + a] / m;
        for (int b = 0; b < 3; ++b) L[3 * a + b] += va * G[3 * k + b];
      }
    }
    const double de[6] = {L[0] * dt, L[4] * dt, L[8] * dt, (0.5 * (L[5] + L[7])) * dt,
                          (0.5 * (L[2] + L[6])) * dt, (0.5 * (L[1] + L[3])) * dt};
    const double dw[3] = {(0.5 * (L[5] - L[7])) * dt, (0.5 * (L[2] - L[6])) * dt,
                          (0.5 * (L[1] - L[3])) * dt};
    const double vol_old = c->vol[p];
    const double vol_new = vol_old * (1.0 + ((de[0] + de[1]) + de[2]));
    StressState st{c->sig + 6 * p, c->epeff + p, c->ie + p, c->temp ? c->temp + p : nullptr};
    stress_update(c->mats[c->mat[p]], de, dw, dt, c->mass[p], vol_old, vol_new, st);
    c->vol[p] = vol_new;
  }
}

extern "C" void mpm3d_cxx_energy(StepContext* c) {
  const int B = c->reduce_block;
  const int nblock = (c->np + B - 1) / B;
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
  for (int f = 0; f < kReduceFields; ++f) {
    double s = 0.0;
    for (int blk = 0; blk < nblock; ++blk) s += c->partials[kReduceFields * blk + f];
    c->result[f] = s;
  }
}
