// The stress update of constitution.cpp written once for a "lane type" T: T = double
// updates one particle, T = a GCC vector of W doubles (lanes.hpp) updates W particles of
// one material at once. Every lane performs exactly the IEEE operations of the scalar
// update in the same order (docs/DESIGN.md 5: vectorising across particles keeps the bits):
// branches that depend on the particle become selects that compute both arms, branches
// that depend on the material stay branches, and the transcendental calls (pow, log, exp)
// and the Drucker-Prager return run lane by lane through the scalar functions.
// Internal linkage throughout (see lanes.hpp): constitution_avx2.cpp compiles its own
// copy for AVX2.
#pragma once
#include <cmath>

#include "materials/constitution.hpp"
#include "core/lanes.hpp"
#include "materials/material.hpp"

namespace mpm3d {

// Scalar helpers of constitution.cpp that the lanes call one lane at a time.
double dp_return(const MaterialParams& m, double s[6], double* sm, double K, double G);
void eos_coefficients(const MaterialParams& m, double mu, double* a, double* b);
void yield_stress(const MaterialParams& m, double epeff, double strain_rate, double temp,
                  double* sy, double* ep);

namespace {  // internal linkage, see above

// The operations of the update, generic in the lane type T with lane traits TL.
template <class T, class TL>
struct LaneUpdate {
  // sigma : de with the shear terms counted twice, in a fixed order.
  static T double_dot(const T* s, const T* d) {
    return ((s[0] * d[0] + s[1] * d[1]) + s[2] * d[2]) +
           2.0 * ((s[3] * d[3] + s[4] * d[4]) + s[5] * d[5]);
  }

  static void jaumann_rotate(T sig[6], const T dw[3]) {
    const T sxx = sig[0], syy = sig[1], szz = sig[2];
    const T syz = sig[3], sxz = sig[4], sxy = sig[5];
    const T wyz = dw[0], wxz = dw[1], wxy = dw[2];
    sig[0] = sxx + 2.0 * (wxy * sxy + wxz * sxz);
    sig[1] = syy + 2.0 * (wyz * syz - wxy * sxy);
    sig[2] = szz - 2.0 * (wxz * sxz + wyz * syz);
    sig[3] = syz + (wyz * (szz - syy) - (wxy * sxz + wxz * sxy));
    sig[4] = sxz + (wxz * (szz - sxx) + (wxy * syz - wyz * sxy));
    sig[5] = sxy + (wxy * (syy - sxx) + (wxz * syz + wyz * sxz));
  }

  // q = rho l (q1 l d^2 - q2 c d) for d < 0, else 0.
  static T bulk_viscosity(T rho, double len, double c, T rate, double q1, double q2) {
    const T q = (rho * len) * ((q1 * len) * (rate * rate) - (q2 * c) * rate);
    return TL::select(rate < 0.0, q, TL::splat(0.0));
  }

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
      // C1 mu, b = 0.
      const double c1 = m.rho0 * (c[0] * c[0]);
      const double c2 = c1 * (2.0 * c[1] - 1.0);
      const double c3 = (c1 * (c[1] - 1.0)) * (3.0 * c[1] - 1.0);
      const T mu2 = mu * mu;
      const T hug = ((c1 * mu) + c2 * mu2) + c3 * (mu2 * mu);
      const T compressed = hug * (1.0 - ((0.5 * c[2]) * mu) / (1.0 + mu));
      *a = TL::select(mu > 0.0, compressed, c1 * mu);
      *b = TL::select(mu > 0.0, TL::splat(c[2]), TL::splat(0.0));
    }
  }

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

