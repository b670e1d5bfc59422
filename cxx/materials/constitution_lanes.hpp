// The stress update of constitution.cpp written once for a "lane type" T: T = double
// updates one particle, T = a GCC vector of W doubles (lanes.hpp) updates W particles of
// one material at once. Every lane performs exactly the IEEE operations of the scalar
// update in the same order (docs/DESIGN.md 5: vectorising across particles keeps the bits):
// branches that depend on the particle become selects that compute both arms, branches
// that depend on the material stay branches, and the transcendental calls (pow, log, exp)
// run lane by lane through the scalar functions.
// This file holds the update's skeleton and the dispatch on the material; each model
// family is a header of its own, templates over T:
//   stress_ops_lanes.hpp       what all share: sigma : de, Jaumann rotation, bulk viscosity, det(I + A)
//   eos_lanes.hpp              equations of state (linear, weakly compressible, JWL, Mie-Gruneisen)
//   j2_plasticity_lanes.hpp    J2 plasticity: elas, pla1, pla2, clay, Johnson-Cook (yield, return, heating)
//   drucker_prager_lanes.hpp   dpm
//   neo_hookean_lanes.hpp      neoh, updated and total Lagrangian (TLmp)
// The fluids hiex and null are branches of the skeleton (no deviator or the viscous one,
// hiex's programmed burn on the EOS pressure); their pressure is the EOS's.
// Internal linkage throughout (see lanes.hpp): constitution_avx2.cpp compiles its own
// copy for AVX2.
#pragma once
#include <cmath>

#include "materials/constitution.hpp"
#include "core/lanes.hpp"
#include "materials/material.hpp"
#include "materials/stress_ops_lanes.hpp"
#include "materials/eos_lanes.hpp"
#include "materials/j2_plasticity_lanes.hpp"
#include "materials/drucker_prager_lanes.hpp"
#include "materials/neo_hookean_lanes.hpp"

namespace mpm3d {

namespace {  // internal linkage, see above

// The update, generic in the lane type T with lane traits TL: the steps every model takes
// and the model families' parts.
template <class T, class TL>
struct LaneUpdate {
  typedef StressOps<T, TL> Ops;
  typedef EosLanes<T, TL> Eos;
  typedef J2Lanes<T, TL> J2;
  typedef DruckerPragerLanes<T, TL> DruckerPrager;

  // The current program's bulk viscosity (rules bulk_switch=stress, bulk_linear=original).
  // It computes q only while its mean stress is compressive, at a point of the update that
  // depends on the model: the models without an EOS (elas, pla1, pla2, clay, john, dpm) test the
  // new mean stress, after the elastic update and the return; neoh the new mean stress (our
  // neo_hookean does so under either rule); those with an EOS (sjc, sjcf, jcf, hiex, null)
  // test the old mean stress, rotated, before the EOS (hiex and null unrotated: the same
  // trace). Of those with an EOS only the Mie-Gruneisen and the weakly compressible EOS
  // compute q at all: none with the linear EOS or JWL, so none on hiex. Its linear term's
  // c is a per-particle wave speed set only for elas and neoh (sqrt((lambda + 2G) / rho0)) and
  // null (sqrt(K / rho0)), zero for every other model: pla1, pla2, clay, john, dpm, sjc, sjcf and
  // jcf get the quadratic term alone.
  // bulk_q_original: whether material m gets q there, and the linear term's c (*speed).
  static bool bulk_q_original(const MaterialParams& m, double* speed) {
    const bool with_eos = m.type == MAT_SJC || m.type == MAT_SJCF || m.type == MAT_JCF || m.type == MAT_HIEX ||
                          m.type == MAT_NULL;
    const bool linear = m.type == MAT_ELAS || m.type == MAT_NEOH || m.type == MAT_NULL;
    *speed = linear ? m.wave_speed : 0.0;
    return !with_eos || m.eos_type == EOS_MIE_GRUNEISEN || m.eos_type == EOS_WEAK;
  }

