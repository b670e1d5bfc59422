// The equations of state in the form p = a + b e (e: internal energy per initial volume):
// the linear polynomial, the current version's weakly compressible, JWL and Mie-Gruneisen,
// written once for a lane type T (constitution_lanes.hpp). JWL needs exp: it calls the
// scalar eos_coefficients (constitution.cpp) lane by lane. Internal linkage (lanes.hpp).
#pragma once
#include "core/lanes.hpp"
#include "materials/constitution.hpp"
#include "materials/material.hpp"

namespace mpm3d {
namespace {  // internal linkage, see lanes.hpp

template <class T, class TL>
struct EosLanes {
  static void eos_coefficients(const MaterialParams& m, T mu, T* a, T* b) {
    const double* c = m.eos;
    if (m.eos_type == EOS_LINEAR) {
      const T mu2 = TL::select(mu > 0.0, mu * mu, TL::splat(0.0));
      *a = ((c[0] + c[1] * mu) + c[2] * mu2) + c[3] * (mu * mu * mu);
      *b = (c[4] + c[5] * mu) + c[6] * mu2;
    } else if (m.eos_type == EOS_WEAK) {
      // p = c0^2 (rho - rho0) = rho0 c0^2 mu, independent of e.
      *a = (m.rho0 * (c[0] * c[0])) * mu;
      *b = TL::splat(0.0);
    } else if (m.eos_type == EOS_JWL) {
      for (int i = 0; i < TL::W; ++i) {
        double ai, bi;
        mpm3d::eos_coefficients(m, TL::get(mu, i), &ai, &bi);
        TL::set(*a, i, ai);
        TL::set(*b, i, bi);
      }
    } else {
      // Mie-Gruneisen, the book's form (section 5.3.5): in compression the cubic Hugoniot
      // C1 mu + C2 mu^2 + C3 mu^3 times (1 - g0 mu / (2 (1 + mu))), b = g0; in tension
      // C1 mu, b = 0. m.eos_k1, where set, replaces C1 in the linear term alone (rule null_eos).
      const double c1 = m.rho0 * (c[0] * c[0]);
      const double c2 = c1 * (2.0 * c[1] - 1.0);
      const double c3 = (c1 * (c[1] - 1.0)) * (3.0 * c[1] - 1.0);
      const double k1 = m.eos_k1 != 0.0 ? m.eos_k1 : c1;
      const T mu2 = mu * mu;
      const T hug = ((k1 * mu) + c2 * mu2) + c3 * (mu2 * mu);
      const T compressed = hug * (1.0 - ((0.5 * c[2]) * mu) / (1.0 + mu));
      *a = TL::select(mu > 0.0, compressed, k1 * mu);
      *b = TL::select(mu > 0.0, TL::splat(c[2]), TL::splat(0.0));
    }
  }
};

}  // namespace
}  // namespace mpm3d
