// The deck reader (data_in.hpp): the cards, their checks, and the set-up after 'endi'
// (lighting times, initial energies, GIMP sizes, dt, mass cut-off); the particles of the
// 'part' cards come from particle_gen.cpp.
#include "data_in.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "ffi.hpp"
#include "particle_gen.hpp"

namespace mpm3d {

static const char* const kOutputVars[] = {"seqv", "epef", "mat", "pres", "volu", "engk", "engi",
                                          "velx", "vely", "velz", "cels", "fail", "sspd", "damg"};

bool is_output_variable(const std::string& name) {
  for (const char* v : kOutputVars)
    if (name == v) return true;
  return false;
}

// The process-wide default of the memory budget (set_deck_memory_budget): the one piece of
// state this file keeps; each read takes its budget once, as a parameter of the Reader.
static std::atomic<double> g_memory_budget{0.0};

void set_deck_memory_budget(double bytes) { g_memory_budget.store(bytes); }

double deck_memory_budget() {
  const double set = g_memory_budget.load();
  if (set > 0.0) return set;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? double(pages) * double(page) : 1.0e18;
}

namespace {

std::string megabytes(double bytes) { return std::to_string(long(bytes / 1048576.0 + 0.5)) + " MB"; }

class Reader {
 public:
  Reader(TokenStream ts, double memory_budget)
      : ts_(std::move(ts)), memory_budget_(memory_budget), parts_(m_.particles, ts_.name()) {}
  Model read();

 private:
  TokenStream ts_;
  const double memory_budget_;  // bytes (deck_memory_budget)
  Model m_;
  ParticleAppender parts_;  // appends the particle cards' particles to m_.particles
  bool ended_ = false;
  int box_line_[3] = {0, 0, 0}, dcell_line_ = 0;  // where the box and the cell size were set

