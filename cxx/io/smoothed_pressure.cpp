// The current MPM3D-F90's 'smoo': the particle pressure smoothed through the grid, an output
// (the current program writes it as Smoothpressure and does not feed it back into the
// stress). The pressure -sm of each particle, weighted by its volume, goes to the nodes
// with the run's shape functions (trilinear, GIMP or B-spline, on the deck's lattice):
//   p_i = sum_p N_ip p_p V_p / sum_p N_ip V_p,
// and comes back as spre_p = sum_i N_ip p_i. Computed only when written (output variable
// spre, which 'smoo' adds to the animation variables), from the state of that moment.
#include <cmath>

#include "io/data_out.hpp"
#include "core/grid.hpp"

namespace mpm3d {

namespace {

// Calls visit(node, N) for the nodes of particle p's stencil on the deck's lattice of
// nc cells per axis (nothing when p lies outside the box).
template <class Visit>
void for_stencil(const Model& m, const int nc[3], int p, Visit&& visit) {
  const Particles& P = m.particles;
  const double h = m.dcell, inv_h = 1.0 / h;
  const int nn0 = nc[0] + 1, nn1 = nc[1] + 1;
  double lx[3];
  int ci[3];
  for (int a = 0; a < 3; ++a) {
    const double s = (P.x[3 * size_t(p) + size_t(a)] - m.box_lo[a]) * inv_h;
    if (!(s >= 0.0) || !(s < double(nc[a]))) return;
    ci[a] = int(std::floor(s));
    lx[a] = s - double(ci[a]);
  }
  if (m.shape() != 0) {
    int o[3];
    double N[27], G[81];
    stencil_27(m.shape(), ci, lx, nc, m.gimp ? P.psize[size_t(p)] * inv_h : 0.0, inv_h, o, N, G);
    for (int k = 0; k < 27; ++k) {
      const int i = ci[0] + o[0] + k % 3, j = ci[1] + o[1] + (k / 3) % 3, l = ci[2] + o[2] + k / 9;
      visit(size_t(i) + size_t(nn0) * (size_t(j) + size_t(nn1) * size_t(l)), N[k]);
    }
  } else {
    double N[8], G[24];
    shape_linear(lx, inv_h, N, G);
    for (int k = 0; k < 8; ++k) {
      const int i = ci[0] + (k & 1), j = ci[1] + ((k >> 1) & 1), l = ci[2] + ((k >> 2) & 1);
      visit(size_t(i) + size_t(nn0) * (size_t(j) + size_t(nn1) * size_t(l)), N[k]);
    }
  }
}

}  // namespace

void update_smoothed_pressure(const Model& m) {
  const Particles& P = m.particles;
  int nc[3];
  for (int a = 0; a < 3; ++a) nc[a] = int(std::floor((m.box_hi[a] - m.box_lo[a]) / m.dcell + 0.5));
  const size_t nnode = size_t(nc[0] + 1) * size_t(nc[1] + 1) * size_t(nc[2] + 1);
  std::vector<double> pv(nnode, 0.0), vol(nnode, 0.0);
  for (int p = 0; p < P.np; ++p) {
    const double* s = &P.sig[6 * size_t(p)];
    const double pres = -((s[0] + s[1]) + s[2]) / 3.0, v = P.vol[size_t(p)];
    for_stencil(m, nc, p, [&](size_t n, double N) {
      pv[n] += N * pres * v;
      vol[n] += N * v;
    });
  }
  for (size_t n = 0; n < nnode; ++n)
    if (vol[n] > 0.0) pv[n] /= vol[n];
  m.spre.assign(size_t(P.np), 0.0);
  for (int p = 0; p < P.np; ++p)
    for_stencil(m, nc, p, [&](size_t n, double N) { m.spre[size_t(p)] += N * pv[n]; });
}

}  // namespace mpm3d
