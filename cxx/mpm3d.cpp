#include "mpm3d.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "checkpoint.hpp"
#include "data_out.hpp"
#include "ffi.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace mpm3d {
namespace {

// The first 64-byte boundary in v (which has 8 words to spare), so that each thread's
// patch range word has a cache line of its own.
uint64_t* line_aligned(std::vector<uint64_t>& v) {
  const auto at = reinterpret_cast<std::uintptr_t>(v.data());
  return v.data() + ((64 - at % 64) % 64) / sizeof(uint64_t);
}

// Points c's load-balance arrays (thread shares, busy times, particles done, patch range
// words) at fresh storage in balance and ranges; the first binning sets equal shares.
void bind_balance(StepContext& c, std::vector<double>& balance, std::vector<uint64_t>& ranges) {
  balance.assign(kBalanceValues, 0.0);
  c.thread_share = balance.data();
  c.thread_busy = balance.data() + kBalanceValues / 3;
  c.thread_done = balance.data() + 2 * (kBalanceValues / 3);
  ranges.assign(kPatchRangeWords + 8, 0);
  c.patch_ranges = line_aligned(ranges);
  c.nshare = 0;
}

}  // namespace

Simulation::Simulation(Model m, int patch_cells, ParticleOrder order) : model(std::move(m)), stages_(cxx_stages()) {
  if (patch_cells < 1) throw std::invalid_argument("patch size must be at least one cell");
  // A GIMP stencil reaches one node beyond its patch's cells; the node loops find every
  // node a patch's particles touch among its own and its neighbours' nodes only when a
  // patch is at least two cells wide.
  if (model.gimp && patch_cells < 2) throw std::invalid_argument("GIMP needs patches of at least two cells");
  double hi[3];
  for (int a = 0; a < 3; ++a) hi[a] = model.box_hi[a];
  const int halo = model.gimp ? 1 : 0;  // GIMP stencils reach one node beyond a patch's cells
  grid.define(model.box_lo, hi, model.dcell, patch_cells, halo);
  for (int f = 0; f < 6; ++f) grid.fix[f] = model.fix[f];
  grid.mass_cutoff = model.mass_cutoff;
  const size_t np = size_t(model.particles.np);
  if (order == ParticleOrder::blocks) {
    order_by_blocks(model.particles, model.box_lo, model.dcell, grid.deck_nc, patch_cells);
  } else {
    model.particles.id.resize(np);  // deck order, recorded too (the checkpoint stores it)
    for (size_t p = 0; p < np; ++p) model.particles.id[p] = int32_t(p);
  }
  regrid_every = model.regrid_every;
  if (model.contact && regrid_every > 0) {
    // The two contact grids share one node numbering; the adaptive window is not applied.
    regrid_every = 0;
    model.warnings.push_back("adaptive grid ignored: 'cont' (multi-velocity contact) keeps the deck's box");
  }
  // The first window (the whole box without the adaptive grid); the node arrays are
  // allocated at the window's size only.
  int off[3] = {0, 0, 0}, nc[3] = {grid.deck_nc[0], grid.deck_nc[1], grid.deck_nc[2]};
  if (regrid_every > 0)
    adaptive_window(grid, model.particles.x.data(), model.particles.v.data(), model.particles.np, regrid_every,
                    model.dt, off, nc);
  grid.set_window(off, nc);
  lx_.assign(3 * np, 0.0);
  cell_.assign(np, -1);
  grid.patch_part.assign(np, 0);
  if (model.contact) {
    grid2.setup(model.box_lo, hi, model.dcell, patch_cells, halo);
    for (int f = 0; f < 6; ++f) grid2.fix[f] = model.fix[f];
    grid2.mass_cutoff = model.mass_cutoff;
    grid2.patch_part.assign(np, 0);
  }
  bind();
  measure();
  initial_total_energy = kinetic + internal;
  // Binning of the initial state, for the patch statistics before the first step (every
  // step bins again).
  stages_.fn[ST_BIN](&ctx);
  stats = patch_stats(grid, ctx.patch_start);
  // The patch buffers for these lists now, with the set-up, rather than in the first step:
  // their zero-filling and first touch (1.5 MB on taylor_coarse, 22 us a step averaged over
  // 200 steps at 1 thread) is no part of a step's cost.
  ensure_patch_buffers();
  if (regrid_every > 0) {
    regrids = 1;
    note_regrid(0);
  }
}

