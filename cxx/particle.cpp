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

}  // namespace mpm3d
