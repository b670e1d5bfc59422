// ParticleData: particles as one array per field (structure of arrays), shared in
// layout with Fortran: vectors x(3,np) at x[c + 3*p], stress sig(6,np) in Voigt order
// xx yy zz yz xz xy, scalars (np). Optional fields stay empty when no scene needs them.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace mpm3d {

struct Body {
  int first = 0;      // deck number of the first particle (0-based): the deck numbers
  int count = 0;      // first .. first + count - 1 (not the storage order, Particles::id)
  int component = 1;  // contact component (1-based, as in the deck)
  double spacing = 0.0;  // particle spacing dp of bloc/sphe/cyli cards; 0 for poin
  double gravity[3] = {0.0, 0.0, 0.0};
};

struct Particles {
  int np = 0;
  std::vector<double> x, v, sig;           // (3,np) (3,np) (6,np)
  std::vector<double> mass, vol, epeff, ie;  // (np)
  std::vector<int32_t> mat, body;          // 0-based material and body index
  std::vector<double> temp;                // (np) only with thermal Johnson-Cook
  std::vector<double> fext;                // (3,np) only with point/body loads
  std::vector<double> tlight;              // (np) only with hiex: lighting time
  std::vector<double> qv;                  // (np) only with 'bulk': bulk viscosity pressure
  std::vector<double> psize;               // (np) GIMP particle half-size lp, only with gimp
  std::vector<double> defgrad;             // (9,np) F - I (row-major), only with neoh
  std::vector<double> x0;                  // (3,np) initial position: disx/disy/disz, TLmp
  std::vector<double> pk1;                 // (9,np) V0 P, first Piola-Kirchhoff stress, TLmp only
  std::vector<int32_t> id;                 // (np) deck number (0-based) of each stored
                                           // particle; empty: stored in deck order

  void resize(int n);
  double density(int p) const { return mass[p] / vol[p]; }
  int deck_number(int p) const { return id.empty() ? p : id[size_t(p)]; }  // 0-based
};

// Storage order of the solver (Simulation, mpm3d_ref): the particles sorted by the block of
// block_cells^3 cells of the deck's lattice (origin lo, cell h, nc cells per axis) that
// holds them, blocks in patch order (x fastest, z slowest), deck order within a block. The
// patch stages give each thread a run of consecutive patches, which is then a run of
// consecutive particles: deck order (z fastest in a cylinder or block) gave every thread
// particles in every cache line at each column's cut, and at two threads each thread ran
// 1.6x slower than one thread alone (docs/PERFORMANCE.md). The sort key is
// block * np + deck number, unique, so any sort gives the same order; P.id records it.
// Every array of particle_fields() is permuted. Outputs are written in deck order
// (stored_index).
enum class ParticleOrder { blocks, deck };
void order_by_blocks(Particles& P, const double lo[3], double h, const int nc[3], int block_cells);
// Stored index of each deck particle (the inverse of id; the identity when id is empty).
std::vector<int> stored_index(const Particles& P);

// Row i of dst (ncomp values) = row from(i) of src, for rows 0..n-1: every move of a
// per-particle array between the storage order and the deck order (the set-up sort, the
// outputs, the C API's arrays).
template <class T, class From>
void gather_rows(const T* src, int ncomp, int n, From&& from, T* dst) {
  for (int i = 0; i < n; ++i) {
    const size_t s = size_t(ncomp) * size_t(from(i)), d = size_t(ncomp) * size_t(i);
    for (int c = 0; c < ncomp; ++c) dst[d + size_t(c)] = src[s + size_t(c)];
  }
}

// Every array of Particles by name, for generic code (the checkpoint stores and restores
// each allocated one). Exactly one of d, i is set; ncomp values per particle. A new array
// in Particles must be listed in particle_fields() (cxx/core/particle.cpp); cxx/solver/checkpoint.cpp
// checks sizeof(Particles) so a forgotten one stops the build.
struct ParticleField {
  const char* name;
  int ncomp;
  std::vector<double>* d;
  std::vector<int32_t>* i;
};
std::vector<ParticleField> particle_fields(Particles& P);
constexpr int kParticleArrays = 18;  // arrays listed by particle_fields

// Physical sums over all particles (deterministic, see update_step).
struct Energies {
  double kinetic = 0.0, internal = 0.0;
  double momentum[3] = {0.0, 0.0, 0.0};
};

}  // namespace mpm3d
