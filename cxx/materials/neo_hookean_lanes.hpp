// The compressible neo-Hookean solid (neoh), updated (hyperelastic, from F) and in total
// Lagrangian form (TLmp), written once for a lane type T (constitution_lanes.hpp); ln J
// runs lane by lane. Internal linkage (lanes.hpp).
#pragma once
#include <cmath>

#include "core/lanes.hpp"
#include "materials/material.hpp"
#include "materials/stress_ops_lanes.hpp"

namespace mpm3d {
namespace {  // internal linkage, see lanes.hpp

template <class T, class TL>
struct NeoHookeanLanes {
  typedef StressOps<T, TL> Ops;

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
    const T J = Ops::det_identity_plus(H);
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
    T work = Ops::double_dot(sig_old, de) + Ops::double_dot(sig, de);
    if (has_q) {
      const T dkk = (de[0] + de[1]) + de[2];
      const T mean = ((sig[0] + sig[1]) + sig[2]) / 3.0;
      const T q = Ops::bulk_viscosity(mass / vol_new, qlen, m.wave_speed, dkk / dt, q1, q2);
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
  // trapezoid of the old and new V0 P on dF. vol: the old volume in, the new out.
  // work_current_volume (rule tl_shape=centre): the current program's energy, the trapezoid
  // of P on dF times the mean of the old and new current volumes, where P is per reference
  // volume (written as V0 P scaled by that mean over V0).
  static void neo_hookean_tl(const MaterialParams& m, const T dF[9], T H[9], T mass, T pk[9], T sig[6], T& vol,
                             T& ie, bool work_current_volume) {
    for (int r = 0; r < 9; ++r) H[r] = H[r] + dF[r];
    T f[9];
    for (int r = 0; r < 9; ++r) f[r] = (r % 4 == 0) ? 1.0 + H[r] : H[r];
    const T J = Ops::det_identity_plus(H);
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
    const T vol_new = v0 * J;
    if (work_current_volume)
      ie = ie + (0.5 * (work_old + work_new)) * ((0.5 * (vol + vol_new)) / v0);
    else
      ie = ie + 0.5 * (work_old + work_new);
    vol = vol_new;
  }
};

}  // namespace
}  // namespace mpm3d
