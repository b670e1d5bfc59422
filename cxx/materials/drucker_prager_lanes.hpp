// Drucker-Prager (dpm), written for a lane type T (constitution_lanes.hpp): the return of
// dp_return (constitution.cpp, where the formulas and their branches are explained) with
// its four branches (elastic, shear, tension cut-off, apex) as selects that compute every
// arm, so W particles return at once with the scalar function's bits; and the original
// programs' return (rule dp_return=original). Internal linkage (lanes.hpp).
#pragma once
#include <cmath>

#include "core/lanes.hpp"
#include "materials/constitution.hpp"
#include "materials/material.hpp"

namespace mpm3d {
namespace {  // internal linkage, see lanes.hpp

template <class T, class TL>
struct DruckerPragerLanes {
  // tau = sqrt(J2) of the deviator s (Voigt), which both returns start from.
  static T shear_stress(const T s[6]) {
    return TL::sqrt(0.5 * ((s[0] * s[0] + s[1] * s[1]) + s[2] * s[2]) + ((s[3] * s[3] + s[4] * s[4]) + s[5] * s[5]));
  }

  // dp_return lane by lane: s (deviator) and sm (mean stress) returned in place; the
  // equivalent plastic strain increment returned. The operations of each arm are the
  // scalar function's, in its order; a lane takes the arm the scalar branches would.
  static T dp_return(const MaterialParams& m, T s[6], T& sm, double K, double G) {
    const T zero = TL::splat(0.0);
    const T tau = shear_stress(s);
    const double qphi = m.dp_qphi, kphi = m.dp_kphi, qpsi = m.dp_qpsi, sigt = m.dp_tension;
    const T fs = (tau + qphi * sm) - kphi;
    const T ft = sm - sigt;
    const auto yields = (fs > 0.0) | (ft > 0.0);
    const double tau_p = kphi - qphi * sigt;
    const double alpha_p = std::sqrt(1.0 + qphi * qphi) - qphi;
    const T h = (tau - tau_p) - alpha_p * (sm - sigt);
    // Shear return, kept where it lands inside the apex and the cut-off.
    const T lam = fs / (G + (K * qphi) * qpsi);
    const T tau_s = tau - G * lam;
    const T sm_s = sm - (K * qpsi) * lam;
    const auto shear = (fs > 0.0) & (h > 0.0);
    // Tension return: onto the cut-off, at most to the corner.
    const T tau_t = TL::select(tau > tau_p, TL::splat(tau_p), tau);
    const T sm_t = TL::splat(sigt);
    const auto beyond = (tau_s < 0.0) | (sm_s > sigt);
    const T tau_new = TL::select(shear, TL::select(beyond, tau_t, tau_s), tau_t);
    const T sm_new = TL::select(shear, TL::select(beyond, sm_t, sm_s), sm_t);
    sm = TL::select(yields, sm_new, sm);
    const T ratio = tau_new / tau;
    const auto scaled = yields & (tau > 0.0);
    for (int c = 0; c < 6; ++c) s[c] = TL::select(scaled, s[c] * ratio, s[c]);
    return TL::select(yields, (tau - tau_new) / (std::sqrt(3.0) * G), zero);
  }

  // The original programs' return (rule dp_return=original; M3DM9, alike in the book and
  // the current program), with our variables and plastic strain measure. Below the cut-off
  // (sm < sigma_t) the shear return where f_s > 0; at or beyond it the shear return above
  // the corner line (h > 0), which may leave sm beyond the cut-off, else the tension
  // return sm' = sigma_t that keeps the deviator. The shear return's tau' is
  // k_phi - q_phi sm' (on the cone). The original's cut-off is 0 when q_phi = 0.
  static T dp_return_original(const MaterialParams& m, T s[6], T& sm, double K, double G) {
    const T zero = TL::splat(0.0);
    const T tau = shear_stress(s);
    const double qphi = m.dp_qphi, kphi = m.dp_kphi, qpsi = m.dp_qpsi;
    const double sigt = qphi == 0.0 ? 0.0 : m.dp_tension;
    const T fs = (tau + qphi * sm) - kphi;
    const T ft = sm - sigt;
    const double tau_p = kphi - qphi * sigt;
    const double alpha_p = std::sqrt(1.0 + qphi * qphi) - qphi;
    const T h = (tau - tau_p) - alpha_p * ft;
    const T lam = fs / (G + (K * qphi) * qpsi);
    const T sm_s = sm - (K * qpsi) * lam;
    const T tau_s = kphi - qphi * sm_s;
    const T ratio = tau_s / tau;
    const T deps_s = (tau - tau_s) / (std::sqrt(3.0) * G);
    // The original's branches: below the cut-off shear or elastic, else shear or tension.
    const auto below = ft < 0.0;
    const auto shear_below = fs > 0.0;
    const auto shear_beyond = h > 0.0;
    for (int c = 0; c < 6; ++c) {
      const T s_s = s[c] * ratio;
      s[c] = TL::select(below, TL::select(shear_below, s_s, s[c]), TL::select(shear_beyond, s_s, s[c]));
    }
    sm = TL::select(below, TL::select(shear_below, sm_s, sm), TL::select(shear_beyond, sm_s, TL::splat(sigt)));
    return TL::select(below, TL::select(shear_below, deps_s, zero), TL::select(shear_beyond, deps_s, zero));
  }
};

}  // namespace
}  // namespace mpm3d
