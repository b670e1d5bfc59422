#include "particle.hpp"

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
          {"gimp_half_size", 1, &P.psize, nullptr}};
}

}  // namespace mpm3d
