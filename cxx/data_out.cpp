#include "data_out.hpp"

#include <hdf5.h>

#include "h5_quiet.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

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

double particle_variable(const Model& m, const std::string& var, int p) {
  const Particles& P = m.particles;
  const double* s = &P.sig[6 * size_t(p)];
  const double* v = &P.v[3 * size_t(p)];
  const MaterialParams& mp = m.mats[size_t(P.mat[p])];
  const double pres = -((s[0] + s[1]) + s[2]) / 3.0;
  if (var == "seqv") {
    const double d0 = s[0] + pres, d1 = s[1] + pres, d2 = s[2] + pres;
    return std::sqrt(1.5 * ((d0 * d0 + d1 * d1 + d2 * d2) + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
  }
  if (var == "epef") return P.epeff[p];
  if (var == "mat") return double(P.mat[p] + 1);
  if (var == "pres") return pres;
  if (var == "volu") return P.vol[p];
  if (var == "engk") return 0.5 * P.mass[p] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (var == "engi") return P.ie[p];
  if (var == "velx") return v[0];
  if (var == "vely") return v[1];
  if (var == "velz") return v[2];
  if (var == "cels") return P.temp.empty() ? 0.0 : P.temp[p];
  if (var == "fail") return (mp.fail_strain > 0.0 && P.epeff[p] >= mp.fail_strain) ? 1.0 : 0.0;
  if (var == "damg") return mp.fail_strain > 0.0 ? std::min(1.0, P.epeff[p] / mp.fail_strain) : 0.0;
  if (var == "sspd") return std::sqrt((mp.lambda + 2.0 * mp.shear) / P.density(p));
  return 0.0;
}

namespace {

struct H5File {
  hid_t id;
  ~H5File() { if (id >= 0) H5Fclose(id); }
};

void check(herr_t s, const char* what) {
  if (s < 0) throw std::runtime_error(std::string("HDF5: cannot write ") + what);
}

void write_dataset(hid_t group, const char* name, hid_t type, const void* data, hsize_t rows, hsize_t cols) {
  hsize_t dims[2] = {rows, cols};
  hid_t space = H5Screate_simple(cols ? 2 : 1, dims, nullptr);
  hid_t ds = H5Dcreate2(group, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
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
    H5File f{H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT)};
    if (f.id < 0) throw std::runtime_error("cannot create the state file " + path);
    hid_t g = H5Gcreate2(f.id, "/particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) throw std::runtime_error("cannot create /particles in " + path);
    const Particles& P = m.particles;
    const hsize_t n = hsize_t(P.np);
    std::vector<double> rho(P.np);
    for (int p = 0; p < P.np; ++p) rho[size_t(p)] = P.mass[size_t(p)] / P.vol[size_t(p)];
    std::vector<int> mat(P.mat.begin(), P.mat.end()), body(P.body.begin(), P.body.end());
    for (int& v : mat) v += 1;
    for (int& v : body) v += 1;
    try {
      write_dataset(g, "position", H5T_NATIVE_DOUBLE, P.x.data(), n, 3);
      write_dataset(g, "velocity", H5T_NATIVE_DOUBLE, P.v.data(), n, 3);
      write_dataset(g, "stress", H5T_NATIVE_DOUBLE, P.sig.data(), n, 6);
      write_dataset(g, "mass", H5T_NATIVE_DOUBLE, P.mass.data(), n, 0);
      write_dataset(g, "volume", H5T_NATIVE_DOUBLE, P.vol.data(), n, 0);
      write_dataset(g, "density", H5T_NATIVE_DOUBLE, rho.data(), n, 0);
      write_dataset(g, "epeff", H5T_NATIVE_DOUBLE, P.epeff.data(), n, 0);
      write_dataset(g, "internal_energy", H5T_NATIVE_DOUBLE, P.ie.data(), n, 0);
      if (!P.temp.empty()) write_dataset(g, "temperature", H5T_NATIVE_DOUBLE, P.temp.data(), n, 0);
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

LegacyOutput::~LegacyOutput() { close(); }

FILE* LegacyOutput::create(const std::string& name) {
  const std::string path = dir_ + "/" + name;
  FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  written.push_back(path);
  return f;
}

void LegacyOutput::open(const Model& m, const std::string& dir) {
  dir_ = dir;
  base_ = m.base_name;
  out_ = create(base_ + ".out");
  curv_ = create(base_ + "_curv.dat");
  energy_ = create("EnergyPlot.dat");
  momentum_ = create("MomentumPlot.dat");
  if (m.contact) contact_ = create("ContforcPlot.dat");
  std::fprintf(curv_, "Time %-12s%-12s", "engk1", "engi1");
  for (const auto& c : m.curves) std::fprintf(curv_, "%-12s", (c.var + std::to_string(c.particle + 1)).c_str());
  std::fprintf(curv_, "\n");
  if (m.tecplot) {
    tec_ = create(base_ + "_anim.dat");
    std::fprintf(tec_, "TITLE = \"%s\"\nVARIABLES = \"X\", \"Y\", \"Z\"", m.title.c_str());
    for (const auto& v : m.anim_vars) std::fprintf(tec_, ", \"%s\"", v.c_str());
    std::fprintf(tec_, "\n");
  }
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
  for (const auto& c : m.curves) std::fprintf(curv_, "%s", fortran_e12_4(particle_variable(m, c.var, c.particle)).c_str());
  std::fprintf(curv_, "\n");
}

void LegacyOutput::contact(double time, const double force[3]) {
  if (!contact_) return;
  // Columns: time, Fx, Fy, Fz (E12.4, as EnergyPlot.dat), the force that component 2 exerts
  // on component 1, summed over the contact nodes of the step.
  std::fprintf(contact_, "%s%s%s%s\n", fortran_e12_4(time).c_str(), fortran_e12_4(force[0]).c_str(),
               fortran_e12_4(force[1]).c_str(), fortran_e12_4(force[2]).c_str());
}

static bool in_pt2d(const Model& m, int p) {
  if (!m.has_pt2d) return true;
  const double* x = &m.particles.x[3 * size_t(p)];
  return x[0] >= m.pt2d[0] && x[0] <= m.pt2d[1] && x[1] >= m.pt2d[2] && x[1] <= m.pt2d[3] &&
         x[2] >= m.pt2d[4] && x[2] <= m.pt2d[5];
}

void LegacyOutput::frame(const Model& m, double time) {
  const Particles& P = m.particles;
  if (tec_) {
    int n = 0;
    for (int p = 0; p < P.np; ++p) n += in_pt2d(m, p);
    std::fprintf(tec_, "ZONE T=\"%.6E\" I=%d F=POINT\n", time, n);
    for (int p = 0; p < P.np; ++p) {
      if (!in_pt2d(m, p)) continue;
      const double* x = &P.x[3 * size_t(p)];
      std::fprintf(tec_, "%.6E %.6E %.6E", x[0], x[1], x[2]);
      for (const auto& v : m.anim_vars) std::fprintf(tec_, " %.6E", particle_variable(m, v, p));
      std::fprintf(tec_, "\n");
    }
  }
  if (m.paraview) {
    const std::string name = base_ + "_anim_" + std::to_string(frames_) + ".vtu";
    FILE* f = create(name);
    std::fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                    "<UnstructuredGrid>\n<Piece NumberOfPoints=\"%d\" NumberOfCells=\"%d\">\n<Points>\n"
                    "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n", P.np, P.np);
    for (int p = 0; p < P.np; ++p)
      std::fprintf(f, "%.9E %.9E %.9E\n", P.x[3 * size_t(p)], P.x[3 * size_t(p) + 1], P.x[3 * size_t(p) + 2]);
    std::fprintf(f, "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n");
    for (int p = 0; p < P.np; ++p) std::fprintf(f, "%d\n", p);
    std::fprintf(f, "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n");
    for (int p = 0; p < P.np; ++p) std::fprintf(f, "%d\n", p + 1);
    std::fprintf(f, "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for (int p = 0; p < P.np; ++p) std::fprintf(f, "1\n");
    std::fprintf(f, "</DataArray>\n</Cells>\n<PointData>\n");
    for (const auto& v : m.anim_vars) {
      std::fprintf(f, "<DataArray type=\"Float64\" Name=\"%s\" format=\"ascii\">\n", v.c_str());
      for (int p = 0; p < P.np; ++p) std::fprintf(f, "%.9E\n", particle_variable(m, v, p));
      std::fprintf(f, "</DataArray>\n");
    }
    std::fprintf(f, "</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    std::fclose(f);
    pvd_.emplace_back(time, name);
    FILE* pvd = std::fopen((dir_ + "/" + base_ + "_anim.pvd").c_str(), "w");
    if (!pvd) throw std::runtime_error("cannot write " + dir_ + "/" + base_ + "_anim.pvd");
    std::fprintf(pvd, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n");
    for (const auto& e : pvd_)
      std::fprintf(pvd, "<DataSet timestep=\"%.9E\" part=\"0\" file=\"%s\"/>\n", e.first, e.second.c_str());
    std::fprintf(pvd, "</Collection>\n</VTKFile>\n");
    std::fclose(pvd);
  }
  ++frames_;
}

void LegacyOutput::close() {
  for (FILE** f : {&out_, &curv_, &energy_, &momentum_, &tec_, &contact_})
    if (*f) {
      std::fclose(*f);
      *f = nullptr;
    }
}

}  // namespace mpm3d