  [[noreturn]] void fail(int line, const std::string& what) { ts_.fail(line, what); }
  bool on_off(const Token& key);
  void need_counts(const Token& key, bool particles, bool materials, bool bodies);
  void read_materials(const Token& key);
  void read_particles(const Token& key);
  void read_velocities(const Token& key);
  void read_loads(const Token& key);
  void read_eos(const Token& key);
  int body_index(const Token& at, long ib);
  int particle_index(const Token& at, long pid);
  std::string output_var(int line);
  void finish(int line);
};

bool Reader::on_off(const Token& key) {
  if (ts_.at_end()) fail(key.line, "'" + key.text + "' needs 'on' or 'off'");
  const Token& t = ts_.next();
  const std::string k = key4(t.text);
  if (k == "on") return true;
  if (k == "off") return false;
  fail(t.line, "'" + key.text + "' needs 'on' or 'off', found '" + t.text + "'");
}

void Reader::need_counts(const Token& key, bool particles, bool materials, bool bodies) {
  if (particles && m_.nbmp < 0) fail(key.line, "'" + key.text + "' before 'nbmp' (number of particles)");
  if (materials && m_.nmat < 0) fail(key.line, "'" + key.text + "' before 'nmat' (number of materials)");
  if (bodies && m_.nbbo < 0) fail(key.line, "'" + key.text + "' before 'nbbo' (number of bodies)");
}

Model Reader::read() {
  m_.deck_path = ts_.name();
  while (!ts_.at_end()) {
    const Token key = ts_.next();
    const std::string k = key4(key.text);
    if (k == "mpm3") {
      m_.title = ts_.rest_of_line(key);
    } else if (k == "nbmp" || k == "nbco" || k == "nbbo" || k == "nmat") {
      const long n = ts_.integer(key.text.c_str());
      if (n < 1 || n > kMaxParticles)
        fail(key.line, "'" + key.text + "' must be a count in 1.." + std::to_string(kMaxParticles) + ", got " + std::to_string(n));
      if (k == "nbmp") {
        if (m_.nbmp >= 0) fail(key.line, "'nbmp' given twice");
        const double need = double(n) * kBytesPerParticle, budget = memory_budget_;
        if (need > budget)
          fail(key.line, "'nbmp' = " + std::to_string(n) + " particles need about " + megabytes(need) +
                             ", more than the " + megabytes(budget) + " of memory available");
        m_.nbmp = int(n);
        m_.particles.resize(0);  // grows as the particle cards generate particles
        parts_.set_limit(m_.nbmp);
      } else if (k == "nbco") {
        if (n > 2) fail(key.line, "'nbco' must be 1 or 2");
        m_.nbco = int(n);
      } else if (k == "nbbo") {
        m_.nbbo = int(n);
      } else {
        if (n > 1000) fail(key.line, "'nmat' too large");
        m_.nmat = int(n);
        m_.mats.assign(size_t(n), MaterialParams{});
        for (auto& mp : m_.mats) mp.type = 0;
      }
    } else if (k == "endt") {
      m_.endtime = ts_.real("the end time");
      if (!(m_.endtime > 0.0)) fail(key.line, "end time must be positive");
      m_.outtime = m_.endtime;
    } else if (k == "grid") {
      for (int a = 0; a < 3; ++a) {
        m_.box_lo[a] = ts_.real("the grid box");
        m_.box_hi[a] = ts_.real("the grid box");
        m_.box_set[a] = true;
        box_line_[a] = key.line;
        if (!(m_.box_hi[a] > m_.box_lo[a]))
          fail(key.line, std::string("'grid': maximum must exceed minimum along ") + char('x' + a));
      }
    } else if (k == "spx" || k == "spy" || k == "spz") {
      const int a = k[2] - 'x';
      m_.box_lo[a] = ts_.real("the box minimum");
      m_.box_hi[a] = ts_.real("the box maximum");
      m_.box_set[a] = true;
      box_line_[a] = key.line;
      if (!(m_.box_hi[a] > m_.box_lo[a])) fail(key.line, "'" + key.text + "': maximum must exceed minimum");
    } else if (k == "dcel") {
      m_.dcell = ts_.real("the cell size");
      if (!(m_.dcell > 0.0)) fail(key.line, "cell size must be positive");
      dcell_line_ = key.line;
    } else if (k == "dtsc") {
      m_.dtscale = ts_.real("the time-step scale");
      if (!(m_.dtscale > 0.0) || m_.dtscale > 2.5) fail(key.line, "time-step scale must lie in (0, 2.5]");
    } else if (k == "outt") {
      m_.outtime = ts_.real("the output interval");
      if (!(m_.outtime > 0.0)) fail(key.line, "output interval must be positive");
    } else if (k == "rptt") {
      m_.rpttime = ts_.real("the report interval");
      if (!(m_.rpttime > 0.0)) fail(key.line, "report interval must be positive");
    } else if (k == "adgr") {  // extension: adaptive background grid every N steps
      const long n = ts_.integer("the regrid interval");
      if (n < 0 || n > 1000000000) fail(key.line, "'adgr' needs a step interval, 0 (off) or more");
      m_.regrid_every = int(n);
    } else if (k == "fixe") {
      for (int f = 0; f < 6; ++f) {
        const long v = ts_.integer("a face condition");
        if (v < 0 || v > 2) fail(key.line, "face conditions are 0 (free), 1 (fixed) or 2 (symmetry)");
        m_.fix[f] = int(v);
      }
    } else if (k == "mate") {
      read_materials(key);
    } else if (k == "part") {
      read_particles(key);
    } else if (k == "musl" || k == "usf" || k == "usl") {
      if (on_off(key)) m_.scheme = k == "musl" ? SCHEME_MUSL : (k == "usf" ? SCHEME_USF : SCHEME_USL);
    } else if (k == "jaum") {
      m_.jaumann = on_off(key);
      if (!m_.jaumann) m_.warnings.push_back("jaum off: stresses are rotated with the Jaumann rate all the same");
    } else if (k == "load") {
      read_loads(key);
    } else if (k == "velo") {
      read_velocities(key);
    } else if (k == "seos") {
      read_eos(key);
    } else if (k == "outr") {
      m_.anim_vars.push_back(output_var(key.line));
    } else if (k == "curv") {
      CurveRequest c;
      c.var = output_var(key.line);
      long pid = 1;
      if (!ts_.at_end() && ts_.peek().line == key.line && parse_integer(ts_.peek().text, pid)) ts_.next();
      need_counts(key, true, false, false);
      c.particle = particle_index(key, pid);
      m_.curves.push_back(c);
    } else if (k == "curx") {
      CurveRequest c;
      c.var = output_var(key.line);
      double xyz[3];
      for (double& v : xyz) v = ts_.real("a curve position");
      if (parts_.count() == 0) fail(key.line, "'curx' must follow the particle cards");
      const double tol = 0.25 * m_.dcell;
      int found = -1;
      for (int p = 0; p < parts_.count() && found < 0; ++p) {
        const double* x = &m_.particles.x[3 * size_t(p)];
        if (std::fabs(x[0] - xyz[0]) <= tol && std::fabs(x[1] - xyz[1]) <= tol && std::fabs(x[2] - xyz[2]) <= tol)
          found = p;
      }
      if (found < 0) fail(key.line, "'curx': no particle within 0.25 h of the point");
      c.particle = found;
      m_.curves.push_back(c);
    } else if (k == "pt2d") {
      for (double& v : m_.pt2d) v = ts_.real("the pt2d box");
      m_.has_pt2d = true;
    } else if (k == "tecp" || k == "para") {
      bool on = true;
      if (!ts_.at_end() && (key4(ts_.peek().text) == "on" || key4(ts_.peek().text) == "off")) on = on_off(key);
      (k == "tecp" ? m_.tecplot : m_.paraview) = on;
    } else if (k == "hdf5") {  // extension: HDF5 + XDMF animation series
      bool on = true;
      if (!ts_.at_end() && (key4(ts_.peek().text) == "on" || key4(ts_.peek().text) == "off")) on = on_off(key);
      m_.hdf5 = on;
    } else if (k == "deto") {
      double xyz[3];
      for (double& v : xyz) v = ts_.real("the detonation point");
      if (m_.deto.size() >= 30) fail(key.line, "at most 10 detonation points ('deto')");
      for (double v : xyz) m_.deto.push_back(v);
    } else if (k == "bulk") {
      m_.bulk_q1 = ts_.real("q1");
      m_.bulk_q2 = ts_.real("q2");
      if (!(m_.bulk_q1 >= 0.0) || !(m_.bulk_q2 >= 0.0))
        fail(key.line, "bulk viscosity coefficients must not be negative");
      m_.has_bulk = true;
    } else if (k == "gimp") {
      m_.gimp = true;
    } else if (k == "cont") {
      if (ts_.at_end()) fail(key.line, "'cont' needs 'lagr mu normbody'");
      const Token& how = ts_.next();
      if (key4(how.text) != "lagr")
        fail(how.line, "'cont': only 'lagr' (multi-velocity grid contact) is supported, found '" + how.text + "'");
      m_.contact_mu = ts_.real("the friction coefficient");
      if (!(m_.contact_mu >= 0.0)) fail(key.line, "'cont': friction coefficient must not be negative");
      const Token& nbt = ts_.peek();
      const long nb = ts_.integer("the normal body (0, 1 or 2)");
      if (nb < 0 || nb > 2) fail(nbt.line, "'cont': normal body must be 0 (average), 1 or 2");
      m_.contact_normbody = int(nb);
      m_.contact = true;
      m_.contact_line = key.line;
    } else if (k == "endi") {
      ended_ = true;
      finish(key.line);
      break;
    } else {
      fail(key.line, "unknown keyword '" + key.text + "'");
    }
  }
  if (!ended_) fail(ts_.line(), "end of file reached before 'endi'");
  return std::move(m_);
}

std::string Reader::output_var(int line) {
  if (ts_.at_end()) fail(line, "missing output variable name");
  const Token& t = ts_.next();
  std::string v = t.text;
  for (char& ch : v) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  if (v.size() > 4) v = v.substr(0, 4);
  if (!is_output_variable(v)) fail(t.line, "unknown output variable '" + t.text + "'");
  return v;
}

int Reader::body_index(const Token& at, long ib) {
  if (ib < 1 || ib > long(m_.bodies.size()))
    fail(at.line, "body " + std::to_string(ib) + " does not exist (" + std::to_string(m_.bodies.size()) +
                      " bodies defined so far)");
  return int(ib - 1);
}

int Reader::particle_index(const Token& at, long pid) {
  if (pid < 1 || pid > m_.nbmp)
    fail(at.line, "particle " + std::to_string(pid) + " out of range 1.." + std::to_string(m_.nbmp));
  return int(pid - 1);
}

void Reader::read_materials(const Token& key) {
  need_counts(key, false, true, false);
  for (;;) {
    const Token& idt = ts_.peek();
    const long num = ts_.integer("a material number");
    if (num < 1 || num > m_.nmat)
      fail(idt.line, "material number " + std::to_string(num) + " out of range 1.." + std::to_string(m_.nmat));
    const Token typ = ts_.next();
    const std::string t = key4(typ.text);
    MaterialParams& mp = m_.mats[size_t(num - 1)];
    const int line = typ.line;
    mp = MaterialParams{};
    auto R = [&](const char* what) { return ts_.real(what); };
    if (t == "elas" || t == "pla1" || t == "pla2") {
      mp.type = t == "elas" ? MAT_ELAS : (t == "pla1" ? MAT_PLA1 : MAT_PLA2);
      mp.rho0 = R("density");
      mp.young = R("Young's modulus");
      mp.poisson = R("Poisson's ratio");
      if (mp.type != MAT_ELAS) mp.yield0 = R("yield stress");
      if (mp.type == MAT_PLA2) {
        const double et = R("tangent modulus");
        if (!(et >= 0.0 && et < mp.young)) fail(line, "tangent modulus must lie in [0, E)");
        mp.hardening = (mp.young * et) / (mp.young - et);
      }
    } else if (t == "john" || t == "jcf") {
      mp.type = t == "john" ? MAT_JOHN : MAT_JCF;
      mp.rho0 = R("density");
      mp.young = R("Young's modulus");
      mp.poisson = R("Poisson's ratio");
      mp.yield0 = R("A");
      mp.hardening = R("B");
      mp.jc_n = R("n");
      mp.jc_c = R("C");
      mp.jc_m = R("m");
      mp.t_room = R("room temperature");
      mp.t_melt = R("melting temperature");
      mp.heat_cap = R("specific heat");
      mp.eps0dot = R("reference strain rate");
      if (mp.type == MAT_JCF) mp.fail_strain = R("failure strain");
      if (!(mp.t_melt > mp.t_room)) fail(line, "melting temperature must exceed room temperature");
      if (!(mp.heat_cap > 0.0)) fail(line, "specific heat must be positive");
    } else if (t == "sjc" || t == "sjcf") {
      mp.type = t == "sjc" ? MAT_SJC : MAT_SJCF;
      mp.rho0 = R("density");
      mp.young = R("Young's modulus");
      mp.poisson = R("Poisson's ratio");
      mp.yield0 = R("A");
      mp.hardening = R("B");
      mp.jc_n = R("n");
      mp.jc_c = R("C");
      mp.eps0dot = R("reference strain rate");
      if (mp.type == MAT_SJCF) mp.fail_strain = R("failure strain");
    } else if (t == "hiex" || t == "null") {
      mp.type = t == "hiex" ? MAT_HIEX : MAT_NULL;
      mp.rho0 = R("density");
      mp.wave_speed = R(t == "hiex" ? "the detonation velocity" : "the wave speed");
      if (mp.type == MAT_HIEX) mp.det_vel = mp.wave_speed;
    } else if (t == "dpm") {
      mp.type = MAT_DPM;
      mp.rho0 = R("density");
      mp.young = R("Young's modulus");
      mp.poisson = R("Poisson's ratio");
      mp.dp_qphi = R("q_phi");
      mp.dp_kphi = R("k_phi");
      mp.dp_qpsi = R("q_psi");
      mp.dp_tension = R("the tension cut-off");
    } else {
      fail(line, "unknown material type '" + typ.text + "'");
    }
    if (mp.type == MAT_SJC || mp.type == MAT_SJCF || mp.type == MAT_JOHN || mp.type == MAT_JCF) {
      if (!(mp.jc_n > 0.0)) fail(line, "Johnson-Cook n must be positive");
      if (mp.jc_c != 0.0 && !(mp.eps0dot > 0.0)) fail(line, "reference strain rate must be positive");
    }
    if (mp.fail_strain < 0.0) fail(line, "failure strain must not be negative");
    const std::string err = material_derive(mp);
    if (!err.empty()) fail(line, "material " + std::to_string(num) + ": " + err);
    if (!std::isfinite(mp.shear) || !std::isfinite(mp.lambda) || !(mp.wave_speed > 0.0) || !std::isfinite(mp.wave_speed))
      fail(line, "material " + std::to_string(num) + ": elastic constants out of range (wave speed not a positive finite number)");
    if (num == m_.nmat) break;
  }
}

void Reader::read_eos(const Token& key) {
  need_counts(key, false, true, false);
  const Token& at = ts_.peek();
  const long mid = ts_.integer("a material number");
  if (mid < 1 || mid > m_.nmat) fail(at.line, "material number " + std::to_string(mid) + " out of range 1.." + std::to_string(m_.nmat));
  MaterialParams& mp = m_.mats[size_t(mid - 1)];
  if (mp.type == 0) fail(at.line, "'seos' for material " + std::to_string(mid) + " before its 'mate' card");
  const long et = ts_.integer("an EOS type");
  if (et == 1) {
    for (int i = 0; i < 7; ++i) mp.eos[i] = ts_.real("an EOS coefficient");
    mp.eos_e0 = ts_.real("E0");
  } else if (et == 2) {
    for (int i = 0; i < 3; ++i) mp.eos[i] = ts_.real("an EOS coefficient");
    mp.eos_e0 = ts_.real("E0");
    if (!(mp.eos[0] > 0.0)) fail(key.line, "Mie-Gruneisen c0 must be positive");
  } else if (et == 3) {
    for (int i = 0; i < 5; ++i) mp.eos[i] = ts_.real("a JWL coefficient");
    mp.eos_e0 = ts_.real("E0");
    if (mp.type != MAT_HIEX && mp.type != MAT_NULL) fail(key.line, "EOS type 3 (JWL) is for hiex and null materials");
    if (!(mp.eos[2] > 0.0) || !(mp.eos[3] > 0.0)) fail(key.line, "JWL R1 and R2 must be positive");
  } else {
    fail(key.line, "unknown EOS type " + std::to_string(et) + " (1 linear polynomial, 2 Mie-Gruneisen, 3 JWL)");
  }
  if (mp.type == MAT_DPM) fail(key.line, "a dpm material takes no equation of state");
  mp.eos_type = int(et);
}

void Reader::read_particles(const Token& key) {
  need_counts(key, true, true, true);
  if (int(m_.bodies.size()) >= m_.nbbo)
    fail(key.line, "more particle cards than 'nbbo' = " + std::to_string(m_.nbbo) + " bodies");
  const Token kind = ts_.next();
  const std::string k = key4(kind.text);
  const Token& ct = ts_.peek();
  const long comp = ts_.integer("a component number");
  if (comp < 1 || comp > m_.nbco) fail(ct.line, "component " + std::to_string(comp) + " out of range 1.." + std::to_string(m_.nbco));
  Body b;
  b.first = parts_.count();
  b.component = int(comp);
  m_.bodies.push_back(b);
  auto material = [&]() {
    const Token& at = ts_.peek();
    const long id = ts_.integer("a material number");
    if (id < 1 || id > m_.nmat) fail(at.line, "material number " + std::to_string(id) + " out of range 1.." + std::to_string(m_.nmat));
    if (m_.mats[size_t(id - 1)].type == 0) fail(at.line, "material " + std::to_string(id) + " is used before its 'mate' card");
    return int(id - 1);
  };
  if (k == "poin") {
    const Token& nt = ts_.peek();
    const long n = ts_.integer("the number of points");
    if (n < 1) fail(nt.line, "number of points must be positive");
    check_points_room(parts_, nt.line, n);
    long last = 0;
    for (long i = 0; i < n; ++i) {
      const Token& pt = ts_.peek();
      const long pid = ts_.integer("a particle id");
      if (pid <= last) fail(pt.line, "particle ids must ascend (" + std::to_string(pid) + " after " + std::to_string(last) + ")");
      last = pid;
      const int mat = material();
      const double mass = ts_.real("the particle mass");
      if (!(mass > 0.0)) fail(pt.line, "particle mass must be positive");
      const double vol = mass / m_.mats[size_t(mat)].rho0;
      if (!(vol > 0.0) || !std::isfinite(vol)) fail(pt.line, "particle volume (mass / density) out of range");
      const double x = ts_.real("x"), y = ts_.real("y"), z = ts_.real("z");
      parts_.add(pt.line, int(m_.bodies.size()) - 1, mat, mass, vol, x, y, z);
    }
  } else if (k == "bloc" || k == "sphe" || k == "cyli") {
    const int mat = material();
    const double rho = ts_.real("the density");
    const double dp = ts_.real("the particle spacing");
    if (!(rho > 0.0) || !(dp > 0.0)) fail(kind.line, "density and spacing must be positive");
    // The card's density gives the mass; the volume is mass over the material's density,
    // as in the book version (the two densities may differ in a deck).
    const double mass = rho * ((dp * dp) * dp);
    const double vol = mass / m_.mats[size_t(mat)].rho0;
    m_.bodies.back().spacing = dp;
    if (!(vol > 0.0) || !(mass > 0.0) || !std::isfinite(mass))
      fail(kind.line, "particle volume (spacing^3) or mass (density * volume) out of range");
    LatticeCard card;
    card.line = kind.line;
    card.body = int(m_.bodies.size()) - 1;
    card.mat = mat;
    card.mass = mass;
    card.vol = vol;
    card.dp = dp;
    if (k == "bloc") {
      double o[3];
      long n[3];
      for (double& v : o) v = ts_.real("the block origin");
      for (long& v : n) {
        v = ts_.integer("a block count");
        if (v < 1 || v > 100000) fail(kind.line, "block counts must be positive");
      }
      generate_block(parts_, card, o, n);
    } else if (k == "sphe") {
      double c[3];
      for (double& v : c) v = ts_.real("the sphere centre");
      const long nr = ts_.integer("the sphere radius in spacings");
      if (nr < 1 || nr > 10000) fail(kind.line, "sphere radius (in spacings) must lie in 1..10000");
      generate_sphere(parts_, card, c, nr);
    } else {
      // Extension: 'part cyli comID matID density dp cx cy z0 R L' - a cylinder along z,
      // axis through (cx, cy), from z0 to z0 + L, radius R, on the lattice of spacing dp.
      const double cx = ts_.real("the cylinder axis x"), cy = ts_.real("the cylinder axis y");
      const double z0 = ts_.real("the cylinder base z");
      const double radius = ts_.real("the cylinder radius"), length = ts_.real("the cylinder length");
      if (!(radius > 0.0) || !(length > 0.0)) fail(kind.line, "cylinder radius and length must be positive");
      generate_cylinder(parts_, card, cx, cy, z0, radius, length);
    }
  } else {
    fail(kind.line, "unknown particle card '" + kind.text + "' (poin, bloc, sphe or cyli)");
  }
  Body& back = m_.bodies.back();
  back.count = parts_.count() - back.first;
  if (back.count == 0) fail(kind.line, "particle card generated no particles");
}

void Reader::read_velocities(const Token& key) {
  need_counts(key, true, false, false);
  for (;;) {
    const Token t = ts_.next();
    const std::string k = key4(t.text);
    if (k == "endv") return;
    double v[3];
    if (k == "node") {
      const long pid = ts_.integer("a particle id");
      const int p = particle_index(t, pid);
      if (p >= parts_.count()) fail(t.line, "velocity for particle " + std::to_string(pid) + " before it is defined");
      for (double& c : v) c = ts_.real("a velocity");
      for (int a = 0; a < 3; ++a) m_.particles.v[3 * size_t(p) + a] = v[a];
    } else if (k == "body") {
      const int ib = body_index(t, ts_.integer("a body number"));
      for (double& c : v) c = ts_.real("a velocity");
      const Body& b = m_.bodies[size_t(ib)];
      for (int p = b.first; p < b.first + b.count; ++p)
        for (int a = 0; a < 3; ++a) m_.particles.v[3 * size_t(p) + a] = v[a];
    } else {
      fail(t.line, "in 'velo': expected 'node', 'body' or 'endv', found '" + t.text + "'");
    }
  }
}

void Reader::read_loads(const Token& key) {
  need_counts(key, true, false, false);
  for (;;) {
    const Token t = ts_.next();
    const std::string k = key4(t.text);
    if (k == "endl") return;
    double f[3];
    if (k == "node" || k == "body") {
      Particles& P = m_.particles;
      if (P.fext.empty()) P.fext.assign(3 * size_t(P.np), 0.0);
      m_.has_loads = true;
      int first, count;
      if (k == "node") {
        const long pid = ts_.integer("a particle id");
        first = particle_index(t, pid);
        if (first >= parts_.count()) fail(t.line, "load on particle " + std::to_string(pid) + " before it is defined");
        count = 1;
      } else {
        const Body& b = m_.bodies[size_t(body_index(t, ts_.integer("a body number")))];
        first = b.first;
        count = b.count;
      }
      for (double& c : f) c = ts_.real("a force");
      for (int p = first; p < first + count; ++p)
        for (int a = 0; a < 3; ++a) P.fext[3 * size_t(p) + a] = P.fext[3 * size_t(p) + a] + f[a];
    } else if (k == "grav") {
      const int ib = body_index(t, ts_.integer("a body number"));
      for (double& c : f) c = ts_.real("an acceleration");
      for (int a = 0; a < 3; ++a) m_.bodies[size_t(ib)].gravity[a] = f[a];
      m_.has_gravity = true;
    } else {
      fail(t.line, "in 'load': expected 'node', 'body', 'grav' or 'endl', found '" + t.text + "'");
    }
  }
}

void Reader::finish(int line) {
  if (m_.nbmp < 0) fail(line, "no 'nbmp' (number of particles) before 'endi'");
  if (m_.nmat < 0) fail(line, "no 'nmat' (number of materials) before 'endi'");
  if (parts_.count() != m_.nbmp)
    fail(line, "'nbmp' = " + std::to_string(m_.nbmp) + " but the particle cards define " + std::to_string(parts_.count()));
  if (m_.nbbo >= 0 && int(m_.bodies.size()) != m_.nbbo)
    fail(line, "'nbbo' = " + std::to_string(m_.nbbo) + " but " + std::to_string(m_.bodies.size()) + " particle cards were read");
  for (int i = 0; i < m_.nmat; ++i)
    if (m_.mats[size_t(i)].type == 0) fail(line, "material " + std::to_string(i + 1) + " has no 'mate' card");
  for (int a = 0; a < 3; ++a)
    if (!m_.box_set[a]) fail(line, std::string("no grid box along ") + char('x' + a) + " (spx/spy/spz or grid)");
  if (!(m_.dcell > 0.0)) fail(line, "no cell size ('dcel')");
  if (!(m_.endtime > 0.0)) fail(line, "no end time ('endt')");
  if (m_.contact && m_.nbco != 2) fail(m_.contact_line, "'cont' needs two components ('nbco 2')");
  if (m_.contact && m_.scheme == SCHEME_USL)
    m_.warnings.push_back("cont with USL: bodies rebounding from a contact vibrate in free flight, and USL "
                          "(light nodes in the strain rate) tends to diverge there; MUSL or USF are safer");
  if (m_.rpttime <= 0.0) m_.rpttime = m_.outtime;
  // Grid size: whole cells per axis, the node count and the memory of the run.
  double nodes = 1.0;
  for (int a = 0; a < 3; ++a) {
    const int at = std::max(box_line_[a], dcell_line_);
    const double n = std::floor((m_.box_hi[a] - m_.box_lo[a]) / m_.dcell + 0.5);
    if (!(n >= 1.0)) fail(at, std::string("grid box along ") + char('x' + a) + " is shorter than half a cell");
    if (!(n <= 1.0e6)) fail(at, std::string("grid box along ") + char('x' + a) + " has more than 1000000 cells");
    nodes *= n + 1.0;
  }
  {
    const int at = std::max({box_line_[0], box_line_[1], box_line_[2], dcell_line_});
    if (nodes > kMaxNodes)
      fail(at, "grid of " + std::to_string(long(nodes)) + " nodes exceeds the limit of " + std::to_string(long(kMaxNodes)));
    const double need = nodes * kBytesPerNode + double(m_.nbmp) * kBytesPerParticle, budget = memory_budget_;
    if (need > budget)
      fail(at, "grid of " + std::to_string(long(nodes)) + " nodes and " + std::to_string(m_.nbmp) +
                   " particles need about " + megabytes(need) + ", more than the " + megabytes(budget) +
                   " of memory available");
  }
  for (int a = 0; a < 3; ++a) {
    const double n = (m_.box_hi[a] - m_.box_lo[a]) / m_.dcell;
    if (std::fabs(n - std::floor(n + 0.5)) > 1e-6 * n)
      m_.warnings.push_back(std::string("box length along ") + char('x' + a) +
                            " is not a whole number of cells; rounded to " + std::to_string(long(std::floor(n + 0.5))));
  }
  // Explosives: every hiex and null material needs an EOS, hiex a detonation point.
  bool hiex = false;
  for (int i = 0; i < m_.nmat; ++i) {
    MaterialParams& mp = m_.mats[size_t(i)];
    if ((mp.type == MAT_HIEX || mp.type == MAT_NULL) && mp.eos_type == EOS_NONE)
      fail(line, "material " + std::to_string(i + 1) + " (" + material_keyword(mp.type) +
                     ") needs an equation of state ('seos')");
    if (mp.type == MAT_HIEX) {
      if (m_.deto.empty()) fail(line, "material " + std::to_string(i + 1) + " (hiex) needs a detonation point ('deto')");
      mp.burn_width = 1.5 * m_.dcell;
      hiex = true;
    }
  }
  if (!m_.deto.empty() && !hiex) m_.warnings.push_back("'deto' points given but no hiex material: ignored");
  // Initial internal energy from E0 (per unit initial volume).
  Particles& P = m_.particles;
  if (hiex) {
    // Lighting time: distance from the initial position to the nearest detonation point / D.
    P.tlight.assign(size_t(P.np), 0.0);
    const size_t nd = m_.deto.size() / 3;
    for (int p = 0; p < P.np; ++p) {
      const MaterialParams& mp = m_.mats[size_t(P.mat[p])];
      if (mp.type != MAT_HIEX) continue;
      const double* x = &P.x[3 * size_t(p)];
      double dmin = 0.0;
      for (size_t k = 0; k < nd; ++k) {
        const double dx = x[0] - m_.deto[3 * k], dy = x[1] - m_.deto[3 * k + 1], dz = x[2] - m_.deto[3 * k + 2];
        const double d = std::sqrt((dx * dx + dy * dy) + dz * dz);
        if (k == 0 || d < dmin) dmin = d;
      }
      P.tlight[size_t(p)] = dmin / mp.det_vel;
    }
  }
  if (m_.has_bulk) P.qv.assign(size_t(P.np), 0.0);
  // pt2d: TecPlot output only for the particles whose initial position lies in the box
  // (the original marks them as they are generated).
  if (m_.has_pt2d) {
    m_.tec_skip.assign(size_t(P.np), 0);
    for (int p = 0; p < P.np; ++p) {
      const double* x = &P.x[3 * size_t(p)];
      bool in = true;
      for (int a = 0; a < 3; ++a) in = in && x[a] >= m_.pt2d[2 * a] && x[a] <= m_.pt2d[2 * a + 1];
      m_.tec_skip[size_t(p)] = in ? 0 : 1;
    }
  }
  bool thermal = false;
  for (const auto& mp : m_.mats) thermal = thermal || mp.type == MAT_JOHN || mp.type == MAT_JCF;
  if (thermal) P.temp.assign(size_t(P.np), 0.0);
  double c_max = 0.0, rho_sum = 0.0;
  for (const auto& mp : m_.mats) {
    c_max = std::max(c_max, mp.wave_speed);
    rho_sum += mp.rho0;
  }
  for (int p = 0; p < P.np; ++p) {
    const MaterialParams& mp = m_.mats[size_t(P.mat[p])];
    if (mp.eos_type != EOS_NONE) P.ie[p] = mp.eos_e0 * (P.mass[p] / mp.rho0);
    if (thermal) P.temp[p] = mp.t_room;
  }
  // GIMP particle half-size lp: half the spacing of bloc/sphe/cyli particles, half the
  // cube root of the volume of poin particles; at most h/2 (the 27-node stencil).
  if (m_.gimp) {
    P.psize.assign(size_t(P.np), 0.0);
    bool clamped = false;
    for (const Body& b : m_.bodies)
      for (int p = b.first; p < b.first + b.count; ++p) {
        double lp = b.spacing > 0.0 ? 0.5 * b.spacing : 0.5 * std::pow(P.vol[p], 1.0 / 3.0);
        if (lp > 0.5 * m_.dcell) {
          lp = 0.5 * m_.dcell;
          clamped = true;
        }
        P.psize[p] = lp;
      }
    if (clamped) m_.warnings.push_back("gimp: particles larger than the cell size take half a cell as their half-size");
    for (int a = 0; a < 3; ++a)
      if (std::floor((m_.box_hi[a] - m_.box_lo[a]) / m_.dcell + 0.5) < 2.0)
        fail(line, "'gimp' needs at least two cells along each axis");
  }
  // dt = dtscale * h / c_max (the dilatational wave speed, D for hiex, c for null), fixed
  // for the run as in the original. With bulk viscosity the stable step of a material at
  // rest is h / (Q + sqrt(Q^2 + c^2)) with Q = q2 c: dt = dtscale h / (c_max (q2 + sqrt(1 + q2^2))).
  if (m_.has_bulk)
    m_.dt = (m_.dtscale * m_.dcell) / (c_max * (m_.bulk_q2 + std::sqrt(1.0 + m_.bulk_q2 * m_.bulk_q2)));
  else
    m_.dt = m_.dtscale * m_.dcell / c_max;
  if (!(m_.dt > 0.0) || !std::isfinite(m_.dt))
    fail(std::max(dcell_line_, line), "time step dtscale * dcel / wave speed is not a positive finite number");
  m_.mass_cutoff = 1.0e-5 * (rho_sum / double(m_.nmat)) * ((m_.dcell * m_.dcell) * m_.dcell);
  // Base name: the deck's file name up to its first '.'.
  std::string base = m_.deck_path;
  const size_t slash = base.find_last_of('/');
  if (slash != std::string::npos) base = base.substr(slash + 1);
  const size_t dot = base.find('.');
  if (dot != std::string::npos && dot > 0) base = base.substr(0, dot);
  m_.base_name = base.empty() ? "mpm3d" : base;
}

}  // namespace

Model read_deck(const std::string& path, double memory_budget) {
  return Reader(TokenStream::from_file(path), memory_budget).read();
}

Model read_deck_text(const std::string& text, const std::string& name, double memory_budget) {
  return Reader(TokenStream::from_string(text, name), memory_budget).read();
}

}  // namespace mpm3d
