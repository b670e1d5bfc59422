#include "data_out.hpp"

#include <hdf5.h>

#include "h5_quiet.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "checkpoint.hpp"
#include "constitution.hpp"

namespace mpm3d {

std::string fortran_e12_4(double v) {
  char buf[64];
  if (v == 0.0 || !std::isfinite(v)) {
    if (!std::isfinite(v)) std::snprintf(buf, sizeof buf, "%12s", std::isnan(v) ? "NaN" : (v > 0 ? "Infinity" : "-Infinity"));
    else std::snprintf(buf, sizeof buf, "  0.0000E+00");
    return buf;
  }
  char e[32];
  std::snprintf(e, sizeof e, "%.3E", std::fabs(v));  // d.dddE+xx
  const int exponent = std::atoi(e + 6) + 1;
  std::snprintf(buf, sizeof buf, "%s0.%c%c%c%cE%c%02d", v < 0 ? "-" : "", e[0], e[2], e[3], e[4],
                exponent < 0 ? '-' : '+', std::abs(exponent));
  std::string s = buf;
  if (s.size() < 12) s.insert(0, 12 - s.size(), ' ');
  return s;
}

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
double var_pres(const Model& m, int p) { return pressure(&m.particles.sig[6 * size_t(p)]); }
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
double var_sspd(const Model& m, int p) {
  const MaterialParams& mp = mat_of(m, p);
  double k = mp.lambda + (2.0 / 3.0) * mp.shear;
  if (mp.eos_type == EOS_MIE_GRUNEISEN) k = mp.rho0 * (mp.eos[0] * mp.eos[0]);
  else if (mp.eos_type == EOS_LINEAR) k = mp.eos[1];
  const double modulus = k + (4.0 / 3.0) * mp.shear;
  const double rho = m.particles.density(p);
  if (!(modulus > 0.0) || !(rho > 0.0)) return mp.wave_speed;
  return std::sqrt(modulus / rho);
}

}  // namespace

const std::vector<OutputVariable>& output_variables() {
  static const std::vector<OutputVariable> vars = {
      {"seqv", var_seqv}, {"epef", var_epef}, {"mat", var_mat},   {"pres", var_pres}, {"volu", var_volu},
      {"engk", var_engk}, {"engi", var_engi}, {"velx", var_velx}, {"vely", var_vely}, {"velz", var_velz},
      {"cels", var_cels}, {"fail", var_fail}, {"sspd", var_sspd}, {"damg", var_damg}};
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

namespace {

struct H5File {
  hid_t id;
  ~H5File() { if (id >= 0) H5Fclose(id); }
};

void check(herr_t s, const char* what) {
  if (s < 0) throw std::runtime_error(std::string("HDF5: cannot write ") + what);
}

// A per-particle array (ncomp values each) in deck order: the order of every output file,
// whatever the solver's storage order (Particles::id; at = stored_index).
template <class T>
std::vector<T> deck_ordered(const std::vector<T>& a, int ncomp, const std::vector<int>& at) {
  std::vector<T> out(a.size());
  gather_rows(a.data(), ncomp, int(at.size()), [&](int i) { return at[size_t(i)]; }, out.data());
  return out;
}

void write_dataset(hid_t group, const char* name, hid_t type, const void* data, hsize_t rows, hsize_t cols) {
  hsize_t dims[2] = {rows, cols};
  hid_t space = H5Screate_simple(cols ? 2 : 1, dims, nullptr);
  hid_t ds = H5Dcreate2(group, name, type, space, H5P_DEFAULT, H5Untimed().dataset, H5P_DEFAULT);
  herr_t st = ds < 0 ? -1 : H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  if (ds >= 0) H5Dclose(ds);
  H5Sclose(space);
  check(st, name);
}

void write_attr(hid_t obj, const char* name, hid_t type, const void* v) {
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  herr_t st = a < 0 ? -1 : H5Awrite(a, type, v);
  if (a >= 0) H5Aclose(a);
  H5Sclose(space);
  check(st, name);
}

}  // namespace

void write_state_h5(const std::string& path, const Model& m, double time, long step, double dt) {
  const std::string tmp = path + ".tmp";
  const H5ErrorSilencer quiet;  // our own messages instead; the caller's handler is restored
  {
    H5File f{H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5Untimed().file, H5P_DEFAULT)};
    if (f.id < 0) throw std::runtime_error("cannot create the state file " + path);
    hid_t g = H5Gcreate2(f.id, "/particles", H5P_DEFAULT, H5Untimed().group, H5P_DEFAULT);
    if (g < 0) throw std::runtime_error("cannot create /particles in " + path);
    const Particles& P = m.particles;
    const hsize_t n = hsize_t(P.np);
    const std::vector<int> at = stored_index(P);
    std::vector<double> rho(P.np);
    std::vector<int> mat(P.np), body(P.np);
    for (int i = 0; i < P.np; ++i) {
      const size_t p = size_t(at[size_t(i)]);
      rho[size_t(i)] = P.mass[p] / P.vol[p];
      mat[size_t(i)] = P.mat[p] + 1;
      body[size_t(i)] = P.body[p] + 1;
    }
    try {
      write_dataset(g, "position", H5T_NATIVE_DOUBLE, deck_ordered(P.x, 3, at).data(), n, 3);
      write_dataset(g, "velocity", H5T_NATIVE_DOUBLE, deck_ordered(P.v, 3, at).data(), n, 3);
      write_dataset(g, "stress", H5T_NATIVE_DOUBLE, deck_ordered(P.sig, 6, at).data(), n, 6);
      write_dataset(g, "mass", H5T_NATIVE_DOUBLE, deck_ordered(P.mass, 1, at).data(), n, 0);
      write_dataset(g, "volume", H5T_NATIVE_DOUBLE, deck_ordered(P.vol, 1, at).data(), n, 0);
      write_dataset(g, "density", H5T_NATIVE_DOUBLE, rho.data(), n, 0);
      write_dataset(g, "epeff", H5T_NATIVE_DOUBLE, deck_ordered(P.epeff, 1, at).data(), n, 0);
      write_dataset(g, "internal_energy", H5T_NATIVE_DOUBLE, deck_ordered(P.ie, 1, at).data(), n, 0);
      if (!P.temp.empty())
        write_dataset(g, "temperature", H5T_NATIVE_DOUBLE, deck_ordered(P.temp, 1, at).data(), n, 0);
      write_dataset(g, "material", H5T_NATIVE_INT, mat.data(), n, 0);
      write_dataset(g, "body", H5T_NATIVE_INT, body.data(), n, 0);
      write_attr(g, "time", H5T_NATIVE_DOUBLE, &time);
      write_attr(g, "step", H5T_NATIVE_LONG, &step);
      write_attr(g, "dt", H5T_NATIVE_DOUBLE, &dt);
    } catch (...) {
      H5Gclose(g);
      std::remove(tmp.c_str());
      throw;
    }
    H5Gclose(g);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write the state file " + path);
  }
}

