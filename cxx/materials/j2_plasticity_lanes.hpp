// J2 plasticity (elas, pla1, pla2, clay and the Johnson-Cook family john, jcf, sjc, sjcf),
// written once for a lane type T (constitution_lanes.hpp): the yield stress, the radial
// return of the deviator and the adiabatic heating of the thermal Johnson-Cook materials.
// The hardening laws that need pow, log or the temperature call the scalar yield_stress
// (constitution.cpp) lane by lane. Internal linkage (lanes.hpp).
#pragma once
#include "core/lanes.hpp"
#include "materials/constitution.hpp"
#include "materials/material.hpp"

namespace mpm3d {
namespace {  // internal linkage, see lanes.hpp

template <class T, class TL>
struct J2Lanes {
  static T j2_of(const T s[6]) {
    return 0.5 * ((s[0] * s[0] + s[1] * s[1]) + s[2] * s[2]) +
           ((s[3] * s[3] + s[4] * s[4]) + s[5] * s[5]);
  }

  // Yield stress and plastic modulus (yield_stress in constitution.cpp). The hardening
  // laws without pow, log or temperature are done here, as yield_stress does them
  // (pow(e, 1) == e, factor 1); the others call it lane by lane.
  static void yield(const MaterialParams& m, T epeff, T strain_rate, T temp, T& sy, T& ep) {
    const bool jc_plain = (m.type == MAT_SJC || m.type == MAT_SJCF) && m.jc_n == 1.0 && m.jc_c == 0.0;
    if (m.type == MAT_PLA1) {
      sy = TL::splat(m.yield0);
      ep = TL::splat(0.0);
    } else if (m.type == MAT_PLA2) {
      sy = m.yield0 + m.hardening * epeff;
      ep = TL::splat(m.hardening);
    } else if (jc_plain) {
      sy = TL::select(epeff > 0.0, m.yield0 + m.hardening * epeff, TL::splat(m.yield0));
      ep = TL::splat(m.hardening);
    } else {
      for (int i = 0; i < TL::W; ++i) {
        double syi, epi;
        yield_stress(m, TL::get(epeff, i), TL::get(strain_rate, i), TL::get(temp, i), &syi, &epi);
        TL::set(sy, i, syi);
        TL::set(ep, i, epi);
      }
    }
  }

  // Radial return of the deviator s against the yield stress; updates epeff, returns
  // the plastic strain increment (0 where elastic).
  static T radial_return(const MaterialParams& m, T s[6], T& epeff, T strain_rate, T temp) {
    if (m.type == MAT_ELAS) return TL::splat(0.0);
    const T q = TL::sqrt(3.0 * j2_of(s));
    T sy, ep;
    yield(m, epeff, strain_rate, temp, sy, ep);
    const auto yielded = q > sy;
    const double g3 = 3.0 * m.shear;
    const T deps = (q - sy) / (g3 + ep);
    const T ratio = (q - g3 * deps) / q;
    for (int c = 0; c < 6; ++c) s[c] = TL::select(yielded, s[c] * ratio, s[c]);
    epeff = TL::select(yielded, epeff + deps, epeff);
    return TL::select(yielded, deps, TL::splat(0.0));
  }

  // clay's return (clay_return in constitution.cpp), lane by lane: its Newton iterations
  // run as many times as each particle needs.
  static T clay_return_lanes(const MaterialParams& m, T s[6], T& epeff, bool original) {
    T deps = TL::splat(0.0);
    for (int i = 0; i < TL::W; ++i) {
      double si[6], e = TL::get(epeff, i);
      for (int c = 0; c < 6; ++c) si[c] = TL::get(s[c], i);
      const double d = clay_return(m, si, &e, original);
      for (int c = 0; c < 6; ++c) TL::set(s[c], i, si[c]);
      TL::set(epeff, i, e);
      TL::set(deps, i, d);
    }
    return deps;
  }

  // Adiabatic heating of thermal Johnson-Cook materials (Taylor-Quinney 0.9).
  static void adiabatic_heating(const MaterialParams& m, const T s[6], T deps, T mass, T vol_new,
                                T& temp) {
    if (!(m.heat_cap > 0.0)) return;
    const T q_new = TL::sqrt(1.5 * (((s[0] * s[0] + s[1] * s[1]) + s[2] * s[2]) +
                                    2.0 * ((s[3] * s[3] + s[4] * s[4]) + s[5] * s[5])));
    const T heated = temp + (0.9 * (q_new * deps)) / ((mass / vol_new) * m.heat_cap);
    temp = TL::select(deps > 0.0, heated, temp);
  }
};

}  // namespace
}  // namespace mpm3d
