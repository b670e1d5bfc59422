#include "solver/checkpoint.hpp"

#include <hdf5.h>

#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>

#include "io/h5_quiet.hpp"
#include "solver/simulation.hpp"

namespace mpm3d {

// Every array of Particles must be listed in particle_fields() so checkpoints hold it:
// this fails when one is added without raising kParticleArrays (and listing it).
static_assert(sizeof(Particles) == alignof(std::vector<double>) + kParticleArrays * sizeof(std::vector<double>),
              "Particles gained a member: list it in particle_fields() (cxx/core/particle.cpp) and raise kParticleArrays");

namespace {

// Whether a checkpoint's rules text ("name=value ...") names the rules r. A rule added after
// the checkpoint was written is missing from its text: the run then held our value (0).
bool same_rules(const std::string& written, const StepRules& r) {
  std::istringstream in(written);
  std::map<std::string, std::string> value_of;
  std::string tok;
  while (in >> tok) {
    const size_t eq = tok.find('=');
    if (eq != std::string::npos) value_of[tok.substr(0, eq)] = tok.substr(eq + 1);
  }
  for (int i = 0; i < kRuleCount; ++i) {
    const auto it = value_of.find(kRules[i].name);
    const std::string v = it == value_of.end() ? kRules[i].value[0] : it->second;
    if (v != kRules[i].value[rule_value(r, i)]) return false;
  }
  return true;
}


constexpr const char* kFormat = "mpm3d-checkpoint";
constexpr int kVersion = 1;

struct Id {  // closes an HDF5 object on scope exit
  hid_t id;
  herr_t (*close)(hid_t);
  ~Id() {
    if (id >= 0) close(id);
  }
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("checkpoint " + path + ": " + what);
}

void put(const std::string& path, hid_t obj, const char* name, hid_t type, const void* v, hsize_t n = 0) {
  Id space{n ? H5Screate_simple(1, &n, nullptr) : H5Screate(H5S_SCALAR), H5Sclose};
  Id a{H5Acreate2(obj, name, type, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  if (a.id < 0 || H5Awrite(a.id, type, v) < 0) fail(path, std::string("cannot write ") + name);
}

void put_string(const std::string& path, hid_t obj, const char* name, const std::string& s) {
  Id type{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(type.id, s.size() + 1);
  Id space{H5Screate(H5S_SCALAR), H5Sclose};
  Id a{H5Acreate2(obj, name, type.id, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  if (a.id < 0 || H5Awrite(a.id, type.id, s.c_str()) < 0) fail(path, std::string("cannot write ") + name);
}

// Reads attribute `name` of n values (n = 1: a scalar).
void get(const std::string& path, hid_t obj, const char* name, hid_t type, void* v, hsize_t n = 1) {
  Id a{H5Aopen(obj, name, H5P_DEFAULT), H5Aclose};
  if (a.id < 0) fail(path, std::string("no attribute ") + name);
  Id space{H5Aget_space(a.id), H5Sclose};
  if (H5Sget_simple_extent_npoints(space.id) != hssize_t(n)) fail(path, std::string("attribute ") + name + " has the wrong size");
  if (H5Aread(a.id, type, v) < 0) fail(path, std::string("cannot read ") + name);
}

std::string get_string(const std::string& path, hid_t obj, const char* name) {
  Id a{H5Aopen(obj, name, H5P_DEFAULT), H5Aclose};
  if (a.id < 0) fail(path, std::string("no attribute ") + name);
  Id ftype{H5Aget_type(a.id), H5Tclose};
  if (H5Tget_class(ftype.id) != H5T_STRING) fail(path, std::string("attribute ") + name + " is not a string");
  const size_t n = H5Tget_size(ftype.id);
  std::string s(n, '\0');
  Id mtype{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(mtype.id, n);
  if (H5Aread(a.id, mtype.id, &s[0]) < 0) fail(path, std::string("cannot read ") + name);
  s.resize(s.find('\0') == std::string::npos ? n : s.find('\0'));
  return s;
}

void put_array(const std::string& path, hid_t g, const char* name, hid_t type, const void* data, hsize_t rows,
               hsize_t cols) {
  const hsize_t dims[2] = {rows, cols};
  Id space{H5Screate_simple(cols > 1 ? 2 : 1, dims, nullptr), H5Sclose};
  Id d{H5Dcreate2(g, name, type, space.id, H5P_DEFAULT, H5Untimed().dataset, H5P_DEFAULT), H5Dclose};
  if (d.id < 0 || (rows * cols > 0 && H5Dwrite(d.id, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0))
    fail(path, std::string("cannot write ") + name);
}

// Reads dataset `name` of exactly `count` values into data; false when absent.
bool get_array(const std::string& path, hid_t g, const char* name, hid_t type, void* data, hsize_t count) {
  if (H5Lexists(g, name, H5P_DEFAULT) <= 0) return false;
  Id d{H5Dopen2(g, name, H5P_DEFAULT), H5Dclose};
  if (d.id < 0) fail(path, std::string("cannot open ") + name);
  Id space{H5Dget_space(d.id), H5Sclose};
  if (hsize_t(H5Sget_simple_extent_npoints(space.id)) != count)
    fail(path, std::string("dataset ") + name + " has " + std::to_string(H5Sget_simple_extent_npoints(space.id)) +
                   " values, the model needs " + std::to_string(count));
  if (count > 0 && H5Dread(d.id, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail(path, std::string("cannot read ") + name);
  return true;
}

}  // namespace

void write_checkpoint(const std::string& path, const Simulation& sim, const OutputSchedule& out,
                      const Particles* particles) {
  const Particles& P = particles ? *particles : sim.model.particles;
  const std::string tmp = path + ".tmp";
  const H5ErrorSilencer quiet;
  {
    Id f{H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5Untimed().file, H5P_DEFAULT), H5Fclose};
    if (f.id < 0) fail(path, "cannot create " + tmp);
    try {
      const Model& m = sim.model;
      put_string(path, f.id, "format", kFormat);
      put(path, f.id, "version", H5T_NATIVE_INT, &kVersion);
      put_string(path, f.id, "deck", m.base_name);
      const int counts[3] = {P.np, int(m.bodies.size()), int(m.mats.size())};
      put(path, f.id, "counts", H5T_NATIVE_INT, counts, 3);

      Id s{H5Gcreate2(f.id, "/simulation", H5P_DEFAULT, H5Untimed().group, H5P_DEFAULT), H5Gclose};
      if (s.id < 0) fail(path, "cannot create /simulation");
      put(path, s.id, "step", H5T_NATIVE_LONG, &sim.steps);
      put(path, s.id, "time", H5T_NATIVE_DOUBLE, &sim.time);
      put(path, s.id, "dt", H5T_NATIVE_DOUBLE, &m.dt);
      put(path, s.id, "kinetic_energy", H5T_NATIVE_DOUBLE, &sim.kinetic);
      put(path, s.id, "internal_energy", H5T_NATIVE_DOUBLE, &sim.internal);
      put(path, s.id, "momentum", H5T_NATIVE_DOUBLE, sim.momentum, 3);
      put(path, s.id, "initial_total_energy", H5T_NATIVE_DOUBLE, &sim.initial_total_energy);
      put(path, s.id, "external_work", H5T_NATIVE_DOUBLE, &sim.external_work);
      put(path, s.id, "load_work", H5T_NATIVE_DOUBLE, &sim.load_work);
      put(path, s.id, "particles_outside_grid", H5T_NATIVE_INT, &sim.outside);
      put(path, s.id, "grid_origin", H5T_NATIVE_DOUBLE, sim.grid.origin, 3);
      put(path, s.id, "grid_cell", H5T_NATIVE_DOUBLE, &sim.grid.h);
      put(path, s.id, "grid_cells", H5T_NATIVE_INT, sim.grid.deck_nc, 3);
      put(path, s.id, "patch_cells", H5T_NATIVE_INT, &sim.grid.patch_cells);
      // The rules the run was made with: a restart must keep them (checked on reading).
      put_string(path, s.id, "rules", rules_text(m.rules));
      // The adaptive grid's window on the deck's lattice (the whole box without it).
      put(path, s.id, "grid_window_offset", H5T_NATIVE_INT, sim.grid.off, 3);
      put(path, s.id, "grid_window_cells", H5T_NATIVE_INT, sim.grid.nc, 3);
      // USF with contact: the nodes in contact at the end of the last step (their unit
      // normals, zero elsewhere), which the next step's recontact stage reads.
      if (m.contact && m.scheme == SCHEME_USF)
        put_array(path, s.id, "contact_marks", H5T_NATIVE_DOUBLE, sim.ctx.contact.gnormal, hsize_t(sim.grid.nnode()), 3);

      Id g{H5Gcreate2(f.id, "/particles", H5P_DEFAULT, H5Untimed().group, H5P_DEFAULT), H5Gclose};
      if (g.id < 0) fail(path, "cannot create /particles");
      const hsize_t np = hsize_t(P.np);
      for (const ParticleField& fd : particle_fields(const_cast<Particles&>(P))) {
        if (fd.d && !fd.d->empty()) put_array(path, g.id, fd.name, H5T_NATIVE_DOUBLE, fd.d->data(), np, hsize_t(fd.ncomp));
        if (fd.i && !fd.i->empty()) put_array(path, g.id, fd.name, H5T_NATIVE_INT32, fd.i->data(), np, hsize_t(fd.ncomp));
      }

      Id o{H5Gcreate2(f.id, "/output", H5P_DEFAULT, H5Untimed().group, H5P_DEFAULT), H5Gclose};
      if (o.id < 0) fail(path, "cannot create /output");
      put(path, o.id, "next_output_time", H5T_NATIVE_DOUBLE, &out.next_out);
      put(path, o.id, "next_report_time", H5T_NATIVE_DOUBLE, &out.next_rpt);
      put_array(path, o.id, "frame_times", H5T_NATIVE_DOUBLE, out.frame_times.data(), out.frame_times.size(), 1);
      // Appended text files: names one per line, sizes in the same order.
      std::string names;
      std::vector<long long> sizes;
      for (const auto& e : out.files) {
        names += e.first + "\n";
        sizes.push_back(e.second);
      }
      put_string(path, o.id, "file_names", names);
      put_array(path, o.id, "file_sizes", H5T_NATIVE_LLONG, sizes.data(), sizes.size(), 1);
    } catch (...) {
      std::remove(tmp.c_str());
      throw;
    }
    if (H5Fflush(f.id, H5F_SCOPE_GLOBAL) < 0) {
      std::remove(tmp.c_str());
      fail(path, "cannot write " + tmp);
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    fail(path, "cannot rename " + tmp + " to it");
  }
}

namespace {

hid_t open_checked(const std::string& path) {
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) fail(path, "cannot open (missing, or not an HDF5 file)");
  Id guard{f, H5Fclose};
  if (H5Aexists(f, "format") <= 0 || get_string(path, f, "format") != kFormat) fail(path, "not an mpm3d checkpoint");
  int version = 0;
  get(path, f, "version", H5T_NATIVE_INT, &version);
  if (version != kVersion)
    fail(path, "format version " + std::to_string(version) + ", this program reads " + std::to_string(kVersion));
  guard.id = -1;
  return f;
}

}  // namespace

int checkpoint_patch_cells(const std::string& path) {
  const H5ErrorSilencer quiet;
  Id f{open_checked(path), H5Fclose};
  Id s{H5Gopen2(f.id, "/simulation", H5P_DEFAULT), H5Gclose};
  if (s.id < 0) fail(path, "no /simulation group");
  int pc = 0;
  get(path, s.id, "patch_cells", H5T_NATIVE_INT, &pc);
  if (pc < 1 || pc > 64) fail(path, "bad patch size");
  return pc;
}

bool checkpoint_has_particle_array(const std::string& path, const char* name) {
  const H5ErrorSilencer quiet;
  Id f{open_checked(path), H5Fclose};
  Id g{H5Gopen2(f.id, "/particles", H5P_DEFAULT), H5Gclose};
  return g.id >= 0 && H5Lexists(g.id, name, H5P_DEFAULT) > 0;
}

void read_checkpoint(const std::string& path, Simulation& sim, OutputSchedule& out) {
  const H5ErrorSilencer quiet;
  Id f{open_checked(path), H5Fclose};
  Model& m = sim.model;
  int counts[3];
  get(path, f.id, "counts", H5T_NATIVE_INT, counts, 3);
  const int want[3] = {m.particles.np, int(m.bodies.size()), int(m.mats.size())};
  const char* what[3] = {"particles", "bodies", "materials"};
  for (int k = 0; k < 3; ++k)
    if (counts[k] != want[k])
      fail(path, "written for a model of " + std::to_string(counts[k]) + " " + what[k] + ", the deck has " +
                     std::to_string(want[k]) + " (another deck?)");

  Id s{H5Gopen2(f.id, "/simulation", H5P_DEFAULT), H5Gclose};
  if (s.id < 0) fail(path, "no /simulation group");
  double origin[3], h;
  int nc[3], pc;
  get(path, s.id, "grid_origin", H5T_NATIVE_DOUBLE, origin, 3);
  get(path, s.id, "grid_cell", H5T_NATIVE_DOUBLE, &h);
  get(path, s.id, "grid_cells", H5T_NATIVE_INT, nc, 3);
  get(path, s.id, "patch_cells", H5T_NATIVE_INT, &pc);
  int woff[3], wnc[3];
  get(path, s.id, "grid_window_offset", H5T_NATIVE_INT, woff, 3);
  get(path, s.id, "grid_window_cells", H5T_NATIVE_INT, wnc, 3);
  for (int a = 0; a < 3; ++a)
    if (woff[a] < 0 || wnc[a] < 1 || woff[a] + wnc[a] > nc[a]) fail(path, "bad grid window");
  long steps;
  double time, dt, ke, ie, mom[3], e0, work, load_work = 0.0;
  int outside;
  get(path, s.id, "step", H5T_NATIVE_LONG, &steps);
  get(path, s.id, "time", H5T_NATIVE_DOUBLE, &time);
  get(path, s.id, "dt", H5T_NATIVE_DOUBLE, &dt);
  get(path, s.id, "kinetic_energy", H5T_NATIVE_DOUBLE, &ke);
  get(path, s.id, "internal_energy", H5T_NATIVE_DOUBLE, &ie);
  get(path, s.id, "momentum", H5T_NATIVE_DOUBLE, mom, 3);
  get(path, s.id, "initial_total_energy", H5T_NATIVE_DOUBLE, &e0);
  get(path, s.id, "external_work", H5T_NATIVE_DOUBLE, &work);
  // Written since 2026-12-05; an older checkpoint's balance starts from its restart.
  if (H5Aexists(s.id, "load_work") > 0) get(path, s.id, "load_work", H5T_NATIVE_DOUBLE, &load_work);
  get(path, s.id, "particles_outside_grid", H5T_NATIVE_INT, &outside);
  if (steps < 0 || !(dt > 0.0) || !(h > 0.0)) fail(path, "bad step, dt or cell size");
  {
    // A checkpoint without the attribute was written before the rules existed: by ours.
    const std::string written = H5Aexists(s.id, "rules") > 0
                                    ? get_string(path, s.id, "rules")
                                    : rules_text(resolve_rules(RuleRequest(), m.deck_current));
    if (!same_rules(written, m.rules))
      fail(path, "written under the rules '" + written + "', the run asks for '" + rules_text(m.rules) +
                     "' (give the same --rules and --rule options)");
  }

  const bool marks = m.contact && m.scheme == SCHEME_USF;
  if (marks != (H5Lexists(s.id, "contact_marks", H5P_DEFAULT) > 0))
    fail(path, marks ? "no /simulation/contact_marks (the deck's USF contact needs them)"
                     : "/simulation/contact_marks is not used by this deck");
  std::vector<double> contact_marks;
  if (marks) {
    // The node count of the stored grid window (contact keeps the deck's box).
    contact_marks.resize(3 * size_t(wnc[0] + 1) * size_t(wnc[1] + 1) * size_t(wnc[2] + 1));
    get_array(path, s.id, "contact_marks", H5T_NATIVE_DOUBLE, contact_marks.data(), contact_marks.size());
  }

  // Particle arrays: read into copies first, so a bad file leaves the model unchanged.
  Id g{H5Gopen2(f.id, "/particles", H5P_DEFAULT), H5Gclose};
  if (g.id < 0) fail(path, "no /particles group");
  const hsize_t np = hsize_t(m.particles.np);
  std::vector<std::vector<double>> dbuf;
  std::vector<std::vector<int32_t>> ibuf;
  const auto fields = particle_fields(m.particles);
  for (const ParticleField& fd : fields) {
    const bool used = fd.d ? !fd.d->empty() : !fd.i->empty();
    const bool stored = H5Lexists(g.id, fd.name, H5P_DEFAULT) > 0;
    if (used != stored)
      fail(path, std::string("particle array '") + fd.name + (used ? "' is missing (the model needs it)" : "' is not used by this model"));
    if (fd.d) {
      dbuf.emplace_back(used ? np * hsize_t(fd.ncomp) : 0);
      if (used) get_array(path, g.id, fd.name, H5T_NATIVE_DOUBLE, dbuf.back().data(), np * hsize_t(fd.ncomp));
    } else {
      ibuf.emplace_back(used ? np * hsize_t(fd.ncomp) : 0);
      if (used) get_array(path, g.id, fd.name, H5T_NATIVE_INT32, ibuf.back().data(), np * hsize_t(fd.ncomp));
    }
  }

  {
    // The storage order must be a permutation of the deck's particles: the outputs write
    // through it.
    size_t k = 0;
    for (const ParticleField& fd : fields) {
      if (fd.d) continue;
      if (std::string(fd.name) == "deck_id" && !ibuf[k].empty()) {
        std::vector<char> seen(size_t(np), 0);
        for (int32_t v : ibuf[k]) {
          if (v < 0 || hsize_t(v) >= np || seen[size_t(v)]) fail(path, "particle array 'deck_id' is not a permutation of the particles");
          seen[size_t(v)] = 1;
        }
      }
      ++k;
    }
  }

  OutputSchedule o;
  Id og{H5Gopen2(f.id, "/output", H5P_DEFAULT), H5Gclose};
  if (og.id < 0) fail(path, "no /output group");
  get(path, og.id, "next_output_time", H5T_NATIVE_DOUBLE, &o.next_out);
  get(path, og.id, "next_report_time", H5T_NATIVE_DOUBLE, &o.next_rpt);
  {
    Id d{H5Dopen2(og.id, "frame_times", H5P_DEFAULT), H5Dclose};
    if (d.id < 0) fail(path, "no /output/frame_times");
    Id sp{H5Dget_space(d.id), H5Sclose};
    o.frame_times.resize(size_t(H5Sget_simple_extent_npoints(sp.id)));
    if (!o.frame_times.empty() && H5Dread(d.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, o.frame_times.data()) < 0)
      fail(path, "cannot read /output/frame_times");
  }
  {
    const std::string names = get_string(path, og.id, "file_names");
    std::vector<std::string> list;
    for (size_t a = 0, b; (b = names.find('\n', a)) != std::string::npos; a = b + 1) list.push_back(names.substr(a, b - a));
    std::vector<long long> sizes(list.size());
    if (!get_array(path, og.id, "file_sizes", H5T_NATIVE_LLONG, sizes.data(), sizes.size()))
      fail(path, "no /output/file_sizes");
    for (size_t k = 0; k < list.size(); ++k) o.files.emplace_back(list[k], sizes[k]);
  }

  // Everything read: apply.
  sim.set_grid(origin, h, nc, pc, woff, wnc);
  if (marks) {
    if (contact_marks.size() != 3 * size_t(sim.grid.nnode())) fail(path, "contact_marks do not fit the grid");
    std::copy(contact_marks.begin(), contact_marks.end(), sim.ctx.contact.gnormal);
  }
  size_t kd = 0, ki = 0;
  for (const ParticleField& fd : fields) {
    if (fd.d) {
      std::vector<double>& b = dbuf[kd++];
      if (!b.empty()) std::copy(b.begin(), b.end(), fd.d->begin());  // in place: ctx points at these
    } else {
      std::vector<int32_t>& b = ibuf[ki++];
      if (!b.empty()) std::copy(b.begin(), b.end(), fd.i->begin());
    }
  }
  // The patch lists of the restored particles: the energy stage sums over them (a measure()
  // before the next step, as mpm3d_set_array does, needs them).
  sim.bin_particles();
  m.dt = dt;
  sim.steps = steps;
  sim.time = time;
  sim.kinetic = ke;
  sim.internal = ie;
  for (int a = 0; a < 3; ++a) sim.momentum[a] = mom[a];
  sim.initial_total_energy = e0;
  sim.external_work = work;
  sim.load_work = load_work;
  sim.outside = outside;
  out = std::move(o);
}

}  // namespace mpm3d
