// The output variables (output_variables.hpp): one function each and the one list of them.
#include "input/output_variables.hpp"

#include <algorithm>
#include <cmath>

namespace mpm3d {

namespace {

double pressure(const double* s) { return -((s[0] + s[1]) + s[2]) / 3.0; }
const MaterialParams& mat_of(const Model& m, int p) { return m.mats[size_t(m.particles.mat[p])]; }

double var_seqv(const Model& m, int p) {
  const double* s = &m.particles.sig[6 * size_t(p)];
  const double pres = pressure(s);
  const double d0 = s[0] + pres, d1 = s[1] + pres, d2 = s[2] + pres;
  return std::sqrt(1.5 * ((d0 * d0 + d1 * d1 + d2 * d2) + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
}
double var_epef(const Model& m, int p) { return m.particles.epeff[p]; }
double var_mat(const Model& m, int p) { return double(m.particles.mat[p] + 1); }
// Rule pressure_q=out: the stored stress carries the bulk viscosity q in its pressure; the
// current program writes its mean stress, which holds no q.
double var_pres(const Model& m, int p) {
  const double with_q = pressure(&m.particles.sig[6 * size_t(p)]);
  return m.rules.pressure_q && !m.particles.qv.empty() ? with_q - m.particles.qv[size_t(p)] : with_q;
}
double var_volu(const Model& m, int p) { return m.particles.vol[p]; }
double var_engk(const Model& m, int p) {
  const double* v = &m.particles.v[3 * size_t(p)];
  return 0.5 * m.particles.mass[p] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}
double var_engi(const Model& m, int p) { return m.particles.ie[p]; }
double var_velx(const Model& m, int p) { return m.particles.v[3 * size_t(p)]; }
double var_vely(const Model& m, int p) { return m.particles.v[3 * size_t(p) + 1]; }
double var_velz(const Model& m, int p) { return m.particles.v[3 * size_t(p) + 2]; }
double var_cels(const Model& m, int p) { return m.particles.temp.empty() ? 0.0 : m.particles.temp[p]; }
double var_fail(const Model& m, int p) {
  const double ef = mat_of(m, p).fail_strain;
  return (ef > 0.0 && m.particles.epeff[p] >= ef) ? 1.0 : 0.0;
}
double var_damg(const Model& m, int p) {
  const double ef = mat_of(m, p).fail_strain;
  return ef > 0.0 ? std::min(1.0, std::max(0.0, m.particles.epeff[p] / ef)) : 0.0;
}
double var_stsx(const Model& m, int p) { return m.particles.sig[6 * size_t(p)]; }
// 0 where the initial positions are not held (a restart from a checkpoint without them).
double displacement(const Model& m, int p, int a) {
  if (m.particles.x0.empty()) return 0.0;
  return m.particles.x[3 * size_t(p) + size_t(a)] - m.particles.x0[3 * size_t(p) + size_t(a)];
}
double var_disx(const Model& m, int p) { return displacement(m, p, 0); }
double var_disy(const Model& m, int p) { return displacement(m, p, 1); }
double var_disz(const Model& m, int p) { return displacement(m, p, 2); }
double var_spre(const Model& m, int p) { return m.spre.empty() ? 0.0 : m.spre[size_t(p)]; }
double var_sspd(const Model& m, int p) {
  const MaterialParams& mp = mat_of(m, p);
  double k = mp.lambda + (2.0 / 3.0) * mp.shear;
  if (mp.eos_type == EOS_MIE_GRUNEISEN) k = mp.rho0 * (mp.eos[0] * mp.eos[0]);
  else if (mp.eos_type == EOS_LINEAR) k = mp.eos[1];
  else if (mp.eos_type == EOS_WEAK) k = mp.rho0 * (mp.eos[0] * mp.eos[0]);
  const double modulus = k + (4.0 / 3.0) * mp.shear;
  const double rho = m.particles.density(p);
  if (!(modulus > 0.0) || !(rho > 0.0)) return mp.wave_speed;
  return std::sqrt(modulus / rho);
}

}  // namespace

// The one list of the output variables (data_out.hpp): a new one is one entry here.
const std::vector<OutputVariable>& output_variables() {
  static const std::vector<OutputVariable> vars = {
      {"seqv", var_seqv}, {"epef", var_epef}, {"mat", var_mat},   {"pres", var_pres}, {"volu", var_volu},
      {"engk", var_engk}, {"engi", var_engi}, {"velx", var_velx}, {"vely", var_vely}, {"velz", var_velz},
      {"cels", var_cels}, {"fail", var_fail}, {"sspd", var_sspd}, {"damg", var_damg}, {"stsx", var_stsx},
      {"disx", var_disx}, {"disy", var_disy}, {"disz", var_disz}, {"spre", var_spre}};
  return vars;
}

ParticleVarFn output_variable(const std::string& name) {
  for (const auto& v : output_variables())
    if (name == v.name) return v.fn;
  return nullptr;
}

double particle_variable(const Model& m, const std::string& var, int p) {
  const ParticleVarFn f = output_variable(var);
  return f ? f(m, p) : 0.0;
}

}  // namespace mpm3d
