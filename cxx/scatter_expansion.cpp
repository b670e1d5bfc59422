// The benchmark alternative of the p2g, forces and g2p stages: the scatters into per-thread
// copies of the grid ("array expansion", the scheme the MPM3DMP paper compared with its
// patches), reduced node by node in thread order. Selected with `mpm3d --scatter expansion`.
//
// Every thread scatters a fixed contiguous range of particles (ascending index) into its
// own copy of the node fields (kNodeFields, nnode); the copies are then reduced node by
// node, in thread order: node = 0.0 + copy_0 + copy_1 + ... So results are deterministic
// for a given thread count but, unlike the patch scheme, NOT the same for different thread
// counts (the grouping of a node's sum follows the thread ranges), and at one thread they
// differ from the patch scheme by round-off only (one running sum over the particles
// instead of per-patch partial sums). C++ only. The particle arithmetic (shape functions,
// forces, gathers) is that of the patch stages (stage_common.hpp).
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "grid.hpp"
#include "stage_common.hpp"
#include "update_step.hpp"

namespace mpm3d {
namespace {

inline double* copy_of(const StepContext* c, int t) {
  return c->tgrid + size_t(t) * size_t(c->nnode) * kNodeFields;
}

// Particles [p0, p1) of thread t of T: equal runs of the particle index.
inline void thread_run(const StepContext* c, int t, int T, int& p0, int& p1) {
  p0 = int(int64_t(c->np) * t / T);
  p1 = int(int64_t(c->np) * (t + 1) / T);
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
    store_node_fields(first, count, sum, n, c->gmass, c->gmom, c->gforce);
  }
}

// Scatter of mass, momentum and (optionally) forces into the per-thread copies; returns
// the number of copies written.
int scatter(StepContext* c, bool with_mass_mom, bool with_forces) {
  int used = 1;
  const size_t copy_len = size_t(c->nnode) * kNodeFields;
  const CellDecoder dec(c);
#pragma omp parallel num_threads(c->ntgrid)
  {
    int t, T, p0, p1;
    team_position(t, T);
#pragma omp single
    used = T;
    double* g = copy_of(c, t);
    std::memset(g, 0, sizeof(double) * copy_len);
    thread_run(c, t, T, p0, p1);
    for (int p = p0; p < p1; ++p) {
      if (c->cell[p] < 0) continue;
      double N[8], G[24];
      shape_linear(c->lx + 3 * p, c->inv_h, N, G);
      const int base = base_node(c, dec, c->cell[p]);
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
  apply_bc(c, c->gmom);
}

extern "C" void mpm3d_cxx_forces_expansion(StepContext* c) {
  const int used = scatter(c, false, true);
  reduce(c, used, 4, 3);
}

extern "C" void mpm3d_cxx_g2p_expansion(StepContext* c) {
  const bool remap = c->scheme == SCHEME_MUSL;
  const size_t copy_len = size_t(c->nnode) * kNodeFields;
  const CellDecoder dec(c);
  int used = 1;
#pragma omp parallel num_threads(c->ntgrid)
  {
    int t, T, p0, p1;
    team_position(t, T);
#pragma omp single
    used = T;
    double* g = copy_of(c, t);
    if (remap) std::memset(g, 0, sizeof(double) * copy_len);
    thread_run(c, t, T, p0, p1);
    for (int p = p0; p < p1; ++p) {
      if (c->cell[p] < 0) continue;
      double N[8], G[24];
      shape_linear(c->lx + 3 * p, c->inv_h, N, G);
      const int base = base_node(c, dec, c->cell[p]);
      g2p_particle<8>(c, p, N, [&](int k) { return node_of(c, base, k); });
      if (remap) remap_particle<8>(c, p, N, [&](int k) { return g + size_t(node_of(c, base, k)) * kNodeFields; });
    }
  }
  if (remap) {
    reduce(c, used, 1, 3);
    apply_bc(c, c->gmom);
  }
}
