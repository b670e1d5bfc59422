#include "io/frame_fields.hpp"

#include <cmath>

#include "materials/material_models.hpp"

namespace mpm3d {

namespace {

// The original's particles start at 293 (its celsius_t, whatever the deck) and only the
// thermal Johnson-Cook materials change it; ours hold a temperature for those only.
constexpr double kOriginalStartTemperature = 293.0;

double f_celsius_t(const Model& m, int p) {
  const Particles& P = m.particles;
  if (P.temp.empty()) return kOriginalStartTemperature;
  const MaterialModel* mm = material_model(m.mats[size_t(P.mat[p])].type);
  return (mm && mm->thermal) ? P.temp[size_t(p)] : kOriginalStartTemperature;
}
// Neither version keeps a damage value in its particles (the current one computes one
// inside jcf and drops it), so both write 0 (outr damg is epeff / eps_f).
double f_damage(const Model&, int) { return 0.0; }
double f_mean_normal_stress(const Model& m, int p) {
  const double* s = &m.particles.sig[6 * size_t(p)];
  return ((s[0] + s[1]) + s[2]) / 3.0;
}
double f_smooth_mean_normal_stress(const Model& m, int p) { return m.spre.empty() ? 0.0 : -m.spre[size_t(p)]; }
// The deck's point and body loads (load node/part/body; 0 without).
double load(const Model& m, int p, int a) {
  return m.particles.fext.empty() ? 0.0 : m.particles.fext[3 * size_t(p) + size_t(a)];
}
double f_fxpx(const Model& m, int p) { return load(m, p, 0); }
double f_fxpy(const Model& m, int p) { return load(m, p, 1); }
double f_fxpz(const Model& m, int p) { return load(m, p, 2); }

}  // namespace

std::vector<FrameField> frame_fields(const Model& m) {
  std::vector<FrameField> f;
  auto add = [&](const char* name, ParticleVarFn fn) { f.push_back({name, fn, -1}); };
  auto var = [](const char* outr_name) { return output_variable(outr_name); };
  add("seqv", var("seqv"));
  add("epeff", var("epef"));
  add("pressure", var("pres"));  // -(sxx + syy + szz)/3
  if (m.current_version) {
    add("Smoothpressure", var("spre"));  // 0 without smoo, as the original
    add("MeanNormalStress", f_mean_normal_stress);
    add("SmoothMeanNormalStress", f_smooth_mean_normal_stress);
  }
  add("vx", var("velx"));
  add("vy", var("vely"));
  add("vz", var("velz"));
  if (m.current_version) {
    add("disx", var("disx"));
    add("disy", var("disy"));
    add("disz", var("disz"));
    add("fxpx", f_fxpx);
    add("fxpy", f_fxpy);
    add("fxpz", f_fxpz);
  }
  add("vol", var("volu"));
  add("celsius_t", f_celsius_t);
  add("damage", f_damage);
  if (m.current_version) add("stressx", var("stsx"));
  // The outr variables; a name already written (disx on a current deck) is not repeated.
  for (const auto& v : m.anim_vars) {
    bool have = false;
    for (const auto& e : f) have = have || e.name == v;
    if (have) continue;
    FrameField e{v, output_variable(v), -1};
    for (size_t k = 0; k < f.size() && e.alias_of < 0; ++k)
      if (f[k].fn == e.fn && f[k].alias_of < 0) e.alias_of = int(k);
    f.push_back(e);
  }
  return f;
}

DeckLattice::DeckLattice(const Model& m) : h(m.dcell) {
  for (int a = 0; a < 3; ++a) {
    lo[a] = m.box_lo[a];
    nc[a] = (long long)std::floor((m.box_hi[a] - m.box_lo[a]) / m.dcell + 0.5);
  }
}

double DeckLattice::node_coord(long long n, int a) const {
  const long long nx = nc[0] + 1, ny = nc[1] + 1;
  const long long i = a == 0 ? n % nx : a == 1 ? (n / nx) % ny : n / (nx * ny);
  return lo[a] + double(i) * h;
}

long long DeckLattice::voxel_node(long long c, int k) const {
  const long long i = c % nc[0] + (k & 1), j = (c / nc[0]) % nc[1] + ((k >> 1) & 1),
                  l = c / (nc[0] * nc[1]) + ((k >> 2) & 1);
  return i + (nc[0] + 1) * (j + (nc[1] + 1) * l);
}

}  // namespace mpm3d
