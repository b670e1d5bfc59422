#include "materials/constitution.hpp"
#include "materials/constitution_lanes.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace mpm3d {

// One particle: the lane-generic update of constitution_lanes.hpp (and the families'
// headers) with T = double.
using Scalar = LaneUpdate<double, ScalarLane>;

void jaumann_rotate(double sig[6], const double dw[3]) { Scalar::Ops::jaumann_rotate(sig, dw); }

void eos_coefficients(const MaterialParams& m, double mu, double* a, double* b) {
  if (m.eos_type != EOS_JWL) {
    // Linear, weakly compressible and Mie-Gruneisen (eos_lanes.hpp; it calls back here for JWL).
    Scalar::Eos::eos_coefficients(m, mu, a, b);
    return;
  }
  // JWL: A B R1 R2 omega; V = rho0 / rho.
  const double* c = m.eos;
  const double V = 1.0 / (1.0 + mu);
  const double r1v = c[2] * V, r2v = c[3] * V;
  *a = (c[0] * (1.0 - c[4] / r1v)) * std::exp(-r1v) + (c[1] * (1.0 - c[4] / r2v)) * std::exp(-r2v);
  *b = c[4] / V;
}

double bulk_viscosity(double rho, double len, double c, double rate, double q1, double q2) {
  return Scalar::Ops::bulk_viscosity(rho, len, c, rate, q1, q2);
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
// This is the return as branches, the reference that the update's lanes
// (drucker_prager_lanes.hpp, selects over the four arms) are tested against bit for bit.
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
    case MAT_CLAY: {
      const double drop = m.clay_peak - m.clay_residual, decay = std::exp(-(m.clay_softening * epeff));
      *sy = m.clay_residual + drop * decay;
      *ep = -((m.clay_softening * drop) * decay);
      return;
    }
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

// clay's return. Ours (original false) solves the consistency condition of the backward-Euler
// return, q_trial - 3G d = sigma_y(epeff + d), by Newton's method from d = 0: r(d) is
// decreasing and concave (3G + H > 0, checked by material_derive), so the iterates after the
// first approach the root from above; the stress ends on the softening curve at the new
// epeff, and on a proportional strain path the result does not depend on the step.
// The original (rule clay_return=linear, M3DM12 of the newest program): one linearised step
// d = (q - sigma_y) / (3G + H(epeff)), then the deviator scaled to sigma_y(epeff + d) / q;
// where sigma_y(epeff + d) > q the step is undone and the trial stress kept.
double clay_return(const MaterialParams& m, double s[6], double* epeff, bool original) {
  const double j2 = 0.5 * ((s[0] * s[0] + s[1] * s[1]) + s[2] * s[2]) + ((s[3] * s[3] + s[4] * s[4]) + s[5] * s[5]);
  const double q = std::sqrt(3.0 * j2);
  double sy, h;
  yield_stress(m, *epeff, 0.0, 0.0, &sy, &h);
  if (!(q > sy)) return 0.0;
  const double g3 = 3.0 * m.shear;
  double d = (q - sy) / (g3 + h), ratio;
  if (original) {
    yield_stress(m, *epeff + d, 0.0, 0.0, &sy, &h);
    if (sy > q) {
      *epeff = (*epeff + d) - d;
      return 0.0;
    }
    ratio = sy / q;
  } else {
    for (int it = 0; it < kClayIterations; ++it) {
      yield_stress(m, *epeff + d, 0.0, 0.0, &sy, &h);
      const double r = (q - g3 * d) - sy;
      if (!(std::fabs(r) > kClayTolerance * q)) break;
      d = d + r / (g3 + h);
    }
    ratio = (q - g3 * d) / q;
  }
  for (int c = 0; c < 6; ++c) s[c] = s[c] * ratio;
  *epeff = *epeff + d;
  return d;
}

void stress_update(const MaterialParams& m, const double de[6], const double dw[3], double dt,
                   double mass, double vol_old, double vol_new, StressState st, double burn, double q1,
                   double q2, double qlen, const StepRules& rules) {
  double temp = st.temp ? *st.temp : 0.0, qv = st.q ? *st.q : 0.0, vol = vol_new;
  Scalar::update(m, de, dw, dt, mass, vol_old, vol, st.sig, *st.epeff, *st.ie, temp,
                 st.temp != nullptr, qv, st.q != nullptr, burn, q1, q2, qlen, rules);
  if (st.vol) *st.vol = vol;
  if (st.temp) *st.temp = temp;
  if (st.q) *st.q = qv;
}

// constitution_avx2.cpp: the same lanes in AVX2 registers.
void stress_block_avx2(const MaterialParams& m, StressBlock& b, const StressBlockArgs& a);

bool lanes_use_avx2() {
  // MPM3D_ISA=baseline keeps the SSE2 code (the tests compare both builds' bits).
  static const bool avx2 = [] {
    const char* isa = std::getenv("MPM3D_ISA");
    if (isa && std::strcmp(isa, "baseline") == 0) return false;
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return avx2;
}

void stress_block(const MaterialParams& m, StressBlock& b, const StressBlockArgs& a) {
  if (lanes_use_avx2())
    stress_block_avx2(m, b, a);
  else
    stress_block_lanes<VectorLane<kStressLanes>>(m, b, 0, a);
}

void stress_block_lane(const MaterialParams& m, StressBlock& b, int i, const StressBlockArgs& a) {
  stress_block_lanes<ScalarLane>(m, b, i, a);
}

}  // namespace mpm3d