  // Drucker-Prager, one lane at a time (its returns branch in four ways).
  static T dp_return(const MaterialParams& m, T s[6], T& sm, double K, double G) {
    T deps;
    for (int i = 0; i < TL::W; ++i) {
      double si[6], smi = TL::get(sm, i);
      for (int c = 0; c < 6; ++c) si[c] = TL::get(s[c], i);
      TL::set(deps, i, mpm3d::dp_return(m, si, &smi, K, G));
      for (int c = 0; c < 6; ++c) TL::set(s[c], i, si[c]);
      TL::set(sm, i, smi);
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

  // det(I + A) of a 3x3 increment A (row-major), by the cofactors of the first row.
  static T det_identity_plus(const T A[9]) {
    const T a0 = 1.0 + A[0], a4 = 1.0 + A[4], a8 = 1.0 + A[8];
    return (a0 * (a4 * a8 - A[5] * A[7]) - A[1] * (A[3] * a8 - A[5] * A[6])) + A[2] * (A[3] * A[7] - a4 * A[6]);
  }

  // Compressible neo-Hookean (neoh): H = F - I advanced by the increment dL = L dt as
  // F_new = (I + dL) F, i.e. H_new = H + (dL + dL H); then, with J = det F and
  // B - I = H + H^T + H H^T (kept in H so that small strains lose no digits),
  // sigma = (G (B - I) + lambda ln J I) / J. No Jaumann rotation: the stress is a function
  // of F. Internal energy by the trapezoid of the old and new stress on de, as the
  // hypoelastic path. With bulk viscosity (has_q; the current version has it on by
  // default), as the current version applies it to neoh: q (bulk_viscosity at the new
  // density) where the new mean stress is compressive, kept in qv and carried by the stored
  // stress (sigma - q I), its work q tr(de) in the energy; the old stress enters the
  // trapezoid without its q.
  static void neo_hookean(const MaterialParams& m, const T dL[9], const T de[6], T H[9], T vol_old, T vol_new,
                          T sig[6], T& ie, bool has_q, T& qv, T mass, double dt, double q1, double q2,
                          double qlen) {
    T hn[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        hn[3 * i + j] = H[3 * i + j] +
                        (dL[3 * i + j] + ((dL[3 * i] * H[j] + dL[3 * i + 1] * H[3 + j]) + dL[3 * i + 2] * H[6 + j]));
    for (int r = 0; r < 9; ++r) H[r] = hn[r];
    const T J = det_identity_plus(H);
    T ln_j;
    for (int i = 0; i < TL::W; ++i) TL::set(ln_j, i, std::log(TL::get(J, i)));
    T bm[6];  // (B - I) in Voigt order xx yy zz yz xz xy
    const int ra[6] = {0, 1, 2, 1, 0, 0}, rb[6] = {0, 1, 2, 2, 2, 1};
    for (int c = 0; c < 6; ++c) {
      const int a = ra[c], b = rb[c];
      bm[c] = (H[3 * a + b] + H[3 * b + a]) +
              ((H[3 * a] * H[3 * b] + H[3 * a + 1] * H[3 * b + 1]) + H[3 * a + 2] * H[3 * b + 2]);
    }
    const T inv_j = 1.0 / J;
    const T lam_ln = m.lambda * ln_j;
    T sig_old[6];
    for (int c = 0; c < 6; ++c) sig_old[c] = sig[c];
    if (has_q)
      for (int c = 0; c < 3; ++c) sig_old[c] = sig_old[c] + qv;
    for (int c = 0; c < 3; ++c) sig[c] = inv_j * (m.shear * bm[c] + lam_ln);
    for (int c = 3; c < 6; ++c) sig[c] = inv_j * (m.shear * bm[c]);
    const T vavg = 0.5 * (vol_old + vol_new);
    T work = double_dot(sig_old, de) + double_dot(sig, de);
    if (has_q) {
      const T dkk = (de[0] + de[1]) + de[2];
      const T mean = ((sig[0] + sig[1]) + sig[2]) / 3.0;
      const T q = bulk_viscosity(mass / vol_new, qlen, m.wave_speed, dkk / dt, q1, q2);
      qv = TL::select(mean < 0.0, q, TL::splat(0.0));
      work = work - 2.0 * (qv * dkk);
      for (int c = 0; c < 3; ++c) sig[c] = sig[c] - qv;
    }
    ie = ie + (0.5 * work) * vavg;
  }

  // Compressible neo-Hookean in total Lagrangian form (TLmp): H = F - I advanced by the
  // reference increment dF = L0 dt; with J = det F and F^-T = cof(F) / J, the first
  // Piola-Kirchhoff stress P = G (F - F^-T) + lambda ln J F^-T, kept as V0 P (pk), the
  // Cauchy stress sigma = P F^T / J, the volume V0 J, and the internal energy by the
  // trapezoid of the old and new V0 P on dF.
  static void neo_hookean_tl(const MaterialParams& m, const T dF[9], T H[9], T mass, T pk[9], T sig[6], T& vol,
                             T& ie) {
    for (int r = 0; r < 9; ++r) H[r] = H[r] + dF[r];
    T f[9];
    for (int r = 0; r < 9; ++r) f[r] = (r % 4 == 0) ? 1.0 + H[r] : H[r];
    const T J = det_identity_plus(H);
    const T cof[9] = {f[4] * f[8] - f[5] * f[7], f[5] * f[6] - f[3] * f[8], f[3] * f[7] - f[4] * f[6],
                      f[2] * f[7] - f[1] * f[8], f[0] * f[8] - f[2] * f[6], f[1] * f[6] - f[0] * f[7],
                      f[1] * f[5] - f[2] * f[4], f[2] * f[3] - f[0] * f[5], f[0] * f[4] - f[1] * f[3]};
    const T inv_j = 1.0 / J;
    T ln_j;
    for (int i = 0; i < TL::W; ++i) TL::set(ln_j, i, std::log(TL::get(J, i)));
    const T lam_ln = m.lambda * ln_j;
    const T v0 = mass / m.rho0;
    T p[9];
    for (int r = 0; r < 9; ++r) {
      const T fit = cof[r] * inv_j;
      p[r] = m.shear * (f[r] - fit) + lam_ln * fit;
    }
    const int ra[6] = {0, 1, 2, 1, 0, 0}, rb[6] = {0, 1, 2, 2, 2, 1};
    for (int c = 0; c < 6; ++c) {
      const int a = ra[c], b = rb[c];
      sig[c] = inv_j * ((p[3 * a] * f[3 * b] + p[3 * a + 1] * f[3 * b + 1]) + p[3 * a + 2] * f[3 * b + 2]);
    }
    T work_old = TL::splat(0.0), work_new = TL::splat(0.0);
    for (int r = 0; r < 9; ++r) {
      const T pn = v0 * p[r];
      work_old = work_old + pk[r] * dF[r];
      work_new = work_new + pn * dF[r];
      pk[r] = pn;
    }
    ie = ie + 0.5 * (work_old + work_new);
    vol = v0 * J;
  }

  // The whole update (contract of stress_update in constitution.hpp). temp and q are
  // read and written only when has_temp / has_q.
  static void update(const MaterialParams& m, const T de[6], const T dw[3], double dt, T mass,
                     T vol_old, T vol_new, T sig[6], T& epeff, T& ie, T& temp, bool has_temp,
                     T& qv, bool has_q, T burn, double q1, double q2, double qlen) {
    jaumann_rotate(sig, dw);
    T sig_r[6];
    for (int c = 0; c < 6; ++c) sig_r[c] = sig[c];

    const T dkk = (de[0] + de[1]) + de[2];
    const T third = dkk / 3.0;
    const T dev[6] = {de[0] - third, de[1] - third, de[2] - third, de[3], de[4], de[5]};
    const double two_g = 2.0 * m.shear;
    const T vavg = 0.5 * (vol_old + vol_new);
    // Equivalent deviatoric strain rate, formed only when the Johnson-Cook rate term is on.
    const T strain_rate = m.jc_c != 0.0 ? TL::sqrt((2.0 / 3.0) * double_dot(dev, dev)) / dt
                                        : TL::splat(0.0);
    const T temp_in = has_temp ? temp : TL::splat(0.0);
    // Bulk viscosity: the stored stress carries the last q in its pressure; q_old is taken
    // out before the (incremental) elastic update, q_new put in after.
    T q_old = TL::splat(0.0), q_new = TL::splat(0.0);
    if (has_q) {
      q_old = qv;
      q_new = bulk_viscosity(mass / vol_new, qlen, m.wave_speed, dkk / dt, q1, q2);
      qv = q_new;
    }

    const T mean_r = ((sig_r[0] + sig_r[1]) + sig_r[2]) / 3.0;
    T s[6];
    if (m.eos_type == EOS_NONE) {
      // Hypoelastic trial stress, then the return of its deviator (J2) or of the whole
      // stress (Drucker-Prager).
      const T lam_dkk = m.lambda * dkk;
      for (int c = 0; c < 3; ++c) {
        const T base = has_q ? sig_r[c] + q_old : sig_r[c];
        sig[c] = base + (lam_dkk + two_g * de[c]);
      }
      for (int c = 3; c < 6; ++c) sig[c] = sig_r[c] + two_g * de[c];
      T mean = ((sig[0] + sig[1]) + sig[2]) / 3.0;
      for (int c = 0; c < 3; ++c) s[c] = sig[c] - mean;
      for (int c = 3; c < 6; ++c) s[c] = sig[c];
      T deps;
      if (m.type == MAT_DPM) {
        deps = dp_return(m, s, mean, m.lambda + two_g / 3.0, m.shear);
        epeff = epeff + deps;
      } else {
        deps = radial_return(m, s, epeff, strain_rate, temp_in);
      }
      T p_new = -mean;
      if (m.fail_strain > 0.0) {
        const auto failed = epeff >= m.fail_strain;
        for (int c = 0; c < 6; ++c) s[c] = TL::select(failed, TL::splat(0.0), s[c]);
        p_new = TL::select(failed & (p_new < 0.0), TL::splat(0.0), p_new);
      }
      const T p_tot = has_q ? p_new + q_new : p_new;
      for (int c = 0; c < 3; ++c) sig[c] = s[c] - p_tot;
      for (int c = 3; c < 6; ++c) sig[c] = s[c];
      ie = ie + (0.5 * (double_dot(sig_r, de) + double_dot(sig, de))) * vavg;
      if (has_temp) adiabatic_heating(m, s, deps, mass, vol_new, temp);
      return;
    }

    // Deviatoric update plus an equation of state for the pressure. hiex and null carry
    // no deviatoric stress.
    T s_r[6];
    for (int c = 0; c < 3; ++c) s_r[c] = sig_r[c] - mean_r;
    for (int c = 3; c < 6; ++c) s_r[c] = sig_r[c];
    T deps = TL::splat(0.0);
    const bool fluid = m.type == MAT_HIEX || m.type == MAT_NULL;
    if (fluid && m.viscosity > 0.0) {
      // The current version's null: the viscous deviator 2 mu dev(D), D = de / dt.
      const double two_mu = (2.0 * m.viscosity) / dt;
      for (int c = 0; c < 6; ++c) s[c] = two_mu * dev[c];
    } else if (fluid) {
      for (int c = 0; c < 6; ++c) s[c] = TL::splat(0.0);
    } else {
      for (int c = 0; c < 6; ++c) s[c] = s_r[c] + two_g * dev[c];
      deps = radial_return(m, s, epeff, strain_rate, temp_in);
    }
    const bool can_fail = m.fail_strain > 0.0;
    const auto failed = epeff >= m.fail_strain;  // used only when can_fail
    if (can_fail)
      for (int c = 0; c < 6; ++c) s[c] = TL::select(failed, TL::splat(0.0), s[c]);

    // Internal energy per unit initial volume, energy equation solved with the new
    // pressure (the EOS is linear in e): e1 = e* - (p1 + q1) dv / 2, p1 = F (a + b e1),
    // where e* holds the deviatoric work and the old pressure's (p0 + q0) half of the pdV
    // work.
    const T vol0 = mass / m.rho0;
    const T dv = (vol_new - vol_old) / vol0;
    const T p_old = -mean_r;
    const T dwork = (0.5 * (double_dot(s_r, de) + double_dot(s, de))) * vavg;
    T e_star = (ie + dwork) / vol0 - (0.5 * p_old) * dv;
    if (has_q) e_star = e_star - (0.5 * q_new) * dv;
    const T mu = vol0 / vol_new - 1.0;
    T a, b;
    eos_coefficients(m, mu, &a, &b);
    if (m.type == MAT_HIEX) {
      a = burn * a;
      b = burn * b;
    }
    T p_new = (a + b * e_star) / (1.0 + (0.5 * b) * dv);
    if (can_fail) p_new = TL::select(failed & (p_new < 0.0), TL::splat(0.0), p_new);
    const T e_new = e_star - (0.5 * p_new) * dv;
    ie = e_new * vol0;
    const T p_tot = has_q ? p_new + q_new : p_new;
    for (int c = 0; c < 3; ++c) sig[c] = s[c] - p_tot;
    for (int c = 3; c < 6; ++c) sig[c] = s[c];
    if (has_temp) adiabatic_heating(m, s, deps, mass, vol_new, temp);
  }
};

// The stress stage's update of the particles of a StressBlock (constitution.hpp) from
// their velocity gradients: TL::W lanes starting at lane `first`.
template <class TL>
void stress_block_lanes(const MaterialParams& m, StressBlock& b, int first, const StressBlockArgs& a) {
  typedef decltype(TL::splat(0.0)) T;
  typedef LaneUpdate<T, TL> U;
  const double dt = a.dt;
  T L[9];
  for (int r = 0; r < 9; ++r) L[r] = TL::load(b.L[r] + first);
  const T de[6] = {L[0] * dt, L[4] * dt, L[8] * dt, (0.5 * (L[5] + L[7])) * dt,
                   (0.5 * (L[2] + L[6])) * dt, (0.5 * (L[1] + L[3])) * dt};
  const T dw[3] = {(0.5 * (L[5] - L[7])) * dt, (0.5 * (L[2] - L[6])) * dt,
                   (0.5 * (L[1] - L[3])) * dt};
  const T vol_old = TL::load(b.vol + first);
  if (a.tl) {  // TLmp (neoh only, checked by the deck reader)
    T H[9], pk[9], dF[9], sig[6], vol, ie = TL::load(b.ie + first);
    for (int r = 0; r < 9; ++r) {
      H[r] = TL::load(b.H[r] + first);
      pk[r] = TL::load(b.pk1[r] + first);
      dF[r] = L[r] * dt;
    }
    U::neo_hookean_tl(m, dF, H, TL::load(b.mass + first), pk, sig, vol, ie);
    TL::store(b.vol + first, vol);
    for (int c = 0; c < 6; ++c) TL::store(b.sig[c] + first, sig[c]);
    for (int r = 0; r < 9; ++r) {
      TL::store(b.H[r] + first, H[r]);
      TL::store(b.pk1[r] + first, pk[r]);
    }
    TL::store(b.ie + first, ie);
    (void)vol_old;
    return;
  }
  const bool from_det = a.uvf || m.type == MAT_NEOH;
  T dL[9];
  if (from_det)
    for (int r = 0; r < 9; ++r) dL[r] = L[r] * dt;
  const T vol_new = from_det ? vol_old * U::det_identity_plus(dL) : vol_old * (1.0 + ((de[0] + de[1]) + de[2]));
  T sig[6];
  for (int c = 0; c < 6; ++c) sig[c] = TL::load(b.sig[c] + first);
  if (m.type == MAT_NEOH) {
    T H[9], ie = TL::load(b.ie + first), qv = TL::load(b.qv + first);
    for (int r = 0; r < 9; ++r) H[r] = TL::load(b.H[r] + first);
    U::neo_hookean(m, dL, de, H, vol_old, vol_new, sig, ie, a.has_q, qv, TL::load(b.mass + first), dt, a.q1, a.q2,
                   a.qlen);
    TL::store(b.vol + first, vol_new);
    for (int c = 0; c < 6; ++c) TL::store(b.sig[c] + first, sig[c]);
    for (int r = 0; r < 9; ++r) TL::store(b.H[r] + first, H[r]);
    TL::store(b.ie + first, ie);
    TL::store(b.qv + first, qv);
    return;
  }
  T epeff = TL::load(b.epeff + first), ie = TL::load(b.ie + first);
  T temp = TL::load(b.temp + first), qv = TL::load(b.qv + first);
  U::update(m, de, dw, dt, TL::load(b.mass + first), vol_old, vol_new, sig, epeff, ie, temp,
            a.has_temp, qv, a.has_q, TL::load(b.burn + first), a.q1, a.q2, a.qlen);
  TL::store(b.vol + first, vol_new);
  for (int c = 0; c < 6; ++c) TL::store(b.sig[c] + first, sig[c]);
  TL::store(b.epeff + first, epeff);
  TL::store(b.ie + first, ie);
  TL::store(b.temp + first, temp);
  TL::store(b.qv + first, qv);
}

}  // namespace
}  // namespace mpm3d
