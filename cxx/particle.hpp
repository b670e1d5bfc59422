// ParticleData: particles as one array per field (structure of arrays), shared in
// layout with Fortran: vectors x(3,np) at x[c + 3*p], stress sig(6,np) in Voigt order
// xx yy zz yz xz xy, scalars (np). Optional fields stay empty when no scene needs them.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace mpm3d {

struct Body {
  int first = 0;      // first particle (0-based)
  int count = 0;      // particles in the body
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

  void resize(int n);
  double density(int p) const { return mass[p] / vol[p]; }
};

// Every array of Particles by name, for generic code (the checkpoint stores and restores
// each allocated one). Exactly one of d, i is set; ncomp values per particle. A new array
// in Particles must be listed in particle_fields() (cxx/particle.cpp); cxx/checkpoint.cpp
// checks sizeof(Particles) so a forgotten one stops the build.
struct ParticleField {
  const char* name;
  int ncomp;
  std::vector<double>* d;
  std::vector<int32_t>* i;
};
std::vector<ParticleField> particle_fields(Particles& P);
constexpr int kParticleArrays = 14;  // arrays listed by particle_fields

// Physical sums over all particles (deterministic, see update_step).
struct Energies {
  double kinetic = 0.0, internal = 0.0;
  double momentum[3] = {0.0, 0.0, 0.0};
};

}  // namespace mpm3d