// ---------------------------------------------------------------- HDF5 + XDMF series

namespace {

long long file_size(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 ? (long long)st.st_size : -1;
}

std::string xml_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '&') r += "&amp;";
    else if (c == '<') r += "&lt;";
    else if (c == '>') r += "&gt;";
    else if (c == '"') r += "&quot;";
    else r += c;
  }
  return r;
}

}  // namespace

void H5Series::open(const Model& m, const std::string& dir, const std::vector<double>& resume_times) {
  dir_ = dir;
  h5_ = m.base_name + "_anim.h5";
  xdmf_ = m.base_name + "_anim.xdmf";
  vars_ = m.anim_vars;
  np_ = m.particles.np;
  times_.clear();
  first_ = 0;
  const H5ErrorSilencer quiet;
  const std::string path = h5_path();
  if (!resume_times.empty() && file_size(path) > 0) {
    // Restart: keep the frames written before the checkpoint, drop any written after it.
    H5File f{H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)};
    // Only a series whose frames are those of the checkpoint is continued (not a stale file
    // of another run).
    bool same = f.id >= 0;
    for (size_t k = 0; same && k < resume_times.size(); ++k) {
      const std::string g = "/frames/" + std::to_string(k);
      double t = -1.0;
      same = H5Lexists(f.id, "/frames", H5P_DEFAULT) > 0 && H5Lexists(f.id, g.c_str(), H5P_DEFAULT) > 0 &&
             H5Aexists_by_name(f.id, g.c_str(), "time", H5P_DEFAULT) > 0;
      if (same) {
        hid_t a = H5Aopen_by_name(f.id, g.c_str(), "time", H5P_DEFAULT, H5P_DEFAULT);
        same = a >= 0 && H5Aread(a, H5T_NATIVE_DOUBLE, &t) >= 0 && t == resume_times[k];
        if (a >= 0) H5Aclose(a);
      }
    }
    if (same) {
      times_ = resume_times;
      if (H5Lexists(f.id, "/frames", H5P_DEFAULT) > 0) {
        for (size_t k = times_.size();; ++k) {
          const std::string g = "/frames/" + std::to_string(k);
          if (H5Lexists(f.id, g.c_str(), H5P_DEFAULT) <= 0) break;
          H5Ldelete(f.id, g.c_str(), H5P_DEFAULT);
        }
      }
      return;
    }
  }
  // New file (or a restart whose earlier series is gone: frames before it are not listed).
  first_ = resume_times.size();
  times_ = resume_times;
  H5File f{H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5Untimed().file, H5P_DEFAULT)};
  if (f.id < 0) throw std::runtime_error("cannot create " + path);
  hid_t g = H5Gcreate2(f.id, "/frames", H5P_DEFAULT, H5Untimed().group, H5P_DEFAULT);
  if (g < 0) throw std::runtime_error("cannot write " + path);
  H5Gclose(g);
}

