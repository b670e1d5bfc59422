// MaterialData: material and equation-of-state parameters (the original's MaterialData).
// MaterialParams is a plain C struct so the Fortran reference can read the same table.
#pragma once
#include <string>

extern "C" {

enum MaterialType {
  MAT_ELAS = 1,  // linear elastic (hypoelastic, Jaumann rate)
  MAT_PLA1 = 2,  // elastic-perfectly plastic, J2
  MAT_PLA2 = 3,  // J2 with linear isotropic hardening
  MAT_JOHN = 4,  // Johnson-Cook with thermal softening, adiabatic heating
  MAT_SJC = 5,   // simplified Johnson-Cook (no thermal term)
  MAT_SJCF = 6,  // simplified Johnson-Cook with failure strain
  MAT_JCF = 7,   // Johnson-Cook with failure strain
  MAT_HIEX = 8,  // high explosive (programmed burn)
  MAT_NULL = 9,  // null material
  MAT_DPM = 10,  // Drucker-Prager
  MAT_NEOH = 11,  // compressible neo-Hookean (hyperelastic, from the deformation gradient)
  MAT_CLAY = 12   // J2 with exponential softening (the newest version's undrained clay)
};

// EOS_WEAK: the current version's weakly compressible p = c0^2 (rho - rho0) (type 4).
enum EosType { EOS_NONE = 0, EOS_LINEAR = 1, EOS_MIE_GRUNEISEN = 2, EOS_JWL = 3, EOS_WEAK = 4 };

// One material set. Derived constants (shear, lambda, hardening, wave speed) are
// computed once by the deck reader with the formulas of material.cpp. hiex and null have
// no shear stiffness (shear = lambda = 0); their wave_speed is D (hiex) or c (null), so
// the time step and the bulk viscosity see them.
struct MaterialParams {
  double rho0;        // initial density
  double young;       // Young's modulus E
  double poisson;     // Poisson's ratio nu
  double shear;       // G = E / (2 (1 + nu))
  double lambda;      // Lame lambda = E nu / ((1 + nu)(1 - 2 nu))
  double yield0;      // initial yield stress (pla1, pla2) or Johnson-Cook A
  double hardening;   // pla2: plastic modulus Ep = E Et / (E - Et); JC: B
  double jc_n;        // JC hardening exponent n
  double jc_c;        // JC strain-rate coefficient C
  double jc_m;        // JC thermal exponent m
  double t_room;      // room temperature
  double t_melt;      // melting temperature
  double heat_cap;    // specific heat c_p
  double eps0dot;     // reference strain rate
  double fail_strain; // equivalent plastic strain at failure (sjcf, jcf); 0 = none
  double wave_speed;  // dilatational wave speed sqrt((lambda + 2G) / rho0)
  double eos[8];      // EOS parameters as in the deck (seos)
  double eos_e0;      // initial internal energy per unit initial volume
  int type;           // MaterialType
  int eos_type;       // EosType
  // Appended for hiex, null and dpm (the Fortran mirror has the same fields, same order).
  double det_vel;     // hiex: detonation velocity D
  double burn_width;  // hiex: width of the programmed-burn ramp, 1.5 h (set by the reader)
  double dp_qphi;     // dpm: friction coefficient q_phi
  double dp_kphi;     // dpm: cohesion term k_phi
  double dp_qpsi;     // dpm: dilatancy coefficient q_psi
  double dp_tension;  // dpm: tension cut-off sigma_t (capped at the apex k_phi / q_phi)
  // Appended for the current version's null (a fluid: density, bulk modulus, viscosity).
  double bulk_modulus;  // K; wave_speed = sqrt(K / rho0)
  double viscosity;     // dynamic viscosity mu: deviatoric stress 2 mu dev(D); 0 = none
  // Appended for clay: sigma_y(epeff) = residual + (peak - residual) exp(-softening epeff).
  double clay_peak;       // kappa_p: peak yield stress
  double clay_residual;   // kappa_r: residual yield stress
  double clay_softening;  // eta: softening coefficient
  // Mie-Gruneisen: the linear term's coefficient when non-zero, else rho0 c0^2 (rule
  // null_eos=wave_speed puts the current program's null wave speed there).
  double eos_k1;
  // Extension 'pmin' (null only): the pressure never falls below p_min (a cavitation
  // cut-off, <= 0) where has_p_min; the energy equation takes the cut pressure.
  double p_min;
  int has_p_min;
};

}  // extern "C"

namespace mpm3d {

const char* material_keyword(int type);
// Fills the derived constants of m from the deck values; returns an error text or "".
std::string material_derive(MaterialParams& m);

}  // namespace mpm3d
