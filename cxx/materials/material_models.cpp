// The material model table (material_models.hpp).
#include "materials/material_models.hpp"

#include <cmath>

namespace mpm3d {
namespace {

using M = MaterialParams;

// The elastic constants every solid starts with.
#define MPM3D_ELASTIC {"density", &M::rho0}, {"Young's modulus", &M::young}, {"Poisson's ratio", &M::poisson}

const MaterialParam kElas[] = {MPM3D_ELASTIC};
const MaterialParam kPla1[] = {MPM3D_ELASTIC, {"yield stress", &M::yield0}};
// The tangent modulus is read into `hardening` and turned into the plastic modulus there.
const MaterialParam kPla2[] = {MPM3D_ELASTIC, {"yield stress", &M::yield0}, {"tangent modulus", &M::hardening}};
// The Johnson-Cook yield stress (A + B eps_p^n)(1 + C ln rate*); the full model also
// softens with temperature, the simplified one (sjc, sjcf) does not.
#define MPM3D_JC_HARDENING {"A", &M::yield0}, {"B", &M::hardening}, {"n", &M::jc_n}, {"C", &M::jc_c}
#define MPM3D_JC_THERMAL                                                                             \
  {"m", &M::jc_m}, {"room temperature", &M::t_room}, {"melting temperature", &M::t_melt},           \
      {"specific heat", &M::heat_cap}
#define MPM3D_RATE {"reference strain rate", &M::eps0dot}
#define MPM3D_FAILURE {"failure strain", &M::fail_strain}
const MaterialParam kJohn[] = {MPM3D_ELASTIC, MPM3D_JC_HARDENING, MPM3D_JC_THERMAL, MPM3D_RATE};
const MaterialParam kJcf[] = {MPM3D_ELASTIC, MPM3D_JC_HARDENING, MPM3D_JC_THERMAL, MPM3D_RATE, MPM3D_FAILURE};
const MaterialParam kSjc[] = {MPM3D_ELASTIC, MPM3D_JC_HARDENING, MPM3D_RATE};
const MaterialParam kSjcf[] = {MPM3D_ELASTIC, MPM3D_JC_HARDENING, MPM3D_RATE, MPM3D_FAILURE};
const MaterialParam kHiex[] = {{"density", &M::rho0}, {"the detonation velocity", &M::wave_speed}};
const MaterialParam kNull[] = {{"density", &M::rho0}, {"the wave speed", &M::wave_speed}};
// The current version's null, a viscous fluid (the dam break's water).
const MaterialParam kNullCurrent[] = {{"density", &M::rho0}, {"the bulk modulus", &M::bulk_modulus}, {"the viscosity", &M::viscosity}};
const MaterialParam kDpm[] = {MPM3D_ELASTIC,
                              {"q_phi", &M::dp_qphi},
                              {"k_phi", &M::dp_kphi},
                              {"q_psi", &M::dp_qpsi},
                              {"the tension cut-off", &M::dp_tension}};
// The newest version's clay: J2 with the yield stress softening exponentially from the peak
// to the residual strength; its last number (a reference strain rate) is read and not used.
const MaterialParam kClay[] = {MPM3D_ELASTIC,
                               {"peak strength kappa_p", &M::clay_peak},
                               {"residual strength kappa_r", &M::clay_residual},
                               {"softening coefficient eta", &M::clay_softening},
                               {"epso (read, not used)", &M::eps0dot}};
#undef MPM3D_ELASTIC
#undef MPM3D_JC_HARDENING
#undef MPM3D_JC_THERMAL
#undef MPM3D_RATE
#undef MPM3D_FAILURE

std::string finish_pla2(M& m) {
  const double et = m.hardening;
  if (!(et >= 0.0 && et < m.young)) return "tangent modulus must lie in [0, E)";
  m.hardening = (m.young * et) / (m.young - et);  // plastic modulus E Et / (E - Et)
  return "";
}

std::string finish_thermal(M& m) {
  if (!(m.t_melt > m.t_room)) return "melting temperature must exceed room temperature";
  if (!(m.heat_cap > 0.0)) return "specific heat must be positive";
  return "";
}

std::string finish_hiex(M& m) {
  m.det_vel = m.wave_speed;  // the programmed burn's D; wave_speed sets dt and the bulk viscosity
  return "";
}

std::string finish_null_current(M& m) {
  if (!(m.rho0 > 0.0)) return "density must be positive";
  if (!(m.bulk_modulus > 0.0)) return "bulk modulus must be positive";
  if (!(m.viscosity >= 0.0)) return "viscosity must not be negative";
  m.wave_speed = std::sqrt(m.bulk_modulus / m.rho0);
  return "";
}

#define MPM3D_PARAMS(a) a, int(sizeof(a) / sizeof(a[0]))
//                                  keyword type    card                 fluid  JC     thermal finish
const MaterialModel kModels[] = {{"elas", MAT_ELAS, MPM3D_PARAMS(kElas), false, false, false, nullptr},
                                 {"pla1", MAT_PLA1, MPM3D_PARAMS(kPla1), false, false, false, nullptr},
                                 {"pla2", MAT_PLA2, MPM3D_PARAMS(kPla2), false, false, false, finish_pla2},
                                 {"john", MAT_JOHN, MPM3D_PARAMS(kJohn), false, true, true, finish_thermal},
                                 {"jcf", MAT_JCF, MPM3D_PARAMS(kJcf), false, true, true, finish_thermal},
                                 {"sjc", MAT_SJC, MPM3D_PARAMS(kSjc), false, true, false, nullptr},
                                 {"sjcf", MAT_SJCF, MPM3D_PARAMS(kSjcf), false, true, false, nullptr},
                                 {"hiex", MAT_HIEX, MPM3D_PARAMS(kHiex), true, false, false, finish_hiex},
                                 {"null", MAT_NULL, MPM3D_PARAMS(kNull), true, false, false, nullptr},
                                 {"dpm", MAT_DPM, MPM3D_PARAMS(kDpm), false, false, false, nullptr},
                                 {"neoh", MAT_NEOH, MPM3D_PARAMS(kElas), false, false, false, nullptr},
                                 {"clay", MAT_CLAY, MPM3D_PARAMS(kClay), false, false, false, nullptr}};
// The current version's card of a keyword whose card changed (decks with a keyword only the
// current version knows read it).
const MaterialModel kCurrentModels[] = {
    {"null", MAT_NULL, MPM3D_PARAMS(kNullCurrent), true, false, false, finish_null_current}};
#undef MPM3D_PARAMS

}  // namespace

const MaterialModel* find_material_model(const std::string& keyword, bool current_version) {
  if (current_version)
    for (const MaterialModel& m : kCurrentModels)
      if (keyword == m.keyword) return &m;
  for (const MaterialModel& m : kModels)
    if (keyword == m.keyword) return &m;
  return nullptr;
}

const MaterialModel* material_model(int type) {
  for (const MaterialModel& m : kModels)
    if (type == m.type) return &m;
  return nullptr;
}

}  // namespace mpm3d
