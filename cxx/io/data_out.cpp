#include "io/data_out.hpp"

#include <hdf5.h>

#include "io/h5_write.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "io/output_schedule.hpp"
#include "materials/constitution.hpp"

namespace mpm3d {

std::string fortran_e12_4(double v) {
  char buf[64];
  if (v == 0.0 || !std::isfinite(v)) {
    if (!std::isfinite(v)) std::snprintf(buf, sizeof buf, "%12s", std::isnan(v) ? "NaN" : (v > 0 ? "Infinity" : "-Infinity"));
    else std::snprintf(buf, sizeof buf, "  0.0000E+00");
    return buf;
  }
  // d.ddde+xx by to_chars (printf's "%.3E" digits; every plot line holds several).
  char e[32];
  *std::to_chars(e, e + sizeof e - 1, std::fabs(v), std::chars_format::scientific, 3).ptr = '\0';
  const int exponent = std::atoi(e + 6) + 1;
  const int mag = std::abs(exponent);
  char* c = buf + 12;  // right-aligned in 12: "  0.1326E-03", " -0.3999E+02"
  *c = '\0';
  *--c = char('0' + mag % 10);
  *--c = char('0' + mag / 10 % 10);
  if (mag >= 100) *--c = char('0' + mag / 100);
  *--c = exponent < 0 ? '-' : '+';
  *--c = 'E';
  for (int d : {4, 3, 2, 0}) *--c = e[d];
  *--c = '.';
  *--c = '0';
  if (v < 0) *--c = '-';
  while (c > buf) *--c = ' ';
  return c;
}

void held_curve_values(const Model& m, std::vector<int>& held, std::vector<double>& values) {
  const Particles& P = m.particles;
  const size_t nc = m.curves.size();
  held.resize(nc, -1);
  values.assign(nc, -INFINITY);
  bool missing = false;
  for (size_t c = 0; c < nc; ++c) {
    const int p = held[c];
    if (p >= 0 && p < P.np && P.deck_number(p) == m.curves[c].particle) values[c] = output_variable(m.curves[c].var)(m, p);
    else missing = true;
  }
  if (!missing) return;
  // One pass over the rows for the curves not where they were (few: a search per curve).
  for (int p = 0; p < P.np; ++p) {
    const int deck = P.deck_number(p);
    for (size_t c = 0; c < nc; ++c) {
      if (values[c] != -INFINITY || deck != m.curves[c].particle) continue;
      held[c] = p;
      values[c] = output_variable(m.curves[c].var)(m, p);
    }
  }
}

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
      h5_write_dataset(g, "position", H5T_NATIVE_DOUBLE, deck_ordered(P.x, 3, at).data(), n, 3);
      h5_write_dataset(g, "velocity", H5T_NATIVE_DOUBLE, deck_ordered(P.v, 3, at).data(), n, 3);
      h5_write_dataset(g, "stress", H5T_NATIVE_DOUBLE, deck_ordered(P.sig, 6, at).data(), n, 6);
      h5_write_dataset(g, "mass", H5T_NATIVE_DOUBLE, deck_ordered(P.mass, 1, at).data(), n, 0);
      h5_write_dataset(g, "volume", H5T_NATIVE_DOUBLE, deck_ordered(P.vol, 1, at).data(), n, 0);
      h5_write_dataset(g, "density", H5T_NATIVE_DOUBLE, rho.data(), n, 0);
      h5_write_dataset(g, "epeff", H5T_NATIVE_DOUBLE, deck_ordered(P.epeff, 1, at).data(), n, 0);
      h5_write_dataset(g, "internal_energy", H5T_NATIVE_DOUBLE, deck_ordered(P.ie, 1, at).data(), n, 0);
      if (!P.temp.empty())
        h5_write_dataset(g, "temperature", H5T_NATIVE_DOUBLE, deck_ordered(P.temp, 1, at).data(), n, 0);
      h5_write_dataset(g, "material", H5T_NATIVE_INT, mat.data(), n, 0);
      h5_write_dataset(g, "body", H5T_NATIVE_INT, body.data(), n, 0);
      h5_write_attr(g, "time", H5T_NATIVE_DOUBLE, &time);
      h5_write_attr(g, "step", H5T_NATIVE_LONG, &step);
      h5_write_attr(g, "dt", H5T_NATIVE_DOUBLE, &dt);
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

// ---------------------------------------------------------------- the writers

void flush_file(FILE* f, const std::string& path) {
  errno = 0;
  if (std::fflush(f) == 0 && !std::ferror(f)) return;
  const int e = errno;
  throw std::runtime_error("cannot write " + path + (e ? std::string(": ") + std::strerror(e) : std::string()));
}

FILE* OutputFiles::create(const std::string& name, bool& appended) const {
  const std::string p = path(name);
  appended = false;
  if (resume_) {
    for (const auto& e : resume_->files) {
      if (e.first != name) continue;
      struct stat st;
      const long long have = stat(p.c_str(), &st) == 0 ? (long long)st.st_size : -1;
      if (have >= e.second && ::truncate(p.c_str(), off_t(e.second)) == 0) {
        FILE* f = std::fopen(p.c_str(), "a");
        if (!f) throw std::runtime_error("cannot write " + p);
        appended = true;
        return f;
      }
    }
  }
  return create(name);
}

FILE* OutputFiles::create(const std::string& name) const {
  const std::string p = path(name);
  FILE* f = std::fopen(p.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + p);
  return f;
}

Output::Output() = default;
Output::~Output() { close(); }

void Output::open(const Model& m, const std::string& dir, bool legacy, bool series, const OutputSchedule* resume,
                  bool vtu_binary) {
  const OutputFiles files(dir, resume);
  if (resume) frame_times_ = resume->frame_times;
  for (const auto& c : m.curves) spre_in_curves_ = spre_in_curves_ || c.var == "spre";
  for (const auto& v : m.anim_vars) spre_in_frames_ = spre_in_frames_ || v == "spre";
  // The order of the writers is the order of the files in a checkpoint's record.
  if (legacy) {
    writers_.push_back(make_curve_writer(m, files));
    if (m.tecplot) writers_.push_back(make_tecplot_writer(m, files));
    if (m.contact) writers_.push_back(make_contact_writer(files));
    if (m.paraview) writers_.push_back(make_vtu_writer(m, files, frame_times_, vtu_binary));
  }
  if (series) writers_.push_back(make_h5_series_writer(m, files, frame_times_));
}

void Output::log(const std::string& line) {
  for (auto& w : writers_) w->log(line);
}

void Output::flush() {
  for (auto& w : writers_) w->flush();
}

void Output::step(const Model& m, const StepRecord& s) {
  if (spre_in_curves_ && !writers_.empty()) update_smoothed_pressure(m);
  for (auto& w : writers_) w->step(m, s);
}

void Output::frame(const Model& m, double time, long step) {
  const std::vector<int> at = stored_index(m.particles);
  if (spre_in_frames_) update_smoothed_pressure(m);
  for (auto& w : writers_) w->frame(m, at, time, step);
  frame_times_.push_back(time);
}

void Output::save_state(OutputSchedule& o) {
  o.frame_times = frame_times_;
  o.files.clear();
  for (auto& w : writers_) w->record_sizes(o.files);
}

void Output::close() { writers_.clear(); }

}  // namespace mpm3d