void Simulation::bind() {
  Particles& P = model.particles;
  StepContext& c = ctx;
  c.x = P.x.data();
  c.v = P.v.data();
  c.sig = P.sig.data();
  c.mass = P.mass.data();
  c.vol = P.vol.data();
  c.epeff = P.epeff.data();
  c.ie = P.ie.data();
  c.temp = P.temp.empty() ? nullptr : P.temp.data();
  c.fext = P.fext.empty() ? nullptr : P.fext.data();
  c.tlight = P.tlight.empty() ? nullptr : P.tlight.data();
  c.qv = P.qv.empty() ? nullptr : P.qv.data();
  c.bulk_q1 = model.bulk_q1;
  c.bulk_q2 = model.bulk_q2;
  c.lx = lx_.data();
  c.mat = P.mat.data();
  c.body = P.body.data();
  c.cell = cell_.data();
  pscratch_.assign(size_t(P.np), 0);
  c.pscratch = pscratch_.data();
  bind_balance(c, balance_, ranges_);
  std::vector<double>& grav = gravity_;
  grav.assign(3 * model.bodies.size(), 0.0);
  for (size_t b = 0; b < model.bodies.size(); ++b)
    for (int a = 0; a < 3; ++a) grav[3 * b + a] = model.bodies[b].gravity[a];
  c.gravity = grav.data();
  c.mats = model.mats.data();
  c.patch_part = grid.patch_part.data();
  c.patch_buf = grid.patch_buf.data();
  c.reduce_block = 4096;
  partials_.assign(size_t(kReduceFields) * (P.np / c.reduce_block + 1), 0.0);
  c.partials = partials_.data();
  c.h = grid.h;
  c.inv_h = 1.0 / grid.h;
  c.dt = model.dt;
  c.dt_int = model.dt;
  c.mass_cutoff = grid.mass_cutoff;
  c.np = P.np;
  c.nbody = int(model.bodies.size());
  c.nmat = int(model.mats.size());
  c.patch_cells = grid.patch_cells;
  for (int f = 0; f < 6; ++f) c.fix[f] = grid.fix[f];
  c.scheme = model.scheme;
  c.has_body_force = (model.has_gravity || model.has_loads) ? 1 : 0;
  // GIMP: 27-node stencils, patch buffers with a halo of one node layer.
  c.psize = model.gimp ? P.psize.data() : nullptr;
  c.shape = model.gimp ? 1 : 0;
  c.patch_halo = grid.patch_halo;
  c.body_comp = nullptr;
  c.other = nullptr;
  c.gnormal = nullptr;
  c.cpartials = nullptr;
  c.only_comp = 0;
  bind_grid();  // before the contact copy: ctx2 starts as a copy of ctx
  if (model.contact) {
    // Two contexts over the same particles: each bins, scatters and updates the particles
    // of its component on its own grid; the contact stage (in ctx) couples the two grids.
    body_comp_.assign(model.bodies.size(), 1);
    for (size_t b = 0; b < model.bodies.size(); ++b) body_comp_[b] = model.bodies[b].component;
    gnormal1_.assign(3 * size_t(grid.nnode()), 0.0);
    gnormal2_.assign(3 * size_t(grid.nnode()), 0.0);
    cpartials_.assign(3 * size_t(grid.npatch), 0.0);
    c.body_comp = body_comp_.data();
    c.contact_mu = model.contact_mu;
    c.contact_normbody = model.contact_normbody;
    c.cpartials = cpartials_.data();
    ctx2 = c;
    c.only_comp = 1;
    c.gnormal = gnormal1_.data();
    c.other = &ctx2;
    ctx2.only_comp = 2;
    ctx2.gnormal = gnormal2_.data();
    ctx2.gmass = grid2.mass.data();
    ctx2.gmom = grid2.mom.data();
    ctx2.gforce = grid2.force.data();
    ctx2.patch_start = grid2.patch_start.data();
    ctx2.patch_part = grid2.patch_part.data();
    ctx2.patch_slot = grid2.patch_slot.data();
    ctx2.patch_buf = grid2.patch_buf.data();
    bind_balance(ctx2, balance2_, ranges2_);
  }
}

void Simulation::bind_grid() {
  StepContext& c = ctx;
  c.gmass = grid.mass.data();
  c.gmom = grid.mom.data();
  c.gforce = grid.force.data();
  c.patch_start = grid.patch_start.data();
  c.patch_slot = grid.patch_slot.data();
  for (int a = 0; a < 3; ++a) {
    c.origin[a] = grid.origin[a];
    c.nc[a] = grid.nc[a];
    c.nn[a] = grid.nn[a];
    c.npd[a] = grid.npd[a];
    c.cell_off[a] = grid.off[a];
  }
  c.nnode = grid.nnode();
  c.npatch = grid.npatch;
}

void Simulation::regrid(int escaped) {
  int off[3], nc[3];
  const Particles& P = model.particles;
  adaptive_window(grid, P.x.data(), P.v.data(), P.np, regrid_every > 0 ? regrid_every : 1, model.dt, off, nc);
  grid.set_window(off, nc);
  bind_grid();
  ++regrids;
  if (escaped > 0) ++regrids_forced;
}

void Simulation::note_regrid(int escaped) {
  char line[320];
  std::snprintf(line, sizeof line,
                "regrid step %ld window %d %d %d %d %d %d cells %d x %d x %d, patches %d, empty %d, "
                "particles per patch max %d mean %.1f, imbalance %.3f",
                steps, grid.off[0], grid.off[0] + grid.nc[0], grid.off[1], grid.off[1] + grid.nc[1], grid.off[2],
                grid.off[2] + grid.nc[2], grid.nc[0], grid.nc[1], grid.nc[2], stats.patches, stats.empty, stats.max,
                stats.mean, stats.imbalance);
  regrid_note = line;
  if (escaped > 0) regrid_note += " (forced: " + std::to_string(escaped) + " particles had left the window)";
}

void Simulation::use_expansion_scatter() {
  stages_.fn[ST_P2G] = mpm3d_cxx_p2g_expansion;
  stages_.fn[ST_FORCES] = mpm3d_cxx_forces_expansion;
  stages_.fn[ST_G2P] = mpm3d_cxx_g2p_expansion;
  expansion_ = true;
}

void Simulation::ensure_expansion_buffers() {
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  const size_t need = size_t(threads) * size_t(grid.nnode()) * kNodeFields;
  if (tgrid_.size() != need) std::vector<double>(need).swap(tgrid_);  // each thread zeroes its own copy
  ctx.tgrid = tgrid_.data();
  ctx.ntgrid = threads;
}

