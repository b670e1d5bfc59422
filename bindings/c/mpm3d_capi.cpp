// The C API of MPM3D-CXX (mpm3d.h) over mpm3d::Simulation. Every entry point catches
// everything: no exception crosses the C boundary, errors become codes plus a thread-local
// message.
#include "mpm3d.h"

#include <cerrno>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/checkpoint.hpp"
#include "input/data_in.hpp"
#include "io/data_out.hpp"
#include "input/ffi.hpp"
#include "mpm3d.hpp"
#include "stages/update_step.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

#ifndef MPM3D_VERSION_STRING
#define MPM3D_VERSION_STRING "unknown"
#endif

struct mpm3d_sim {
  explicit mpm3d_sim(mpm3d::Model m) : sim(std::move(m)), table(mpm3d::cxx_stages()) {}
  mpm3d::Simulation sim;
  mpm3d::StageTable table;  // the table last given to sim.set_stages
};

namespace {

// The calling thread's last message: a fixed buffer, so recording an error cannot fail.
thread_local char g_error[4352];

void clear_error() { g_error[0] = '\0'; }

int fail(int code, const char* fmt, ...) __attribute__((format(printf, 2, 3)));
int fail(int code, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(g_error, sizeof g_error, fmt, ap);
  va_end(ap);
  return code;
}

// Maps the exception in flight to a code and message (call inside a catch block).
int fail_current(const char* context) {
  const char* sep = context && *context ? ": " : "";
  if (!context) context = "";
  try {
    throw;
  } catch (const mpm3d::DeckError& e) {
    return fail(MPM3D_ERR_DECK, "%s", e.what());
  } catch (const mpm3d::HealthError& e) {
    return fail(MPM3D_ERR_HEALTH, "%s", e.what());
  } catch (const std::bad_alloc&) {
    return fail(MPM3D_ERR_MEMORY, "%s%sout of memory", context, sep);
  } catch (const std::exception& e) {
    return fail(MPM3D_ERR_INTERNAL, "%s%s%s", context, sep, e.what());
  } catch (...) {
    return fail(MPM3D_ERR_INTERNAL, "%s%sunknown failure", context, sep);
  }
}

// A particle array of the model by its API name.
struct ArrayRef {
  std::vector<double>* data = nullptr;
  long ncomp = 1;
};

bool find_array(mpm3d::Particles& P, const char* name, ArrayRef& r) {
  const std::string n = name;
  if (n == "position") r = {&P.x, 3};
  else if (n == "velocity") r = {&P.v, 3};
  else if (n == "stress") r = {&P.sig, 6};
  else if (n == "mass") r = {&P.mass, 1};
  else if (n == "volume") r = {&P.vol, 1};
  else if (n == "epeff") r = {&P.epeff, 1};
  else if (n == "internal_energy") r = {&P.ie, 1};
  else if (n == "temperature") r = {&P.temp, 1};
  else return false;
  return true;
}

const char* const kArrayNames =
    "position, velocity, stress, mass, volume, epeff, internal_energy, temperature";

// Resolves name to an array of the model; fails with MPM3D_ERR_ARGUMENT.
int lookup(const mpm3d_sim* s, const char* name, const char* fn, ArrayRef& r) {
  if (!s) return fail(MPM3D_ERR_ARGUMENT, "%s: null handle", fn);
  if (!name) return fail(MPM3D_ERR_ARGUMENT, "%s: null array name", fn);
  auto& P = const_cast<mpm3d::Particles&>(s->sim.model.particles);
  if (!find_array(P, name, r))
    return fail(MPM3D_ERR_ARGUMENT, "%s: unknown array '%s' (one of %s)", fn, name, kArrayNames);
  if (r.data->empty() && P.np > 0)
    return fail(MPM3D_ERR_ARGUMENT, "%s: this model has no '%s' array", fn, name);
  return MPM3D_OK;
}

// The array of a get/set call, checked: its name, then the caller's count n against the
// array's size and the caller's buffer (what: "destination" or "source").
int lookup_sized(const mpm3d_sim* s, const char* name, const char* fn, long n, const void* buf, const char* what,
                 ArrayRef& r) {
  if (int rc = lookup(s, name, fn, r)) return rc;
  const long need = long(r.data->size());
  if (n != need)
    return fail(MPM3D_ERR_ARGUMENT, "%s('%s'): wrong size %ld, need %ld (%ld x %d particles)", fn, name, n, need,
                r.ncomp, s->sim.model.particles.np);
  if (!buf && need > 0) return fail(MPM3D_ERR_ARGUMENT, "%s('%s'): null %s", fn, name, what);
  return MPM3D_OK;
}

}  // namespace