void H5Series::frame(const Model& m, double time, long step) {
  const H5ErrorSilencer quiet;
  const std::string path = h5_path();
  const size_t k = times_.size();
  {
    H5File f{H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)};
    if (f.id < 0) throw std::runtime_error("cannot open " + path);
    if (H5Lexists(f.id, "/frames", H5P_DEFAULT) <= 0) {
      hid_t g0 = H5Gcreate2(f.id, "/frames", H5P_DEFAULT, H5Untimed().group, H5P_DEFAULT);
      if (g0 < 0) throw std::runtime_error("cannot write " + path);
      H5Gclose(g0);
    }
    const std::string name = "/frames/" + std::to_string(k);
    if (H5Lexists(f.id, name.c_str(), H5P_DEFAULT) > 0) H5Ldelete(f.id, name.c_str(), H5P_DEFAULT);
    hid_t g = H5Gcreate2(f.id, name.c_str(), H5P_DEFAULT, H5Untimed().group, H5P_DEFAULT);
    if (g < 0) throw std::runtime_error("cannot write " + path);
    try {
      const Particles& P = m.particles;
      const hsize_t n = hsize_t(P.np);
      const std::vector<int> at = stored_index(P);
      write_dataset(g, "position", H5T_NATIVE_DOUBLE, deck_ordered(P.x, 3, at).data(), n, 3);
      std::vector<double> buf(size_t(P.np));
      for (const auto& v : vars_) {
        const ParticleVarFn fn = output_variable(v);
        for (int i = 0; i < P.np; ++i) buf[size_t(i)] = fn(m, at[size_t(i)]);
        write_dataset(g, v.c_str(), H5T_NATIVE_DOUBLE, buf.data(), n, 0);
      }
      write_attr(g, "time", H5T_NATIVE_DOUBLE, &time);
      write_attr(g, "step", H5T_NATIVE_LONG, &step);
    } catch (...) {
      H5Gclose(g);
      throw;
    }
    H5Gclose(g);
  }
  times_.push_back(time);
  write_xdmf();
}

void H5Series::write_xdmf() {
  const std::string path = xdmf_path(), tmp = path + ".tmp";
  FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  const std::string h5 = xml_escape(h5_);
  std::fprintf(f, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
                  "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  for (size_t k = first_; k < times_.size(); ++k) {
    const std::string g = h5 + ":/frames/" + std::to_string(k);
    std::fprintf(f, "   <Grid Name=\"frame_%zu\" GridType=\"Uniform\">\n    <Time Value=\"%.17g\"/>\n", k, times_[k]);
    std::fprintf(f, "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%d\" NodesPerElement=\"1\"/>\n", np_);
    std::fprintf(f, "    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\"%d 3\" NumberType=\"Float\" "
                    "Precision=\"8\" Format=\"HDF\">%s/position</DataItem>\n    </Geometry>\n", np_, g.c_str());
    for (const auto& v : vars_)
      std::fprintf(f, "    <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">\n     <DataItem "
                      "Dimensions=\"%d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s/%s</DataItem>\n"
                      "    </Attribute>\n", v.c_str(), np_, g.c_str(), v.c_str());
    std::fprintf(f, "   </Grid>\n");
  }
  std::fprintf(f, "  </Grid>\n </Domain>\n</Xdmf>\n");
  const bool ok = std::fflush(f) == 0 && !std::ferror(f);
  std::fclose(f);
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write " + path);
  }
}

// ---------------------------------------------------------------- legacy files

LegacyOutput::~LegacyOutput() { close(); }