void Simulation::set_grid(const double origin[3], double h, const int deck_nc[3], int patch_cells, const int off[3],
                          const int nc[3]) {
  if (patch_cells < 1) throw std::invalid_argument("patch size must be at least one cell");
  double hi[3];
  for (int a = 0; a < 3; ++a) hi[a] = origin[a] + double(deck_nc[a]) * h;
  grid.define(origin, hi, h, patch_cells, model.gimp ? 1 : 0);
  for (int a = 0; a < 3; ++a)
    if (grid.deck_nc[a] != deck_nc[a]) throw std::runtime_error("grid: cannot rebuild the stored grid");
  grid.set_window(off, nc);
  for (int f = 0; f < 6; ++f) grid.fix[f] = model.fix[f];
  grid.mass_cutoff = model.mass_cutoff;
  grid.patch_part.assign(size_t(model.particles.np), 0);
  bind();
}

void Simulation::ensure_patch_buffers() {
  const size_t need = size_t(ctx.nslot) * size_t(grid.patch_nodes) * kNodeFields;
  if (grid.patch_buf.size() < need) {
    grid.patch_buf.resize(need + need / 4);
    ctx.patch_buf = grid.patch_buf.data();
  }
  if (model.contact) {
    const size_t need2 = size_t(ctx2.nslot) * size_t(grid2.patch_nodes) * kNodeFields;
    if (grid2.patch_buf.size() < need2) {
      grid2.patch_buf.resize(need2 + need2 / 4);
      ctx2.patch_buf = grid2.patch_buf.data();
    }
  }
}