extern "C" {

MPM3D_API const char* mpm3d_version(void) {
  clear_error();
  return MPM3D_VERSION_STRING;
}

MPM3D_API const char* mpm3d_last_error(void) { return g_error; }

MPM3D_API int mpm3d_have_fortran_kernels(void) {
  clear_error();
  return mpm3d::have_fortran_stages() ? 1 : 0;
}

MPM3D_API int mpm3d_set_threads(int n) {
  clear_error();
  if (n < 1) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_set_threads: need at least one thread, got %d", n);
#ifdef _OPENMP
  omp_set_num_threads(n);
#endif
  return MPM3D_OK;
}

MPM3D_API int mpm3d_open(const char* deck_path, mpm3d_sim** out) {
  clear_error();
  if (!out) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_open: null output handle pointer");
  *out = nullptr;
  if (!deck_path) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_open: null deck path");
  {
    FILE* f = std::fopen(deck_path, "rb");
    if (!f) return fail(MPM3D_ERR_IO, "%s: cannot open the deck: %s", deck_path, std::strerror(errno));
    std::fclose(f);
  }
  try {
    mpm3d::Model model = mpm3d::read_deck(deck_path);
    *out = new mpm3d_sim(std::move(model));
    return MPM3D_OK;
  } catch (const std::invalid_argument& e) {  // model the grid cannot take
    return fail(MPM3D_ERR_DECK, "%s: %s", deck_path, e.what());
  } catch (...) {
    return fail_current(deck_path);
  }
}

MPM3D_API void mpm3d_close(mpm3d_sim* sim) {
  clear_error();
  delete sim;  // destructors of the model do not throw
}

MPM3D_API int mpm3d_set_kernel(mpm3d_sim* sim, const char* spec) {
  clear_error();
  if (!sim) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_set_kernel: null handle");
  if (!spec) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_set_kernel: null specification");
  try {
    mpm3d::StageTable t = sim->table;
    const bool per_stage = std::strchr(spec, '=') != nullptr;
    mpm3d::select_stages(t, spec, per_stage);
    sim->sim.set_stages(t);
    sim->table = t;
    return MPM3D_OK;
  } catch (const std::bad_alloc&) {
    return fail(MPM3D_ERR_MEMORY, "mpm3d_set_kernel: out of memory");
  } catch (const std::exception& e) {
    return fail(MPM3D_ERR_KERNEL, "mpm3d_set_kernel('%s'): %s", spec, e.what());
  } catch (...) {
    return fail(MPM3D_ERR_KERNEL, "mpm3d_set_kernel('%s'): unknown failure", spec);
  }
}

MPM3D_API int mpm3d_step(mpm3d_sim* sim, int nsteps) {
  clear_error();
  if (!sim) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_step: null handle");
  if (nsteps < 0) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_step: negative number of steps (%d)", nsteps);
  try {
    mpm3d::LoopLimits limits;
    limits.max_steps = sim->sim.steps + nsteps;
    const mpm3d::LoopProgress progress = mpm3d::run_steps(sim->sim, limits);
    if (!progress.failure.empty()) return fail(MPM3D_ERR_HEALTH, "%s", progress.failure.c_str());
    return MPM3D_OK;
  } catch (...) {
    return fail_current(sim->sim.model.deck_path.c_str());
  }
}

static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

#define MPM3D_GETTER(type, name, bad, expr)                                               \
  MPM3D_API type name(const mpm3d_sim* sim) {                                             \
    clear_error();                                                                        \
    if (!sim) {                                                                           \
      fail(MPM3D_ERR_ARGUMENT, "%s: null handle", #name);                                 \
      return bad;                                                                         \
    }                                                                                     \
    const mpm3d::Simulation& s = sim->sim;                                                \
    return expr;                                                                          \
  }

MPM3D_GETTER(double, mpm3d_time, kNaN, s.time)
MPM3D_GETTER(long, mpm3d_steps, -1, s.steps)
MPM3D_GETTER(int, mpm3d_num_particles, -1, s.model.particles.np)
MPM3D_GETTER(double, mpm3d_dt, kNaN, s.model.dt)
MPM3D_GETTER(double, mpm3d_end_time, kNaN, s.model.endtime)
MPM3D_GETTER(double, mpm3d_kinetic_energy, kNaN, s.kinetic)
MPM3D_GETTER(double, mpm3d_internal_energy, kNaN, s.internal)

#undef MPM3D_GETTER

MPM3D_API int mpm3d_momentum(const mpm3d_sim* sim, double* dst) {
  clear_error();
  if (!sim) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_momentum: null handle");
  if (!dst) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_momentum: null destination");
  for (int a = 0; a < 3; ++a) dst[a] = sim->sim.momentum[a];
  return MPM3D_OK;
}

MPM3D_API long mpm3d_array_size(const mpm3d_sim* sim, const char* name) {
  clear_error();
  ArrayRef r;
  if (lookup(sim, name, "mpm3d_array_size", r) != MPM3D_OK) return -1;
  return long(r.data->size());
}

MPM3D_API int mpm3d_get_array(const mpm3d_sim* sim, const char* name, double* dst, long n) {
  clear_error();
  ArrayRef r;
  if (int rc = lookup_sized(sim, name, "mpm3d_get_array", n, dst, "destination", r)) return rc;
  // In deck order (the solver stores the particles in its own order, Particles::id).
  const mpm3d::Particles& P = sim->sim.model.particles;
  const std::vector<int> at = mpm3d::stored_index(P);
  mpm3d::gather_rows(r.data->data(), int(r.ncomp), P.np, [&](int i) { return at[size_t(i)]; }, dst);
  return MPM3D_OK;
}

MPM3D_API int mpm3d_set_array(mpm3d_sim* sim, const char* name, const double* src, long n) {
  clear_error();
  ArrayRef r;
  if (int rc = lookup_sized(sim, name, "mpm3d_set_array", n, src, "source", r)) return rc;
  try {
    // In place (the step context keeps pointing at these arrays), from deck order. The
    // source is read completely before anything changes, so it may alias the array.
    const mpm3d::Particles& P = sim->sim.model.particles;
    std::vector<double> t(src, src + n);
    mpm3d::gather_rows(t.data(), int(r.ncomp), P.np, [&](int p) { return P.deck_number(p); }, r.data->data());
    sim->sim.measure();  // energies and momentum of the new state
    return MPM3D_OK;
  } catch (...) {
    return fail_current("mpm3d_set_array");
  }
}

MPM3D_API int mpm3d_write_state(const mpm3d_sim* sim, const char* path) {
  clear_error();
  if (!sim) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_write_state: null handle");
  if (!path || !*path) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_write_state: no file name");
  try {
    const mpm3d::Simulation& s = sim->sim;
    mpm3d::write_state_h5(path, s.model, s.time, s.steps, s.model.dt);
    return MPM3D_OK;
  } catch (const std::bad_alloc&) {
    return fail(MPM3D_ERR_MEMORY, "mpm3d_write_state: out of memory");
  } catch (const std::exception& e) {
    return fail(MPM3D_ERR_IO, "mpm3d_write_state: %s", e.what());
  } catch (...) {
    return fail(MPM3D_ERR_IO, "mpm3d_write_state: cannot write %s", path);
  }
}

MPM3D_API int mpm3d_write_checkpoint(const mpm3d_sim* sim, const char* path) {
  clear_error();
  if (!sim) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_write_checkpoint: null handle");
  if (!path || !*path) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_write_checkpoint: no file name");
  try {
    mpm3d::OutputSchedule o;  // the library writes no result files: an empty schedule
    o.next_out = sim->sim.model.outtime;
    o.next_rpt = sim->sim.model.rpttime;
    mpm3d::write_checkpoint(path, sim->sim, o);
    return MPM3D_OK;
  } catch (const std::bad_alloc&) {
    return fail(MPM3D_ERR_MEMORY, "mpm3d_write_checkpoint: out of memory");
  } catch (const std::exception& e) {
    return fail(MPM3D_ERR_IO, "mpm3d_write_checkpoint: %s", e.what());
  } catch (...) {
    return fail(MPM3D_ERR_IO, "mpm3d_write_checkpoint: cannot write %s", path);
  }
}

MPM3D_API int mpm3d_restart(mpm3d_sim* sim, const char* path) {
  clear_error();
  if (!sim) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_restart: null handle");
  if (!path || !*path) return fail(MPM3D_ERR_ARGUMENT, "mpm3d_restart: no file name");
  try {
    mpm3d::OutputSchedule o;
    mpm3d::read_checkpoint(path, sim->sim, o);
    return MPM3D_OK;
  } catch (const std::bad_alloc&) {
    return fail(MPM3D_ERR_MEMORY, "mpm3d_restart: out of memory");
  } catch (const std::exception& e) {
    return fail(MPM3D_ERR_IO, "mpm3d_restart: %s", e.what());
  } catch (...) {
    return fail(MPM3D_ERR_IO, "mpm3d_restart: cannot read %s", path);
  }
}

}  // extern "C"
