#include "materials/material.hpp"

#include <cmath>

#include "materials/material_models.hpp"

namespace mpm3d {

const char* material_keyword(int type) {
  const MaterialModel* model = material_model(type);
  return model ? model->keyword : "?";
}

std::string material_derive(MaterialParams& m) {
  if (!(m.rho0 > 0.0)) return "density must be positive";
  const MaterialModel* model = material_model(m.type);
  if (model && model->fluid) {
    // No deviatoric stiffness: pressure from the EOS only. wave_speed is D or c.
    if (!(m.wave_speed > 0.0))
      return m.type == MAT_HIEX ? "detonation velocity must be positive" : "wave speed must be positive";
    m.young = 0.0;
    m.poisson = 0.0;
    m.shear = 0.0;
    m.lambda = 0.0;
    return "";
  }
  if (!(m.young > 0.0)) return "Young's modulus must be positive";
  if (!(m.poisson > -1.0 && m.poisson < 0.5)) return "Poisson's ratio must lie in (-1, 0.5)";
  // Same operation order as fortran_ref/material.f90.
  m.shear = m.young / (2.0 * (1.0 + m.poisson));
  m.lambda = (m.young * m.poisson) / ((1.0 + m.poisson) * (1.0 - 2.0 * m.poisson));
  m.wave_speed = std::sqrt((m.lambda + 2.0 * m.shear) / m.rho0);
  if (m.type == MAT_DPM) {
    if (!(m.dp_qphi >= 0.0) || !(m.dp_kphi >= 0.0) || !(m.dp_qpsi >= 0.0))
      return "Drucker-Prager q_phi, k_phi and q_psi must not be negative";
    if (!(m.dp_tension >= 0.0)) return "Drucker-Prager tension cut-off must not be negative";
    // The tension cut-off may not lie beyond the apex of the cone (sigma_m = k_phi / q_phi).
    if (m.dp_qphi > 0.0 && m.dp_tension > m.dp_kphi / m.dp_qphi) m.dp_tension = m.dp_kphi / m.dp_qphi;
  }
  if (m.type == MAT_CLAY) {
    if (!(m.clay_residual >= 0.0) || !(m.clay_peak >= m.clay_residual))
      return "clay strengths need 0 <= residual kappa_r <= peak kappa_p";
    if (!(m.clay_softening >= 0.0)) return "clay softening coefficient eta must not be negative";
    // The steepest softening slope, eta (kappa_p - kappa_r) at epeff = 0, must stay below 3G:
    // a steeper one has no unique return (the stress would fall faster than unloading can follow).
    if (!(m.clay_softening * (m.clay_peak - m.clay_residual) < 3.0 * m.shear))
      return "clay softening eta (kappa_p - kappa_r) must be below 3G = E / (1 + nu)";
  }
  return "";
}

}  // namespace mpm3d