  // The whole update (contract of stress_update in constitution.hpp). temp and q are
  // read and written only when has_temp / has_q.
  static void update(const MaterialParams& m, const T de[6], const T dw[3], double dt, T mass,
                     T vol_old, T& vol_new, T sig[6], T& epeff, T& ie, T& temp, bool has_temp,
                     T& qv, bool has_q, T burn, double q1, double q2, double qlen, const StepRules& rules) {
    Ops::jaumann_rotate(sig, dw);
    T sig_r[6];
    for (int c = 0; c < 6; ++c) sig_r[c] = sig[c];

    const T dkk = (de[0] + de[1]) + de[2];
    const T third = dkk / 3.0;
    const T dev[6] = {de[0] - third, de[1] - third, de[2] - third, de[3], de[4], de[5]};
    const double two_g = 2.0 * m.shear;
    const T vavg = 0.5 * (vol_old + vol_new);
    // Equivalent deviatoric strain rate, formed only when the Johnson-Cook rate term is on.
    const T strain_rate = m.jc_c != 0.0 ? TL::sqrt((2.0 / 3.0) * Ops::double_dot(dev, dev)) / dt
                                        : TL::splat(0.0);
    const T temp_in = has_temp ? temp : TL::splat(0.0);
    // Bulk viscosity: the stored stress carries the last q in its pressure; q_old is taken
    // out before the (incremental) elastic update, q_new put in after.
    bool q_on = has_q;
    double q_speed = m.wave_speed;  // the linear term's c
    if (has_q && rules.bulk_linear) q_on = bulk_q_original(m, &q_speed);
    T q_old = TL::splat(0.0), q_new = TL::splat(0.0);
    if (q_on) {
      q_old = qv;
      q_new = Ops::bulk_viscosity(mass / vol_new, qlen, q_speed, dkk / dt, q1, q2);
      qv = q_new;
    }

    const T mean_r = ((sig_r[0] + sig_r[1]) + sig_r[2]) / 3.0;
    T s[6];
    if (m.eos_type == EOS_NONE) {
      // Hypoelastic trial stress, then the return of its deviator (J2) or of the whole
      // stress (Drucker-Prager).
      const T lam_dkk = m.lambda * dkk;
      for (int c = 0; c < 3; ++c) {
        const T base = q_on ? sig_r[c] + q_old : sig_r[c];
        sig[c] = base + (lam_dkk + two_g * de[c]);
      }
      for (int c = 3; c < 6; ++c) sig[c] = sig_r[c] + two_g * de[c];
      T mean = ((sig[0] + sig[1]) + sig[2]) / 3.0;
      for (int c = 0; c < 3; ++c) s[c] = sig[c] - mean;
      for (int c = 3; c < 6; ++c) s[c] = sig[c];
      T deps;
      if (m.type == MAT_DPM) {
        if (rules.dp_return)
          deps = DruckerPrager::dp_return_original(m, s, mean, m.lambda + two_g / 3.0, m.shear);
        else {
          // Beyond the tension cut-off the particles separate: the return's volumetric
          // opening (mean stress above sigma_t over K) is space between particles, not a
          // larger particle, so the volume keeps only the rest of the increment. A particle
          // that grew by it would, compressed again, push with the dense moduli from a
          // fraction of the dense mass per volume (cohesionless columns: docs/VERIFICATION.md).
          const T mean_trial = mean;
          const double K = m.lambda + two_g / 3.0;
          deps = DruckerPrager::dp_return(m, s, mean, K, m.shear);
          const T opening = TL::select((mean == m.dp_tension) & (mean_trial > mean), (mean_trial - mean) / K,
                                       TL::splat(0.0));
          vol_new = vol_new - vol_old * opening;
        }
        epeff = epeff + deps;
      } else if (m.type == MAT_CLAY) {
        deps = J2::clay_return_lanes(m, s, epeff, rules.clay_return != 0);
      } else {
        deps = J2::radial_return(m, s, epeff, strain_rate, temp_in);
      }
      if (q_on && rules.bulk_switch) {
        // Rule bulk_switch=stress: q only where the new mean stress (after the return) is compressive.
        q_new = TL::select(mean < 0.0, q_new, TL::splat(0.0));
        qv = q_new;
      }
      T p_new = -mean;
      if (m.fail_strain > 0.0) {
        const auto failed = epeff >= m.fail_strain;
        for (int c = 0; c < 6; ++c) s[c] = TL::select(failed, TL::splat(0.0), s[c]);
        p_new = TL::select(failed & (p_new < 0.0), TL::splat(0.0), p_new);
      }
      const T p_tot = q_on ? p_new + q_new : p_new;
      for (int c = 0; c < 3; ++c) sig[c] = s[c] - p_tot;
      for (int c = 3; c < 6; ++c) sig[c] = s[c];
      T work = Ops::double_dot(sig_r, de) + Ops::double_dot(sig, de);
      if (q_on && rules.bulk_work) {
        // Rule bulk_work=new: q's work by the new q over the whole step (the old stress's q_old
        // replaced by q_new), as the current program; for john it subtracts that work twice.
        work = work + (q_old - q_new) * dkk;
        if (m.type == MAT_JOHN) work = work - 2.0 * (q_new * dkk);
      }
      ie = ie + (0.5 * work) * vavg;
      if (has_temp) J2::adiabatic_heating(m, s, deps, mass, vol_new, temp);
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
      // The current version's null: the viscous deviator 2 mu dev(D), D = de / dt; under the
      // rule fluid_viscous=full the original's 2 mu D (its integer 1/3 drops the trace term).
      const double two_mu = (2.0 * m.viscosity) / dt;
      const T* rate = rules.fluid_viscous ? de : dev;
      for (int c = 0; c < 6; ++c) s[c] = two_mu * rate[c];
    } else if (fluid) {
      for (int c = 0; c < 6; ++c) s[c] = TL::splat(0.0);
    } else {
      for (int c = 0; c < 6; ++c) s[c] = s_r[c] + two_g * dev[c];
      deps = J2::radial_return(m, s, epeff, strain_rate, temp_in);
    }
    const bool can_fail = m.fail_strain > 0.0;
    const auto failed = epeff >= m.fail_strain;  // used only when can_fail
    if (can_fail)
      for (int c = 0; c < 6; ++c) s[c] = TL::select(failed, TL::splat(0.0), s[c]);
    if (q_on && rules.bulk_switch) {
      // Rule bulk_switch=stress: q only where the rotated old mean stress, without its q, is
      // compressive.
      q_new = TL::select(mean_r + q_old < 0.0, q_new, TL::splat(0.0));
      qv = q_new;
    }

    // Internal energy per unit initial volume, energy equation solved with the new
    // pressure (the EOS is linear in e): e1 = e* - (p1 + q1) dv / 2, p1 = F (a + b e1),
    // where e* holds the deviatoric work and the old pressure's (p0 + q0) half of the pdV
    // work.
    const T vol0 = mass / m.rho0;
    const T dv = (vol_new - vol_old) / vol0;
    const T p_old = -mean_r;
    const T dwork = (0.5 * (Ops::double_dot(s_r, de) + Ops::double_dot(s, de))) * vavg;
    T e_star = (ie + dwork) / vol0 - (0.5 * p_old) * dv;
    if (q_on) {
      // Rule bulk_work=new: the current program's -q_new dv in place of the old and new q's
      // halves (p_old carries q_old).
      if (rules.bulk_work)
        e_star = e_star - (q_new - 0.5 * q_old) * dv;
      else
        e_star = e_star - (0.5 * q_new) * dv;
    }
    const T mu = vol0 / vol_new - 1.0;
    T a, b;
    Eos::eos_coefficients(m, mu, &a, &b);
    if (m.type == MAT_HIEX) {
      a = burn * a;
      b = burn * b;
    }
    T p_new = (a + b * e_star) / (1.0 + (0.5 * b) * dv);
    if (can_fail) p_new = TL::select(failed & (p_new < 0.0), TL::splat(0.0), p_new);
    if (m.has_p_min) p_new = TL::select(p_new < m.p_min, TL::splat(m.p_min), p_new);
    const T e_new = e_star - (0.5 * p_new) * dv;
    ie = e_new * vol0;
    const T p_tot = q_on ? p_new + q_new : p_new;
    for (int c = 0; c < 3; ++c) sig[c] = s[c] - p_tot;
    for (int c = 3; c < 6; ++c) sig[c] = s[c];
    if (has_temp) J2::adiabatic_heating(m, s, deps, mass, vol_new, temp);
  }
};

// The stress stage's update of the particles of a StressBlock (constitution.hpp) from
// their velocity gradients: TL::W lanes starting at lane `first`.
template <class TL>
void stress_block_lanes(const MaterialParams& m, StressBlock& b, int first, const StressBlockArgs& a) {
  typedef decltype(TL::splat(0.0)) T;
  typedef LaneUpdate<T, TL> U;
  typedef StressOps<T, TL> Ops;
  typedef NeoHookeanLanes<T, TL> NeoHookean;
  const double dt = a.dt;
  T L[9];
  for (int r = 0; r < 9; ++r) L[r] = TL::load(b.L[r] + first);
  const T de[6] = {L[0] * dt, L[4] * dt, L[8] * dt, (0.5 * (L[5] + L[7])) * dt,
                   (0.5 * (L[2] + L[6])) * dt, (0.5 * (L[1] + L[3])) * dt};
  const T dw[3] = {(0.5 * (L[5] - L[7])) * dt, (0.5 * (L[2] - L[6])) * dt,
                   (0.5 * (L[1] - L[3])) * dt};
  const T vol_old = TL::load(b.vol + first);
  if (a.tl) {  // TLmp (neoh only, checked by the deck reader)
    T H[9], pk[9], dF[9], sig[6], vol = vol_old, ie = TL::load(b.ie + first);
    for (int r = 0; r < 9; ++r) {
      H[r] = TL::load(b.H[r] + first);
      pk[r] = TL::load(b.pk1[r] + first);
      dF[r] = L[r] * dt;
    }
    NeoHookean::neo_hookean_tl(m, dF, H, TL::load(b.mass + first), pk, sig, vol, ie, a.rules.tl_shape != 0);
    TL::store(b.vol + first, vol);
    for (int c = 0; c < 6; ++c) TL::store(b.sig[c] + first, sig[c]);
    for (int r = 0; r < 9; ++r) {
      TL::store(b.H[r] + first, H[r]);
      TL::store(b.pk1[r] + first, pk[r]);
    }
    TL::store(b.ie + first, ie);
    return;
  }
  const bool from_det = a.uvf || m.type == MAT_NEOH;
  T dL[9];
  if (from_det)
    for (int r = 0; r < 9; ++r) dL[r] = L[r] * dt;
  T vol_new = from_det ? vol_old * Ops::det_identity_plus(dL) : vol_old * (1.0 + ((de[0] + de[1]) + de[2]));
  T sig[6];
  for (int c = 0; c < 6; ++c) sig[c] = TL::load(b.sig[c] + first);
  if (m.type == MAT_NEOH) {
    T H[9], ie = TL::load(b.ie + first), qv = TL::load(b.qv + first);
    for (int r = 0; r < 9; ++r) H[r] = TL::load(b.H[r] + first);
    NeoHookean::neo_hookean(m, dL, de, H, vol_old, vol_new, sig, ie, a.has_q, qv, TL::load(b.mass + first), dt,
                            a.q1, a.q2, a.qlen);
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
            a.has_temp, qv, a.has_q, TL::load(b.burn + first), a.q1, a.q2, a.qlen, a.rules);
  TL::store(b.vol + first, vol_new);
  for (int c = 0; c < 6; ++c) TL::store(b.sig[c] + first, sig[c]);
  TL::store(b.epeff + first, epeff);
  TL::store(b.ie + first, ie);
  TL::store(b.temp + first, temp);
  TL::store(b.qv + first, qv);
}

}  // namespace
}  // namespace mpm3d