FILE* LegacyOutput::create(const std::string& name, const OutputSchedule* resume, bool& appended) {
  const std::string path = dir_ + "/" + name;
  appended = false;
  if (resume) {
    for (const auto& e : resume->files) {
      if (e.first != name) continue;
      const long long have = file_size(path);
      if (have >= e.second && ::truncate(path.c_str(), off_t(e.second)) == 0) {
        FILE* f = std::fopen(path.c_str(), "a");
        if (!f) throw std::runtime_error("cannot write " + path);
        written.push_back(path);
        appended = true;
        return f;
      }
    }
  }
  FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  written.push_back(path);
  return f;
}

void LegacyOutput::open(const Model& m, const std::string& dir, bool legacy, bool series,
                        const OutputSchedule* resume) {
  dir_ = dir;
  base_ = m.base_name;
  for (const auto& v : m.anim_vars) anim_fn_.push_back(output_variable(v));
  for (const auto& c : m.curves) curve_fn_.push_back(output_variable(c.var));
  if (resume) frame_times_ = resume->frame_times;
  if (legacy) {
    bool app;
    out_ = create(base_ + ".out", resume, app);
    if (app) std::fprintf(out_, "(restarted)\n");
    bool curv_app;
    curv_ = create(base_ + "_curv.dat", resume, curv_app);
    energy_ = create("EnergyPlot.dat", resume, app);
    momentum_ = create("MomentumPlot.dat", resume, app);
    if (m.contact) contact_ = create("ContforcPlot.dat", resume, app);
    if (!curv_app) {
      std::fprintf(curv_, "Time %-12s%-12s", "engk1", "engi1");
      for (const auto& c : m.curves) std::fprintf(curv_, "%-12s", (c.var + std::to_string(c.particle + 1)).c_str());
      std::fprintf(curv_, "\n");
    }
    if (m.tecplot) {
      tec_ = create(base_ + "_anim.dat", resume, app);
      if (!app) {
        std::fprintf(tec_, "TITLE = \"%s\"\nVARIABLES = \"X\", \"Y\", \"Z\"", m.title.c_str());
        for (const auto& v : m.anim_vars) std::fprintf(tec_, ", \"%s\"", v.c_str());
        std::fprintf(tec_, "\n");
      }
    }
    paraview_ = m.paraview;
    if (paraview_)
      for (size_t k = 0; k < frame_times_.size(); ++k)
        pvd_.emplace_back(frame_times_[k], base_ + "_anim_" + std::to_string(k) + ".vtu");
  }
  if (series) {
    series_.open(m, dir, frame_times_);
    written.push_back(series_.h5_path());
    written.push_back(series_.xdmf_path());
  }
}

void LegacyOutput::save_state(OutputSchedule& o) {
  o.frame_times = frame_times_;
  o.files.clear();
  for (FILE* f : {out_, curv_, energy_, momentum_, tec_, contact_}) {
    if (!f) continue;
    std::fflush(f);
  }
  const std::pair<FILE*, std::string> named[] = {{out_, base_ + ".out"},
                                                 {curv_, base_ + "_curv.dat"},
                                                 {energy_, "EnergyPlot.dat"},
                                                 {momentum_, "MomentumPlot.dat"},
                                                 {tec_, base_ + "_anim.dat"},
                                                 {contact_, "ContforcPlot.dat"}};
  for (const auto& e : named)
    if (e.first) o.files.emplace_back(e.second, (long long)std::ftell(e.first));
}

void LegacyOutput::log(const std::string& line) {
  if (out_) std::fprintf(out_, "%s\n", line.c_str());
}

void LegacyOutput::step(const Model& m, double time, double ke, double ie, const double mom[3]) {
  if (!curv_) return;
  const std::string t = fortran_e12_4(time);
  std::fprintf(energy_, "%s%s%s%s\n", t.c_str(), fortran_e12_4(ke + ie).c_str(), fortran_e12_4(ke).c_str(),
               fortran_e12_4(ie).c_str());
  std::fprintf(momentum_, "%s%s%s%s\n", t.c_str(), fortran_e12_4(mom[0]).c_str(), fortran_e12_4(mom[1]).c_str(),
               fortran_e12_4(mom[2]).c_str());
  std::fprintf(curv_, "%s%s%s", t.c_str(), fortran_e12_4(ke).c_str(), fortran_e12_4(ie).c_str());
  // Stored index of each curve's particle (deck number m.curves[c].particle), found again
  // whenever the storage order is not the one it was found in (a restart).
  const Particles& P = m.particles;
  if (curve_at_.size() != m.curves.size()) curve_at_.assign(m.curves.size(), -1);
  for (size_t c = 0; c < m.curves.size(); ++c) {
    int& p = curve_at_[c];
    if (p < 0 || p >= P.np || P.deck_number(p) != m.curves[c].particle) p = stored_index(P)[size_t(m.curves[c].particle)];
    std::fprintf(curv_, "%s", fortran_e12_4(curve_fn_[c](m, p)).c_str());
  }
  std::fprintf(curv_, "\n");
}

