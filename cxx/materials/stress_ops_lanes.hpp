// The operations the stress updates of all the models share, written once for a lane type
// T (constitution_lanes.hpp): sigma : de, the Jaumann rotation, the artificial bulk
// viscosity and det(I + A). Internal linkage (lanes.hpp).
#pragma once
#include "core/lanes.hpp"

namespace mpm3d {
namespace {  // internal linkage, see lanes.hpp

template <class T, class TL>
struct StressOps {
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

  // det(I + A) of a 3x3 increment A (row-major), by the cofactors of the first row.
  static T det_identity_plus(const T A[9]) {
    const T a0 = 1.0 + A[0], a4 = 1.0 + A[4], a8 = 1.0 + A[8];
    return (a0 * (a4 * a8 - A[5] * A[7]) - A[1] * (A[3] * a8 - A[5] * A[6])) + A[2] * (A[3] * A[7] - a4 * A[6]);
  }
};

}  // namespace
}  // namespace mpm3d