void Simulation::step() {
  StepContext* c = &ctx;
  c->dt = model.dt;
  c->dt_int = steps == 0 ? 0.5 * model.dt : model.dt;  // first step: momentum with dt/2
  c->time = time + model.dt;  // the end of this step (programmed burn)
  const bool contact = model.contact;
  if (contact) {
    ctx2.dt = c->dt;
    ctx2.dt_int = c->dt_int;
    ctx2.time = c->time;
  }
  // A stage on one context; with contact, the particle and grid stages run on both
  // components' contexts in turn (component 1 first).
  auto run1 = [&](int s, StepContext* x) {
    const auto t0 = std::chrono::steady_clock::now();
    stages_.fn[s](x);
    stage_seconds[s] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  auto run = [&](int s) {
    run1(s, c);
    if (contact) run1(s, &ctx2);
  };
  const bool scheduled = regrid_every > 0 && steps > 0 && steps % regrid_every == 0;
  if (scheduled) {
    const auto t0 = std::chrono::steady_clock::now();
    regrid(0);
    stage_seconds[ST_BIN] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  run(ST_BIN);
  int escaped = 0;
  if (c->noutside > 0 && !grid.window_is_box()) {
    // A particle inside the deck's box has left the window: widen it now and bin again,
    // so that the window never freezes a particle the box would not have frozen.
    escaped = count_escaped(grid, c->x, c->cell, c->np);
    if (escaped > 0) {
      const auto t0 = std::chrono::steady_clock::now();
      regrid(escaped);
      stage_seconds[ST_BIN] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      run(ST_BIN);
    }
  }
  stats = patch_stats(grid, c->patch_start);
  if (scheduled || escaped > 0) note_regrid(escaped);
  ensure_patch_buffers();
  if (expansion_) ensure_expansion_buffers();
  run(ST_P2G);
  if (c->scheme == SCHEME_USF) {
    // The P2G momenta of the nodes in contact at the end of the previous step corrected
    // again before the strain rates read them (their velocities moved the particles).
    if (contact) run1(ST_RECONTACT, c);
    run(ST_STRESS);
    run(ST_FORCES);
  }
  run(ST_INTEGRATE);
  if (contact) {  // both grids integrated: correct the momenta and forces of the pair
    run1(ST_CONTACT, c);
    for (int a = 0; a < 3; ++a) contact_force[a] = c->result[5 + a];
    contact_nodes = c->ncontact;
  }
  run(ST_G2P);
  // MUSL: the remapped momenta of the nodes in contact are corrected again before the
  // strain rates (the stress stage) read them.
  if (contact && c->scheme == SCHEME_MUSL) run1(ST_RECONTACT, c);
  if (c->scheme != SCHEME_USF) run(ST_STRESS);
  run1(ST_ENERGY, c);
  outside = c->noutside + (contact ? ctx2.noutside : 0);
  kinetic = c->result[0];
  internal = c->result[1];
  for (int a = 0; a < 3; ++a) momentum[a] = c->result[2 + a];
  ++steps;
  time += model.dt;
  if (ctx.has_body_force) external_work += dt_work_of_body_forces();
  health_check();
}

double Simulation::dt_work_of_body_forces() const {
  const Particles& P = model.particles;
  // An upper bound of the energy the external forces can have put in: |f . v| per particle,
  // so forces that change sign (vibrations, manufactured solutions) do not cancel out.
  double w = 0.0;
  for (int p = 0; p < P.np; ++p) {
    const double* g = &gravity_[3 * size_t(P.body[p])];
    const double* v = &P.v[3 * size_t(p)];
    double pw = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double f = P.mass[p] * g[a] + (P.fext.empty() ? 0.0 : P.fext[3 * size_t(p) + a]);
      pw += f * v[a];
    }
    w += std::fabs(pw);
  }
  return w * model.dt;
}

void Simulation::measure() {
  stages_.fn[ST_ENERGY](&ctx);
  kinetic = ctx.result[0];
  internal = ctx.result[1];
  for (int a = 0; a < 3; ++a) momentum[a] = ctx.result[2 + a];
}

// After every step: non-finite values (when an energy sum is not finite), then one pass
// over the particles for a non-positive volume or a density outside
// [kDensityRatioMin, kDensityRatioMax] rho0 (parallel, the lowest such deck number is
// reported, whatever the thread count), then runaway energy. The pass reads two doubles and
// one int per particle: about 1% of a step.
void Simulation::health_check() {
  const Particles& P = model.particles;
  if (!(std::isfinite(kinetic) && std::isfinite(internal))) {
    const std::vector<int> at = stored_index(P);
    for (int i = 0; i < P.np; ++i) {
      const int p = at[size_t(i)];
      const char* what = nullptr;
      for (int a = 0; a < 3 && !what; ++a) {
        if (!std::isfinite(P.x[3 * size_t(p) + a])) what = "position";
        else if (!std::isfinite(P.v[3 * size_t(p) + a])) what = "velocity";
      }
      for (int s = 0; s < 6 && !what; ++s)
        if (!std::isfinite(P.sig[6 * size_t(p) + s])) what = "stress";
      if (!what && !std::isfinite(P.ie[p])) what = "internal energy";
      if (!what && !std::isfinite(P.vol[p])) what = "volume";
      if (what) {
        std::ostringstream os;
        os << "numerical breakdown at step " << steps << " (t = " << time << "): particle " << i + 1 << " (body "
           << P.body[p] + 1 << ") has a non-finite " << what;
        throw HealthError(os.str());
      }
    }
  }
  double ie_min = 0.0;  // the lowest particle internal energy, if negative (a min is exact)
  {
    const double* vol = P.vol.data();
    const double* mass = P.mass.data();
    const int* mat = P.mat.data();
    const MaterialParams* mats = model.mats.data();
    const int np = P.np;
    const double* ie = P.ie.data();
    int bad = np;  // the lowest deck number of a particle out of bounds
#pragma omp parallel for schedule(static) reduction(min : bad, ie_min)
    for (int p = 0; p < np; ++p) {
      const double r0v = mats[mat[p]].rho0 * vol[p];
      const bool ok = vol[p] > 0.0 && mass[p] >= kDensityRatioMin * r0v && mass[p] <= kDensityRatioMax * r0v;
      if (!ok && P.deck_number(p) < bad) bad = P.deck_number(p);
      if (ie[p] < ie_min) ie_min = ie[p];
    }
    if (bad < np) {
      const int p = stored_index(P)[size_t(bad)];
      std::ostringstream os;
      os << "numerical breakdown at step " << steps << " (t = " << time << "): particle " << bad + 1 << " (body "
         << P.body[p] + 1 << ") has ";
      const double rho0 = mats[mat[p]].rho0;
      if (!(vol[p] > 0.0))
        os << "a non-positive volume " << vol[p] << " (crushed: reduce dtscale, or the impact speed is too high for the grid)";
      else
        os << "density " << mass[p] / vol[p] << " = " << (mass[p] / vol[p]) / rho0 << " rho0 (rho0 = " << rho0
           << "), outside the bounds [" << kDensityRatioMin << ", " << kDensityRatioMax << "] rho0";
      throw HealthError(os.str());
    }
  }
  if (std::isfinite(kinetic) && std::isfinite(internal)) {
    // Runaway energy: the total may not exceed twice the initial energy plus the bound of
    // the work of the external forces (sum of |f . v| dt per particle with the end-of-step
    // velocities; the factor two leaves room for that approximation).
    const double total = kinetic + internal;
    if (std::fabs(total) <= 2.0 * (std::fabs(initial_total_energy) + std::fabs(external_work)) + 1e-300) {
      energy_check(ie_min);
      return;
    }
    int worst = 0;
    double vmax = -1.0;
    for (int p = 0; p < P.np; ++p) {
      const double* v = &P.v[3 * size_t(p)];
      const double s = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
      if (s > vmax || (s == vmax && P.deck_number(p) < P.deck_number(worst))) {
        vmax = s;
        worst = p;
      }
    }
    std::ostringstream os;
    os << "numerical instability at step " << steps << " (t = " << time << "): total energy " << total
       << " exceeds twice the initial energy " << initial_total_energy << " plus the external work "
       << external_work << "; fastest particle " << P.deck_number(worst) + 1 << " (body " << P.body[worst] + 1 << ") at speed "
       << std::sqrt(vmax) << " (reduce dtscale, or use MUSL)";
    throw HealthError(os.str());
  }
  throw HealthError("numerical breakdown at step " + std::to_string(steps) + ": non-finite energy");
}

// Energy bounds that a run can break silently, with its total still conserved: a body's
// internal energy below -kEnergyWarnFraction (|E0| + |W|), or the kinetic energy above
// E0 + |W| by more than that (both seen when a body starts pre-compressed under an EOS, or
// an EOS releases more work than it stored). ie_min, the lowest particle internal energy
// (0 if none is negative), is exact whatever the thread count: the per-body sums (serial,
// in storage order, so their figures do not depend on the threads either) are formed only
// when np * ie_min could reach the bound.
void Simulation::energy_check(double ie_min) {
  const double bound = kEnergyWarnFraction * (std::fabs(initial_total_energy) + std::fabs(external_work));
  const Particles& P = model.particles;
  std::vector<std::string> found;
  if (ie_min < 0.0 && double(P.np) * ie_min < -bound) {
    std::vector<double> body_ie(model.bodies.size(), 0.0);
    for (int p = 0; p < P.np; ++p) body_ie[size_t(P.body[p])] += P.ie[p];
    body_ie_warned_.resize(body_ie.size(), 0);
    for (size_t b = 0; b < body_ie.size(); ++b) {
      if (body_ie_warned_[b] || !(body_ie[b] < -bound)) continue;
      body_ie_warned_[b] = 1;
      std::ostringstream os;
      os << "energy: the internal energy of body " << b + 1 << " is " << body_ie[b] << " at step " << steps
         << " (t = " << time << "), below -" << 100.0 * kEnergyWarnFraction << "% of the initial total energy "
         << initial_total_energy << " plus the external work " << external_work
         << " (its stress work releases more than it stored: check the EOS and that the particle cards' densities "
            "are the materials')";
      found.push_back(os.str());
    }
  }
  if (!kinetic_warned_ && kinetic > (initial_total_energy + std::fabs(external_work)) + bound) {
    kinetic_warned_ = true;
    std::ostringstream os;
    os << "energy: the kinetic energy " << kinetic << " at step " << steps << " (t = " << time
       << ") exceeds the initial total energy " << initial_total_energy << " plus the external work " << external_work
       << " by " << kinetic - (initial_total_energy + std::fabs(external_work)) << " (internal energy " << internal
       << ")";
    found.push_back(os.str());
  }
  if (found.empty()) return;
  if (strict_energy) throw HealthError(found.front() + " (stopped: --strict-energy)");
  for (auto& w : found) new_energy_warnings.push_back(std::move(w));
}

// ---------------------------------------------------------------- command line

namespace {

const char* kVersion = "mpm3d (MPM3D-CXX) 0.1.0";

const char* kUsage =
    "usage: mpm3d [options] DECK.mpm\n"
    "  --threads N        OpenMP threads (default: OMP_NUM_THREADS or all cores)\n"
    "  --steps N          stop after N steps\n"
    "  --end-time T       stop at time T instead of the deck's end time\n"
    "  --out-dir DIR      where result files go, created if missing (default: the current\n"
    "                     directory)\n"
    "  --no-output        no animation, curve or log files\n"
    "  --summary F.json   write a summary of the run\n"
    "  --state F.h5       write the final particle state (HDF5)\n"
    "  --patch-cells N    cells per patch edge of the grid decomposition (default 4)\n"
    "  --regrid-every N   adaptive background grid: redefine the grid from the particles'\n"
    "                     extent every N steps (0: off; default: the deck's 'adgr', else off)\n"
    "  --particle-order blocks|deck  storage order of the particles (default blocks: sorted by\n"
    "                     patch-sized blocks of cells, so each thread's patches hold a run of\n"
    "                     memory; deck: as read). Outputs are in deck order either way\n"
    "  --scatter patches|expansion  grid scatter scheme (default patches: bit-identical for\n"
    "                     any thread count; expansion: per-thread grid copies, a benchmark)\n"
    "  --hdf5             write the animation as an HDF5 + XDMF series (name_anim.h5/.xdmf)\n"
    "  --checkpoint F.h5  write a checkpoint when the run ends (and every N steps, below)\n"
    "  --checkpoint-every N   also write it every N steps (default file name_checkpoint.h5)\n"
    "  --restart F.h5     continue the run of the same deck from a checkpoint\n"
    "  --kernel cxx|fortran       take every step stage from one language\n"
    "  --kernels STAGE=LANG,...   take single stages from a language (see --list-stages)\n"
    "  --list-stages      print the stage names, one per line\n"
    "  --strict-energy    stop (exit 3) at the first energy warning: a body's internal energy\n"
    "                     below -0.1% of the initial total energy plus the external work, or\n"
    "                     the kinetic energy above that total by more than 0.1%\n"
    "  --quiet            no progress lines\n"
    "  --help, --version\n";

struct Options {
  std::string deck, out_dir = ".", summary, state, kernel, kernels, checkpoint, restart;
  long max_steps = -1, checkpoint_every = 0;
  double end_time = -1.0;
  int threads = 0, patch_cells = 4;
  long regrid_every = -1;  // -1: the deck's
  std::string scatter = "patches";
  std::string particle_order = "blocks";
  bool no_output = false, quiet = false, hdf5 = false, patch_given = false, strict_energy = false;
};

// SIGINT/SIGTERM: the time loop finishes the current step, writes a checkpoint and exits
// with 128 + the signal number. The handler is one-shot: a second signal kills at once.
volatile std::sig_atomic_t g_signal = 0;
extern "C" void on_stop_signal(int sig) { g_signal = sig; }

void install_signal_handlers() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART | SA_RESETHAND;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

long to_long(const std::string& opt, const char* s) {
  long v;
  if (!parse_integer(s, v)) throw UsageError(opt + " needs an integer, got '" + s + "'");
  return v;
}

Options parse_args(int argc, char** argv, bool& exit_now) {
  Options o;
  exit_now = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw UsageError(a + " needs a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      exit_now = true;
      return o;
    } else if (a == "--version") {
      std::cout << kVersion << "\n";
      exit_now = true;
      return o;
    } else if (a == "--threads") {
      o.threads = int(to_long(a, value()));
      if (o.threads < 1) throw UsageError("--threads must be at least 1");
    } else if (a == "--steps") {
      o.max_steps = to_long(a, value());
      if (o.max_steps < 0) throw UsageError("--steps must not be negative");
    } else if (a == "--end-time") {
      const char* s = value();
      if (!parse_real(s, o.end_time) || !(o.end_time > 0.0)) throw UsageError("--end-time needs a positive number");
    } else if (a == "--out-dir") {
      o.out_dir = value();
    } else if (a == "--no-output") {
      o.no_output = true;
    } else if (a == "--summary") {
      o.summary = value();
    } else if (a == "--state") {
      o.state = value();
    } else if (a == "--hdf5") {
      o.hdf5 = true;
    } else if (a == "--checkpoint") {
      o.checkpoint = value();
    } else if (a == "--checkpoint-every") {
      o.checkpoint_every = to_long(a, value());
      if (o.checkpoint_every < 1) throw UsageError("--checkpoint-every must be at least 1");
    } else if (a == "--restart") {
      o.restart = value();
    } else if (a == "--patch-cells") {
      o.patch_given = true;
      o.patch_cells = int(to_long(a, value()));
      if (o.patch_cells < 1 || o.patch_cells > 64) throw UsageError("--patch-cells must lie in 1..64");
    } else if (a == "--particle-order") {
      o.particle_order = value();
      if (o.particle_order != "blocks" && o.particle_order != "deck")
        throw UsageError("--particle-order must be blocks or deck");
    } else if (a == "--regrid-every") {
      o.regrid_every = to_long(a, value());
      if (o.regrid_every < 0 || o.regrid_every > 1000000000) throw UsageError("--regrid-every must lie in 0..1000000000");
    } else if (a == "--scatter") {
      o.scatter = value();
      if (o.scatter != "patches" && o.scatter != "expansion") throw UsageError("--scatter takes patches or expansion");
    } else if (a == "--kernel") {
      o.kernel = value();
    } else if (a == "--kernels") {
      o.kernels = value();
    } else if (a == "--list-stages") {
      for (const char* n : kStageNames) std::cout << n << "\n";
      exit_now = true;
      return o;
    } else if (a == "--strict-energy") {
      o.strict_energy = true;
    } else if (a == "--quiet" || a == "-q") {
      o.quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option " + a);
    } else if (o.deck.empty()) {
      o.deck = a;
    } else {
      throw UsageError("more than one deck given ('" + o.deck + "' and '" + a + "')");
    }
  }
  if (o.deck.empty()) throw UsageError("no deck given");
  if (o.scatter == "expansion" && (!o.kernel.empty() || !o.kernels.empty()))
    throw UsageError("--scatter expansion has C++ kernels only (no --kernel/--kernels with it)");
  return o;
}

std::string json_escape(const std::string& s) {
  std::string r;
  for (char ch : s) {
    if (ch == '"' || ch == '\\') r += '\\', r += ch;
    else if (static_cast<unsigned char>(ch) < 32) r += ' ';
    else r += ch;
  }
  return r;
}

std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

void write_text_atomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    if (!f) throw std::runtime_error("cannot write " + path);
    f << text;
    if (!f) throw std::runtime_error("cannot write " + path);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error("cannot write " + path);
}

