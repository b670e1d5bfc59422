#include "core/particle.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mpm3d {

void Particles::resize(int n) {
  np = n;
  x.assign(3 * size_t(n), 0.0);
  v.assign(3 * size_t(n), 0.0);
  sig.assign(6 * size_t(n), 0.0);
  mass.assign(n, 0.0);
  vol.assign(n, 0.0);
  epeff.assign(n, 0.0);
  ie.assign(n, 0.0);
  mat.assign(n, 0);
  body.assign(n, 0);
}

std::vector<ParticleField> particle_fields(Particles& P) {
  return {{"position", 3, &P.x, nullptr},
          {"velocity", 3, &P.v, nullptr},
          {"stress", 6, &P.sig, nullptr},
          {"mass", 1, &P.mass, nullptr},
          {"volume", 1, &P.vol, nullptr},
          {"epeff", 1, &P.epeff, nullptr},
          {"internal_energy", 1, &P.ie, nullptr},
          {"material", 1, nullptr, &P.mat},
          {"body", 1, nullptr, &P.body},
          {"temperature", 1, &P.temp, nullptr},
          {"external_force", 3, &P.fext, nullptr},
          {"lighting_time", 1, &P.tlight, nullptr},
          {"bulk_viscosity", 1, &P.qv, nullptr},
          {"gimp_half_size", 1, &P.psize, nullptr},
          {"deformation_gradient", 9, &P.defgrad, nullptr},
          {"initial_position", 3, &P.x0, nullptr},
          {"first_piola_kirchhoff", 9, &P.pk1, nullptr},
          {"deck_id", 1, nullptr, &P.id}};
}

namespace {
template <class T>
void permute(std::vector<T>& a, int ncomp, const std::vector<int>& from) {
  if (a.empty()) return;
  std::vector<T> t(a.size());
  gather_rows(a.data(), ncomp, int(from.size()), [&](int p) { return from[size_t(p)]; }, t.data());
  a.swap(t);
}
}  // namespace

void order_by_blocks(Particles& P, const double lo[3], double h, const int nc[3], int block_cells) {
  const int np = P.np;
  if (P.id.empty()) {
    P.id.resize(size_t(np));
    std::iota(P.id.begin(), P.id.end(), 0);
  }
  long nb[3];
  for (int a = 0; a < 3; ++a) nb[a] = (std::max(nc[a], 1) - 1) / block_cells + 1;
  std::vector<int64_t> key(static_cast<size_t>(np));
  for (int p = 0; p < np; ++p) {
    long b[3];
    for (int a = 0; a < 3; ++a) {
      // The cell as the bin stage finds it, clamped into the lattice (NaN: cell 0).
      const double t = (P.x[3 * size_t(p) + a] - lo[a]) / h;
      const long i = t >= 0.0 ? (t < double(nc[a]) ? long(t) : long(nc[a]) - 1) : 0;
      b[a] = i / block_cells;
    }
    key[size_t(p)] = int64_t(b[0] + nb[0] * (b[1] + nb[1] * b[2])) * int64_t(np) + p;
  }
  std::sort(key.begin(), key.end());
  std::vector<int> from(static_cast<size_t>(np));
  for (int p = 0; p < np; ++p) from[size_t(p)] = int(key[size_t(p)] % np);
  for (const ParticleField& f : particle_fields(P)) {
    if (f.d) permute(*f.d, f.ncomp, from);
    if (f.i) permute(*f.i, f.ncomp, from);
  }
}

std::vector<int> stored_index(const Particles& P) {
  std::vector<int> at(static_cast<size_t>(P.np));
  for (int p = 0; p < P.np; ++p) at[size_t(P.deck_number(p))] = p;
  return at;
}

}  // namespace mpm3d
