// update_step, benchmark alternative: the scatter stages with per-thread grid copies
// ("array expansion", the scheme the MPM3DMP paper compared with its patches).
//
// Every thread scatters a fixed contiguous range of particles (ascending index) into its
// own copy of the node fields (kNodeFields, nnode); the copies are then reduced node by
// node, in thread order: node = 0.0 + copy_0 + copy_1 + ... So results are deterministic
// for a given thread count but, unlike the patch scheme, NOT the same for different thread
// counts (the grouping of a node's sum follows the thread ranges), and at one thread they
// differ from the patch scheme by round-off only (one running sum over the particles
// instead of per-patch partial sums). Selected with `mpm3d --scatter expansion`; C++ only.
// The particle arithmetic (shape functions, forces, gathers) is that of update_step.cpp.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "grid.hpp"
#include "update_step.hpp"
#include "update_step_detail.hpp"

namespace mpm3d {
namespace {

// Cell index -> base node index of the window.
inline int base_node_of_cell(const StepContext* c, int cell) {
  const int i = cell % c->nc[0];
  const int r = cell / c->nc[0];
  const int j = r % c->nc[1];
  const int k = r / c->nc[1];
  return i + c->nn[0] * (j + c->nn[1] * k);
}

// Boundary conditions of the box faces (as apply_bc in update_step.cpp).
void apply_bc_faces(const StepContext* c, double* a) {
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

inline double* copy_of(const StepContext* c, int t) {
  return c->tgrid + size_t(t) * size_t(c->nnode) * kNodeFields;
}

inline int thread_id() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}
inline int thread_count() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

// Reduction of fields first..first+count-1 of the first `used` copies into the nodes.
void reduce(StepContext* c, int used, int first, int count) {
  const int nnode = c->nnode;
#pragma omp parallel for schedule(static)
  for (int n = 0; n < nnode; ++n) {
    double sum[kNodeFields] = {0, 0, 0, 0, 0, 0, 0};
    for (int t = 0; t < used; ++t) {
      const double* v = copy_of(c, t) + size_t(n) * kNodeFields + first;
      for (int f = 0; f < count; ++f) sum[f] += v[f];
    }
    for (int f = 0; f < count; ++f) {
      const int field = first + f;
      if (field == 0) c->gmass[n] = sum[f];
      else if (field <= 3) c->gmom[3 * n + field - 1] = sum[f];
      else c->gforce[3 * n + field - 4] = sum[f];
    }
  }
}

// Scatter of mass, momentum and (optionally) forces into the per-thread copies; returns
// the number of copies written.
int scatter(StepContext* c, bool with_mass_mom, bool with_forces) {
  int used = 1;
  const size_t copy_len = size_t(c->nnode) * kNodeFields;
#pragma omp parallel num_threads(c->ntgrid)
  {
    const int t = thread_id(), T = thread_count();
#pragma omp single
    used = T;
    double* g = copy_of(c, t);
    std::memset(g, 0, sizeof(double) * copy_len);
    const int p0 = int(int64_t(c->np) * t / T), p1 = int(int64_t(c->np) * (t + 1) / T);
    for (int p = p0; p < p1; ++p) {
      if (c->cell[p] < 0) continue;
      double N[8], G[24];
      shape_linear(c->lx + 3 * p, c->inv_h, N, G);
      const int base = base_node_of_cell(c, c->cell[p]);
      p2g_particle<8>(c, p, N, G, with_mass_mom, with_forces, c->has_body_force != 0,
                   [&](int k) { return g + size_t(node_of(c, base, k)) * kNodeFields; });
    }
  }
  return used;
}

}  // namespace
}  // namespace mpm3d

using namespace mpm3d;

extern "C" void mpm3d_cxx_p2g_expansion(StepContext* c) {
  const bool forces = c->scheme != SCHEME_USF;
  const int used = scatter(c, true, forces);
  reduce(c, used, 0, forces ? 7 : 4);
  apply_bc_faces(c, c->gmom);
}

extern "C" void mpm3d_cxx_forces_expansion(StepContext* c) {
  const int used = scatter(c, false, true);
  reduce(c, used, 4, 3);
}

extern "C" void mpm3d_cxx_g2p_expansion(StepContext* c) {
  const bool remap = c->scheme == SCHEME_MUSL;
  const double cutoff = c->mass_cutoff, dt = c->dt, dt_int = c->dt_int;
  const size_t copy_len = size_t(c->nnode) * kNodeFields;
  int used = 1;
#pragma omp parallel num_threads(c->ntgrid)
  {
    const int t = thread_id(), T = thread_count();
#pragma omp single
    used = T;
    double* g = copy_of(c, t);
    if (remap) std::memset(g, 0, sizeof(double) * copy_len);
    const int p0 = int(int64_t(c->np) * t / T), p1 = int(int64_t(c->np) * (t + 1) / T);
    for (int p = p0; p < p1; ++p) {
      if (c->cell[p] < 0) continue;
      double N[8], G[24];
      shape_linear(c->lx + 3 * p, c->inv_h, N, G);
      const int base = base_node_of_cell(c, c->cell[p]);
      double ax = 0.0, ay = 0.0, az = 0.0, ux = 0.0, uy = 0.0, uz = 0.0;
      for (int k = 0; k < 8; ++k) {
        const int n = node_of(c, base, k);
        const double m = c->gmass[n];
        if (!(m > cutoff)) continue;
        const double r = N[k] / m;
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
        const double mp = c->mass[p];
        for (int k = 0; k < 8; ++k) {
          double* b = g + size_t(node_of(c, base, k)) * kNodeFields;
          const double mn = mp * N[k];
          b[1] += mn * vp[0];
          b[2] += mn * vp[1];
          b[3] += mn * vp[2];
        }
      }
    }
  }
  if (remap) {
    reduce(c, used, 1, 3);
    apply_bc_faces(c, c->gmom);
  }
}