bool dir_writable(const std::string& dir) {
  struct stat st;
  return stat(dir.c_str(), &st) == 0 && S_ISDIR(st.st_mode) && access(dir.c_str(), W_OK) == 0;
}

}  // namespace

int run_main(int argc, char** argv) {
  Options opt;
  try {
    bool exit_now;
    opt = parse_args(argc, argv, exit_now);
    if (exit_now) return 0;
    StageTable probe = cxx_stages();
    if (!opt.kernel.empty()) select_stages(probe, opt.kernel, false);
    if (!opt.kernels.empty()) select_stages(probe, opt.kernels, true);
  } catch (const UsageError& e) {
    std::cerr << "mpm3d: " << e.what() << " (see --help)\n";
    return 2;
  } catch (const std::exception& e) {  // bad --kernel/--kernels
    std::cerr << "mpm3d: " << e.what() << "\n";
    return 2;
  }
  try {
    Model model = read_deck(opt.deck);
    if (opt.regrid_every >= 0) model.regrid_every = int(opt.regrid_every);
    {  // --out-dir: created (with its parents) when missing
      std::error_code ec;
      std::filesystem::create_directories(opt.out_dir, ec);
      if (ec) throw std::runtime_error("cannot create output directory '" + opt.out_dir + "': " + ec.message());
    }
    if (!dir_writable(opt.out_dir)) throw std::runtime_error("output directory '" + opt.out_dir + "' is not writable");
    // A checkpoint is written with --checkpoint, --checkpoint-every or on a signal; the
    // default file is name_checkpoint.h5 in the output directory.
    const std::string default_ckpt = opt.out_dir + "/" + model.base_name + "_checkpoint.h5";
    const std::string ckpt_path =
        !opt.checkpoint.empty() ? opt.checkpoint : (opt.checkpoint_every > 0 ? default_ckpt : std::string());
    for (const std::string* f : std::initializer_list<const std::string*>{&opt.summary, &opt.state, &ckpt_path}) {
      if (f->empty()) continue;
      const size_t slash = f->find_last_of('/');
      const std::string d = slash == std::string::npos ? "." : f->substr(0, slash == 0 ? 1 : slash);
      if (!dir_writable(d)) throw std::runtime_error("cannot write '" + *f + "': directory not writable");
    }
#ifdef _OPENMP
    if (opt.threads > 0) omp_set_num_threads(opt.threads);
    const int threads = omp_get_max_threads();
#else
    const int threads = 1;
#endif
    const auto t_start = std::chrono::steady_clock::now();
    // A restart keeps the patch size of the checkpoint (it fixes the summation order).
    const int patch_cells = opt.restart.empty() ? opt.patch_cells : checkpoint_patch_cells(opt.restart);
    Simulation sim(std::move(model), patch_cells,
                   opt.particle_order == "deck" ? ParticleOrder::deck : ParticleOrder::blocks);
    sim.strict_energy = opt.strict_energy;
    {
      StageTable t = cxx_stages();
      if (!opt.kernel.empty()) select_stages(t, opt.kernel, false);
      if (!opt.kernels.empty()) select_stages(t, opt.kernels, true);
      sim.set_stages(t);
      if (opt.scatter == "expansion") {
        // The per-thread copies are a trilinear, single-grid benchmark.
        if (sim.model.gimp || sim.model.contact) throw UsageError("--scatter expansion supports neither 'gimp' nor 'cont'");
        sim.use_expansion_scatter();
      }
    }
    OutputSchedule resume;
    const bool restarted = !opt.restart.empty();
    if (restarted) read_checkpoint(opt.restart, sim, resume);
    const Model& m = sim.model;
    const double end_time = opt.end_time > 0.0 ? opt.end_time : m.endtime;
    const bool series = opt.hdf5 || (m.hdf5 && !opt.no_output);
    LegacyOutput out;
    if (!opt.no_output || series) out.open(m, opt.out_dir, !opt.no_output, series, restarted ? &resume : nullptr);
    install_signal_handlers();
    std::ostringstream head;
    head << "MPM3D-CXX: " << m.title << "\n  deck " << opt.deck << ", " << m.particles.np << " particles, "
         << m.bodies.size() << " bodies, " << m.nmat << " materials\n  grid " << sim.grid.deck_nc[0] << " x "
         << sim.grid.deck_nc[1] << " x " << sim.grid.deck_nc[2] << " cells of " << m.dcell << ", patches of "
         << sim.grid.patch_cells << "^3 cells";
    if (sim.regrid_every > 0) head << ", adaptive: redefined every " << sim.regrid_every << " steps";
    if (sim.expansion_scatter()) head << "\n  scatter: per-thread grid copies (expansion)";
    head << "\n  scheme "
         << (m.scheme == SCHEME_MUSL ? "MUSL" : m.scheme == SCHEME_USL ? "USL" : "USF") << ", dt " << m.dt
         << ", end time " << end_time << ", threads " << threads;
    if (restarted) head << "\n  restarted from " << opt.restart << " at step " << sim.steps << ", t " << sim.time;
    if (opt.patch_given && restarted && opt.patch_cells != patch_cells)
      head << "\n  warning: --patch-cells ignored: a restart keeps the checkpoint's " << patch_cells;
    if (m.gimp) head << "\n  GIMP shape functions (27 nodes)";
    if (m.contact)
      head << "\n  contact between components 1 and 2, friction " << m.contact_mu << ", normals from "
           << (m.contact_normbody == 0 ? std::string("both components") : "component " + std::to_string(m.contact_normbody));
    for (const auto& w : m.warnings) head << "\n  warning: " << w;
    out.log(head.str());
    if (!opt.quiet) std::cout << head.str() << std::endl;
    auto log_regrid = [&]() {
      if (sim.regrid_note.empty()) return;
      out.log(sim.regrid_note);
      if (!opt.quiet) std::cout << sim.regrid_note << std::endl;
      sim.regrid_note.clear();
    };
    log_regrid();

    double step_seconds = 0.0, dt_min = m.dt, dt_max = m.dt, max_epeff = 0.0;
    double next_out = restarted ? resume.next_out : m.outtime, next_rpt = restarted ? resume.next_rpt : m.rpttime;
    if (!restarted && out.animates()) out.frame(m, 0.0, 0);
    const double eps = 1e-9 * m.dt;
    std::string failure;
    std::vector<std::string> energy_warnings;  // printed when raised, listed in the summary
    long steps_run = 0, last_ckpt = restarted ? sim.steps : -1;
    std::string last_ckpt_path = restarted ? opt.restart : std::string();
    auto save_checkpoint = [&](const std::string& path) {
      OutputSchedule o;
      out.save_state(o);
      o.next_out = next_out;
      o.next_rpt = next_rpt;
      write_checkpoint(path, sim, o);
      last_ckpt = sim.steps;
      last_ckpt_path = path;
    };
    int interrupted = 0;
    while (sim.time < end_time - eps && (opt.max_steps < 0 || sim.steps < opt.max_steps)) {
      const auto t0 = std::chrono::steady_clock::now();
      try {
        sim.step();
      } catch (const HealthError& e) {
        failure = e.what();
      }
      ++steps_run;
      step_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      log_regrid();
      for (const auto& w : sim.new_energy_warnings) {
        out.log("warning: " + w);
        if (!opt.quiet) std::cerr << "mpm3d: warning: " << w << std::endl;
        energy_warnings.push_back(w);
      }
      sim.new_energy_warnings.clear();
      if (!failure.empty()) break;
      out.step(m, sim.time, sim.kinetic, sim.internal, sim.momentum);
      if (m.contact) out.contact(sim.time, sim.contact_force);
      if (sim.time >= next_out - eps) {
        if (out.animates()) out.frame(m, sim.time, sim.steps);
        next_out += m.outtime;
      }
      if (sim.time >= next_rpt - eps || sim.time >= end_time - eps) {
        next_rpt += m.rpttime;
        const double left = (end_time - sim.time) / m.dt * (step_seconds / double(steps_run));
        char line[256];
        std::snprintf(line, sizeof line, "step %7ld  t %.4e  KE %.4e  IE %.4e  E %.4e  outside %d  eta %.1f s",
                      sim.steps, sim.time, sim.kinetic, sim.internal, sim.kinetic + sim.internal, sim.outside,
                      left > 0 ? left : 0.0);
        out.log(line);
        if (!opt.quiet) std::cout << line << std::endl;
      }
      if (opt.checkpoint_every > 0 && sim.steps % opt.checkpoint_every == 0) save_checkpoint(ckpt_path);
      if (g_signal) {
        interrupted = int(g_signal);
        break;
      }
    }
    if (!failure.empty()) {
      if (last_ckpt >= 0)
        failure += "; the last checkpoint (step " + std::to_string(last_ckpt) + ") is kept in " + last_ckpt_path;
    } else if (interrupted) {
      const std::string path = ckpt_path.empty() ? default_ckpt : ckpt_path;
      if (last_ckpt != sim.steps || last_ckpt_path != path) save_checkpoint(path);
    } else if (!ckpt_path.empty() && last_ckpt != sim.steps) {
      save_checkpoint(ckpt_path);
    }
    const Particles& P = m.particles;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int p = 0; p < P.np; ++p) {
      max_epeff = std::max(max_epeff, P.epeff[p]);
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], P.x[3 * size_t(p) + a]);
        hi[a] = std::max(hi[a], P.x[3 * size_t(p) + a]);
      }
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    const double ns = steps_run > 0 ? step_seconds * 1e9 / (double(P.np) * double(steps_run)) : 0.0;
    std::vector<std::string> warnings = m.warnings;
    if (sim.outside > 0)
      warnings.push_back(std::to_string(sim.outside) + " particles left the grid and were frozen");
    const size_t printed_already = energy_warnings.size();  // the energy warnings come first
    warnings.insert(warnings.begin() + long(m.warnings.size()), energy_warnings.begin(), energy_warnings.end());
    if (!failure.empty()) warnings.push_back(failure);
    std::string stop_note;
    if (interrupted) {
      stop_note = std::string("interrupted by ") + (interrupted == SIGINT ? "SIGINT" : "SIGTERM") + " at step " +
                  std::to_string(sim.steps) + "; checkpoint " + last_ckpt_path + " (continue with --restart " +
                  last_ckpt_path + ")";
      warnings.push_back(stop_note);
    }
    // The state file holds the final state: not written when a signal stopped the run.
    if (!opt.state.empty() && !interrupted) write_state_h5(opt.state, m, sim.time, sim.steps, m.dt);
    if (!opt.summary.empty()) {
      std::ostringstream js;
      js << "{\n  \"deck\": \"" << json_escape(opt.deck) << "\",\n  \"title\": \"" << json_escape(m.title)
         << "\",\n  \"particles\": " << P.np << ",\n  \"steps\": " << sim.steps << ",\n  \"time\": " << num(sim.time)
         << ",\n  \"dt_min\": " << num(dt_min) << ",\n  \"dt_max\": " << num(dt_max) << ",\n  \"threads\": " << threads
         << ",\n  \"wall_seconds\": " << num(wall) << ",\n  \"ns_per_particle_step\": " << num(ns)
         << ",\n  \"kinetic_energy\": " << num(sim.kinetic) << ",\n  \"internal_energy\": " << num(sim.internal)
         << ",\n  \"initial_total_energy\": " << num(sim.initial_total_energy) << ",\n  \"momentum\": ["
         << num(sim.momentum[0]) << ", " << num(sim.momentum[1]) << ", " << num(sim.momentum[2])
         << "],\n  \"bbox_min\": [" << num(lo[0]) << ", " << num(lo[1]) << ", " << num(lo[2]) << "],\n  \"bbox_max\": ["
         << num(hi[0]) << ", " << num(hi[1]) << ", " << num(hi[2]) << "],\n  \"max_epeff\": " << num(max_epeff)
         << ",\n  \"particles_outside_grid\": " << sim.outside << ",\n  \"scatter\": \"" << opt.scatter
         << "\",\n  \"regrid_every\": " << sim.regrid_every << ",\n  \"regrids\": " << sim.regrids
         << ",\n  \"regrids_forced\": " << sim.regrids_forced << ",\n  \"grid_window_offset\": [" << sim.grid.off[0]
         << ", " << sim.grid.off[1] << ", " << sim.grid.off[2] << "],\n  \"grid_window_cells\": [" << sim.grid.nc[0]
         << ", " << sim.grid.nc[1] << ", " << sim.grid.nc[2] << "],\n  \"patches\": " << sim.stats.patches
         << ",\n  \"patches_empty\": " << sim.stats.empty << ",\n  \"patch_max_particles\": " << sim.stats.max
         << ",\n  \"patch_mean_particles\": " << num(sim.stats.mean)
         << ",\n  \"patch_imbalance\": " << num(sim.stats.imbalance) << ",\n  \"stage_seconds\": {";
      for (int st = 0; st < ST_COUNT; ++st)
        js << (st ? ", " : "") << "\"" << kStageNames[st] << "\": " << num(sim.stage_seconds[st]);
      js << "},\n  \"warnings\": [";
      for (size_t i = 0; i < warnings.size(); ++i) js << (i ? ", " : "") << "\"" << json_escape(warnings[i]) << "\"";
      js << "]\n}\n";
      write_text_atomic(opt.summary, js.str());
    }
    {
      std::ostringstream st;
      st << "stage shares:";
      double total = 0;
      for (double v : sim.stage_seconds) total += v;
      for (int s = 0; s < ST_COUNT; ++s)
        if (sim.stage_seconds[s] > 0) st << " " << kStageNames[s] << " " << int(100.0 * sim.stage_seconds[s] / total + 0.5) << "%";
      out.log(st.str());
      if (!opt.quiet) std::cout << st.str() << std::endl;
    }
    char tail[256];
    std::snprintf(tail, sizeof tail, "%s: %ld steps, t %.6g, %.2f s wall, %.1f ns per particle-step",
                  interrupted ? "stopped" : (failure.empty() ? "done" : "failed"), sim.steps,
                  sim.time, wall, ns);
    out.log(tail);
    if (!opt.quiet) std::cout << tail << std::endl;
    for (size_t i = 0; i < warnings.size(); ++i) {
      const std::string& w = warnings[i];
      const bool printed = i >= m.warnings.size() && i < m.warnings.size() + printed_already;
      if (!opt.quiet && !printed && w != failure && w != stop_note) std::cerr << "mpm3d: warning: " << w << "\n";
    }
    if (!stop_note.empty() || !failure.empty()) out.log(stop_note.empty() ? failure : stop_note);
    out.close();
    if (!failure.empty()) {
      std::cerr << "mpm3d: " << failure << "\n";
      return 3;
    }
    if (interrupted) {
      std::cerr << "mpm3d: " << stop_note << "\n";
      return 128 + interrupted;
    }
    return 0;
  } catch (const DeckError& e) {
    std::cerr << "mpm3d: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "mpm3d: " << opt.deck << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace mpm3d