void LegacyOutput::contact(double time, const double force[3]) {
  if (!contact_) return;
  // Columns: time, Fx, Fy, Fz (E12.4, as EnergyPlot.dat), the force that component 2 exerts
  // on component 1, summed over the contact nodes of the step.
  std::fprintf(contact_, "%s%s%s%s\n", fortran_e12_4(time).c_str(), fortran_e12_4(force[0]).c_str(),
               fortran_e12_4(force[1]).c_str(), fortran_e12_4(force[2]).c_str());
}

void LegacyOutput::frame(const Model& m, double time, long step) {
  const Particles& P = m.particles;
  const size_t nv = m.anim_vars.size();
  const std::vector<int> at = stored_index(P);  // the files list the particles in deck order
  if (tec_) {
    const bool all = m.tec_skip.empty();  // indexed by deck number
    int n = 0;
    for (int i = 0; i < P.np; ++i) n += all || !m.tec_skip[size_t(i)];
    std::fprintf(tec_, "ZONE T=\"%.6E\" I=%d F=POINT\n", time, n);
    for (int i = 0; i < P.np; ++i) {
      if (!all && m.tec_skip[size_t(i)]) continue;
      const int p = at[size_t(i)];
      const double* x = &P.x[3 * size_t(p)];
      std::fprintf(tec_, "%.6E %.6E %.6E", x[0], x[1], x[2]);
      for (size_t v = 0; v < nv; ++v) std::fprintf(tec_, " %.6E", anim_fn_[v](m, p));
      std::fprintf(tec_, "\n");
    }
  }
  if (paraview_) {
    const std::string name = base_ + "_anim_" + std::to_string(frame_times_.size()) + ".vtu";
    bool app;
    FILE* f = create(name, nullptr, app);
    std::fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                    "<UnstructuredGrid>\n<Piece NumberOfPoints=\"%d\" NumberOfCells=\"%d\">\n<Points>\n"
                    "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n", P.np, P.np);
    for (int i = 0; i < P.np; ++i) {
      const size_t p = size_t(at[size_t(i)]);
      std::fprintf(f, "%.9E %.9E %.9E\n", P.x[3 * p], P.x[3 * p + 1], P.x[3 * p + 2]);
    }
    std::fprintf(f, "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n");
    for (int p = 0; p < P.np; ++p) std::fprintf(f, "%d\n", p);
    std::fprintf(f, "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n");
    for (int p = 0; p < P.np; ++p) std::fprintf(f, "%d\n", p + 1);
    std::fprintf(f, "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for (int p = 0; p < P.np; ++p) std::fprintf(f, "1\n");
    std::fprintf(f, "</DataArray>\n</Cells>\n<PointData>\n");
    for (size_t v = 0; v < nv; ++v) {
      std::fprintf(f, "<DataArray type=\"Float64\" Name=\"%s\" format=\"ascii\">\n", m.anim_vars[v].c_str());
      for (int i = 0; i < P.np; ++i) std::fprintf(f, "%.9E\n", anim_fn_[v](m, at[size_t(i)]));
      std::fprintf(f, "</DataArray>\n");
    }
    std::fprintf(f, "</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    std::fclose(f);
    pvd_.emplace_back(time, name);
    const std::string pvd_path = dir_ + "/" + base_ + "_anim.pvd";
    FILE* pvd = std::fopen((pvd_path + ".tmp").c_str(), "w");
    if (!pvd) throw std::runtime_error("cannot write " + pvd_path);
    std::fprintf(pvd, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n");
    for (const auto& e : pvd_)
      std::fprintf(pvd, "<DataSet timestep=\"%.9E\" part=\"0\" file=\"%s\"/>\n", e.first, e.second.c_str());
    std::fprintf(pvd, "</Collection>\n</VTKFile>\n");
    std::fclose(pvd);
    if (std::rename((pvd_path + ".tmp").c_str(), pvd_path.c_str()) != 0)
      throw std::runtime_error("cannot write " + pvd_path);
  }
  if (series_.is_open()) series_.frame(m, time, step);
  frame_times_.push_back(time);
}

void LegacyOutput::close() {
  for (FILE** f : {&out_, &curv_, &energy_, &momentum_, &tec_, &contact_})
    if (*f) {
      std::fclose(*f);
      *f = nullptr;
    }
}

}  // namespace mpm3d
