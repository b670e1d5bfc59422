#include "material.hpp"

#include <cmath>

namespace mpm3d {

const char* material_keyword(int type) {
  switch (type) {
    case MAT_ELAS: return "elas";
    case MAT_PLA1: return "pla1";
    case MAT_PLA2: return "pla2";
    case MAT_JOHN: return "john";
    case MAT_SJC: return "sjc";
    case MAT_SJCF: return "sjcf";
    case MAT_JCF: return "jcf";
    case MAT_HIEX: return "hiex";
    case MAT_NULL: return "null";
    case MAT_DPM: return "dpm";
  }
  return "?";
}

std::string material_derive(MaterialParams& m) {
  if (!(m.rho0 > 0.0)) return "density must be positive";
  if (!(m.young > 0.0)) return "Young's modulus must be positive";
  if (!(m.poisson > -1.0 && m.poisson < 0.5)) return "Poisson's ratio must lie in (-1, 0.5)";
  // Same operation order as fortran_ref/material.f90.
  m.shear = m.young / (2.0 * (1.0 + m.poisson));
  m.lambda = (m.young * m.poisson) / ((1.0 + m.poisson) * (1.0 - 2.0 * m.poisson));
  m.wave_speed = std::sqrt((m.lambda + 2.0 * m.shear) / m.rho0);
  return "";
}

}  // namespace mpm3d
