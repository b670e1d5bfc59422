#include "constitution.hpp"

#include <cmath>

namespace mpm3d {

// sigma : de with the shear terms counted twice, in a fixed order.
static inline double double_dot(const double* s, const double* d) {
  return ((s[0] * d[0] + s[1] * d[1]) + s[2] * d[2]) +
         2.0 * ((s[3] * d[3] + s[4] * d[4]) + s[5] * d[5]);
}

void jaumann_rotate(double sig[6], const double dw[3]) {
  const double sxx = sig[0], syy = sig[1], szz = sig[2];
  const double syz = sig[3], sxz = sig[4], sxy = sig[5];
  const double wyz = dw[0], wxz = dw[1], wxy = dw[2];
  sig[0] = sxx + 2.0 * (wxy * sxy + wxz * sxz);
  sig[1] = syy + 2.0 * (wyz * syz - wxy * sxy);
  sig[2] = szz - 2.0 * (wxz * sxz + wyz * syz);
  sig[3] = syz + (wyz * (szz - syy) - (wxy * sxz + wxz * sxy));
  sig[4] = sxz + (wxz * (szz - sxx) + (wxy * syz - wyz * sxy));
  sig[5] = sxy + (wxy * (syy - sxx) + (wxz * syz + wyz * sxz));
}

void eos_coefficients(const MaterialParams& m, double mu, double* a, double* b) {
  const double* c = m.eos;
  if (m.eos_type == EOS_LINEAR) {
    // p = C0 + C1 mu + C2 mu^2 + C3 mu^3 + (C4 + C5 mu + C6 mu^2) e; C2 = C6 = 0 in tension.
    const double mu2 = mu > 0.0 ? mu * mu : 0.0;
    *a = ((c[0] + c[1] * mu) + c[2] * mu2) + c[3] * (mu * mu * mu);
    *b = (c[4] + c[5] * mu) + c[6] * mu2;
  } else if (m.eos_type == EOS_JWL) {
    // JWL: A B R1 R2 omega; V = rho0 / rho.
    const double V = 1.0 / (1.0 + mu);
    const double r1v = c[2] * V, r2v = c[3] * V;
    *a = (c[0] * (1.0 - c[4] / r1v)) * std::exp(-r1v) + (c[1] * (1.0 - c[4] / r2v)) * std::exp(-r2v);
    *b = c[4] / V;
  } else {
    // Mie-Gruneisen: c0, s, gamma0. Hugoniot reference in compression, linear in tension.
    const double rc2 = m.rho0 * (c[0] * c[0]);
    if (mu > 0.0) {
      const double den = 1.0 - (c[1] - 1.0) * mu;
      *a = (rc2 * mu) * (1.0 + (1.0 - 0.5 * c[2]) * mu) / (den * den);
    } else {
      *a = rc2 * mu;
    }
    *b = c[2];
  }
}

double burn_fraction(const MaterialParams& m, double t_light, double time) {
  if (m.type != MAT_HIEX) return 1.0;
  const double f = ((time - t_light) * m.det_vel) / m.burn_width;
  if (!(f > 0.0)) return 0.0;
  return f < 1.0 ? f : 1.0;
}

double bulk_viscosity(double rho, double len, double c, double rate, double q1, double q2) {
  if (!(rate < 0.0)) return 0.0;
  return (rho * len) * ((q1 * len) * (rate * rate) - (q2 * c) * rate);
}

// Drucker-Prager, perfectly plastic, with tension cut-off (the FLAC formulation):
//   shear    f_s = tau + q_phi sm - k_phi,   tau = sqrt(J2), sm = tr(sigma)/3 (tension > 0)
//   tension  f_t = sm - sigma_t
//   flow     g_s = tau + q_psi sm (non-associated unless q_psi = q_phi)
// Elastic when f_s <= 0 and f_t <= 0. Otherwise the corner diagonal
//   h = tau - tau_P - alpha_P (sm - sigma_t),  tau_P = k_phi - q_phi sigma_t,
//   alpha_P = sqrt(1 + q_phi^2) - q_phi
// (h = 0 runs from the corner (sigma_t, tau_P) outwards, between the two surfaces' normals)
// splits the two returns: f_s > 0 and h > 0 -> shear return
//   lambda = f_s / (G + K q_phi q_psi), tau' = tau - G lambda, sm' = sm - K q_psi lambda
// (so f_s(tau', sm') = 0); otherwise (h <= 0, then sm > sigma_t), or when the shear
// return lands at tau' < 0 or sm' > sigma_t (non-associated flow near the apex), the
// tension return sm' = sigma_t, tau' = min(tau, tau_P) (onto the cut-off, at most to the
// corner). The deviator is scaled by tau'/tau. The
// equivalent plastic strain grows by (tau - tau') / (sqrt(3) G).
double dp_return(const MaterialParams& m, double s[6], double* sm, double K, double G) {
  const double j2 = 0.5 * ((s[0] * s[0] + s[1] * s[1]) + s[2] * s[2]) +
                    ((s[3] * s[3] + s[4] * s[4]) + s[5] * s[5]);
  const double tau = std::sqrt(j2);
  const double qphi = m.dp_qphi, kphi = m.dp_kphi, qpsi = m.dp_qpsi, sigt = m.dp_tension;
  const double fs = (tau + qphi * *sm) - kphi;
  const double ft = *sm - sigt;
  if (!(fs > 0.0) && !(ft > 0.0)) return 0.0;
  const double tau_p = kphi - qphi * sigt;
  const double alpha_p = std::sqrt(1.0 + qphi * qphi) - qphi;
  const double h = (tau - tau_p) - alpha_p * (*sm - sigt);
  double tau_new = 0.0, sm_new = sigt;
  bool tension = true;
  if (fs > 0.0 && h > 0.0) {
    const double lam = fs / (G + (K * qphi) * qpsi);
    tau_new = tau - G * lam;
    sm_new = *sm - (K * qpsi) * lam;
    // A non-associated return (q_psi < q_phi) may land beyond the apex or the cut-off:
    // then the tension return below applies.
    tension = tau_new < 0.0 || sm_new > sigt;
  }
  if (tension) {
    tau_new = tau > tau_p ? tau_p : tau;
    sm_new = sigt;
  }
  *sm = sm_new;
  if (tau > 0.0) {
    const double ratio = tau_new / tau;
    for (int c = 0; c < 6; ++c) s[c] = s[c] * ratio;
  }
  return (tau - tau_new) / (std::sqrt(3.0) * G);
}

void yield_stress(const MaterialParams& m, double epeff, double strain_rate, double temp,
                  double* sy, double* ep) {
  switch (m.type) {
    case MAT_PLA1:
      *sy = m.yield0;
      *ep = 0.0;
      return;
    case MAT_PLA2:
      *sy = m.yield0 + m.hardening * epeff;
      *ep = m.hardening;
      return;
    default: {  // Johnson-Cook family
      double hard = m.yield0, slope;
      if (epeff > 0.0) {
        // pow(e, 1) == e and pow(e, 0) == 1 exactly: the shortcut keeps the bits.
        const bool linear = m.jc_n == 1.0;
        hard = m.yield0 + m.hardening * (linear ? epeff : std::pow(epeff, m.jc_n));
        slope = (m.jc_n * m.hardening) * (linear ? 1.0 : std::pow(epeff, m.jc_n - 1.0));
      } else {
        slope = m.jc_n == 1.0 ? m.hardening : 0.0;
      }
      double factor = 1.0;
      if (m.jc_c != 0.0) {
        const double ratio = strain_rate / m.eps0dot;
        if (ratio > 1.0) factor = 1.0 + m.jc_c * std::log(ratio);
      }
      if (m.type == MAT_JOHN || m.type == MAT_JCF) {
        double tstar = (temp - m.t_room) / (m.t_melt - m.t_room);
        if (tstar > 0.0) {
          if (tstar > 1.0) tstar = 1.0;
          factor = factor * (1.0 - std::pow(tstar, m.jc_m));
        }
      }
      *sy = hard * factor;
      *ep = slope * factor;
      return;
    }
  }
}

// Radial return of the deviator s (6) against the yield stress; updates epeff and
// returns the plastic strain increment (0 when elastic).
static double radial_return(const MaterialParams& m, double s[6], double* epeff,
                            double strain_rate, double temp) {
  if (m.type == MAT_ELAS) return 0.0;
  const double j2 = 0.5 * ((s[0] * s[0] + s[1] * s[1]) + s[2] * s[2]) +
                    ((s[3] * s[3] + s[4] * s[4]) + s[5] * s[5]);
  const double q = std::sqrt(3.0 * j2);
  double sy, ep;
  yield_stress(m, *epeff, strain_rate, temp, &sy, &ep);
  if (!(q > sy)) return 0.0;
  const double g3 = 3.0 * m.shear;
  const double deps = (q - sy) / (g3 + ep);
  const double ratio = (q - g3 * deps) / q;
  for (int c = 0; c < 6; ++c) s[c] = s[c] * ratio;
  *epeff = *epeff + deps;
  return deps;
}

// Adiabatic heating of thermal Johnson-Cook materials (Taylor-Quinney 0.9) from the new
// deviator s and the plastic strain increment; other materials carry no heat capacity.
static void adiabatic_heating(const MaterialParams& m, const double s[6], double deps, double mass,
                              double vol_new, double* temp) {
  if (!temp || !(deps > 0.0) || !(m.heat_cap > 0.0)) return;
  const double q_new = std::sqrt(1.5 * (((s[0] * s[0] + s[1] * s[1]) + s[2] * s[2]) +
                                        2.0 * ((s[3] * s[3] + s[4] * s[4]) + s[5] * s[5])));
  *temp = *temp + (0.9 * (q_new * deps)) / ((mass / vol_new) * m.heat_cap);
}

void stress_update(const MaterialParams& m, const double de[6], const double dw[3], double dt,
                   double mass, double vol_old, double vol_new, StressState st, double burn, double q1,
                   double q2, double qlen) {
  double* sig = st.sig;
  jaumann_rotate(sig, dw);
  double sig_r[6];
  for (int c = 0; c < 6; ++c) sig_r[c] = sig[c];

  const double dkk = (de[0] + de[1]) + de[2];
  const double third = dkk / 3.0;
  const double dev[6] = {de[0] - third, de[1] - third, de[2] - third, de[3], de[4], de[5]};
  const double two_g = 2.0 * m.shear;
  const double vavg = 0.5 * (vol_old + vol_new);
  // Equivalent deviatoric strain rate (for the Johnson-Cook rate term).
  // Only the Johnson-Cook rate term reads it; it is formed only when that term is on.
  const double strain_rate =
      m.jc_c != 0.0 ? std::sqrt((2.0 / 3.0) * double_dot(dev, dev)) / dt : 0.0;
  const double temp = st.temp ? *st.temp : 0.0;
  // Bulk viscosity: the stored stress carries the last q in its pressure; q_old is taken
  // out before the (incremental) elastic update, q_new put in after.
  double q_old = 0.0, q_new = 0.0;
  if (st.q) {
    q_old = *st.q;
    q_new = bulk_viscosity(mass / vol_new, qlen, m.wave_speed, dkk / dt, q1, q2);
    *st.q = q_new;
  }

  const double mean_r = ((sig_r[0] + sig_r[1]) + sig_r[2]) / 3.0;
  double s[6];
  if (m.eos_type == EOS_NONE) {
    // Hypoelastic trial stress, then the return of its deviator (J2) or of the whole
    // stress (Drucker-Prager).
    const double lam_dkk = m.lambda * dkk;
    for (int c = 0; c < 3; ++c) {
      const double base = st.q ? sig_r[c] + q_old : sig_r[c];
      sig[c] = base + (lam_dkk + two_g * de[c]);
    }
    for (int c = 3; c < 6; ++c) sig[c] = sig_r[c] + two_g * de[c];
    double mean = ((sig[0] + sig[1]) + sig[2]) / 3.0;
    for (int c = 0; c < 3; ++c) s[c] = sig[c] - mean;
    for (int c = 3; c < 6; ++c) s[c] = sig[c];
    double deps;
    if (m.type == MAT_DPM) {
      deps = dp_return(m, s, &mean, m.lambda + two_g / 3.0, m.shear);
      *st.epeff = *st.epeff + deps;
    } else {
      deps = radial_return(m, s, st.epeff, strain_rate, temp);
    }
    double p_new = -mean;
    bool failed = m.fail_strain > 0.0 && *st.epeff >= m.fail_strain;
    if (failed) {
      for (int c = 0; c < 6; ++c) s[c] = 0.0;
      if (p_new < 0.0) p_new = 0.0;
    }
    const double p_tot = st.q ? p_new + q_new : p_new;
    for (int c = 0; c < 3; ++c) sig[c] = s[c] - p_tot;
    for (int c = 3; c < 6; ++c) sig[c] = s[c];
    *st.ie = *st.ie + (0.5 * (double_dot(sig_r, de) + double_dot(sig, de))) * vavg;
    adiabatic_heating(m, s, deps, mass, vol_new, st.temp);
    return;
  }

  // Deviatoric update plus an equation of state for the pressure. hiex and null carry no
  // deviatoric stress.
  double s_r[6];
  for (int c = 0; c < 3; ++c) s_r[c] = sig_r[c] - mean_r;
  for (int c = 3; c < 6; ++c) s_r[c] = sig_r[c];
  double deps = 0.0;
  const bool fluid = m.type == MAT_HIEX || m.type == MAT_NULL;
  if (fluid) {
    for (int c = 0; c < 6; ++c) s[c] = 0.0;
  } else {
    for (int c = 0; c < 6; ++c) s[c] = s_r[c] + two_g * dev[c];
    deps = radial_return(m, s, st.epeff, strain_rate, temp);
  }
  const bool failed = m.fail_strain > 0.0 && *st.epeff >= m.fail_strain;
  if (failed)
    for (int c = 0; c < 6; ++c) s[c] = 0.0;

  // Internal energy per unit initial volume, energy equation solved with the new pressure
  // (the EOS is linear in e): e1 = e* - (p1 + q1) dv / 2, p1 = F (a + b e1), where e*
  // holds the deviatoric work and the old pressure's (p0 + q0) half of the pdV work.
  const double vol0 = mass / m.rho0;
  const double dv = (vol_new - vol_old) / vol0;
  const double p_old = -mean_r;
  const double dwork = (0.5 * (double_dot(s_r, de) + double_dot(s, de))) * vavg;
  double e_star = (*st.ie + dwork) / vol0 - (0.5 * p_old) * dv;
  if (st.q) e_star = e_star - (0.5 * q_new) * dv;
  const double mu = vol0 / vol_new - 1.0;
  double a, b;
  eos_coefficients(m, mu, &a, &b);
  if (m.type == MAT_HIEX) {
    a = burn * a;
    b = burn * b;
  }
  double p_new = (a + b * e_star) / (1.0 + (0.5 * b) * dv);
  if (failed && p_new < 0.0) p_new = 0.0;
  const double e_new = e_star - (0.5 * p_new) * dv;
  *st.ie = e_new * vol0;
  const double p_tot = st.q ? p_new + q_new : p_new;
  for (int c = 0; c < 3; ++c) sig[c] = s[c] - p_tot;
  for (int c = 3; c < 6; ++c) sig[c] = s[c];
  adiabatic_heating(m, s, deps, mass, vol_new, st.temp);
}

}  // namespace mpm3d
