// The simulation (cxx/solver/simulation.hpp): set-up and binding of the step contexts, one step
// through the stage table, the adaptive regrid and the energy measure (the checks after
// every step: health_checks.cpp).
#include "solver/simulation.hpp"

#include "core/patch_loops.hpp"
#include "materials/constitution.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace mpm3d {
namespace {

// Patches at rest: how far, in cells, the data of one step reaches. With sgmp a particle's
// update reads the cell centres of its auxiliary cell (one cell either side),
// which read their corner nodes (one more), which gather the centres next to them (one
// more), which the particles of their own and the neighbouring cells scatter to (one more):
// 3 cells from the particles' start-of-step state to a G2P. MUSL's remap and stress go
// round once more from the updated velocities (6 cells), and USF's G2P reads the forces of
// the stresses it updated first (8). A 27-node stencil reaches at most 2 cells each way
// (the B-spline's node base - 1 of a particle near base + 1: 4, 8, 8), a trilinear one 1
// (2, 4, 4). So a patch whose every patch within 8 cells holds only particles that are
// still and at rest computes this step exactly what it computed in the step before.
constexpr int kRestReachCells = 8;
// The work of a particle of a patch at rest (binning, the energy sums) against one that is
// computed, for the threads' shares (thread_patches). Most stages skip the patches at rest,
// so the shares follow the computed particles: 1 to 32 ran 0.86-0.92 of the time of 1 to 8
// at 2 threads on the explosive columns, 1 to 64 and 1 to 1024 no faster
// (docs/PERFORMANCE.md).
constexpr int kMovingWork = 32;
// Keeping the still bits costs every particle a comparison in G2P and the stress stage; a
// scene where no patch is quiet (a vibrating beam) checks again only every this many steps.
// Skipping begins at most this many steps later than it could; the results are the same.
constexpr long kRestProbeSteps = 16;

inline uint64_t bits_of(double x) {
  uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// Particle p, as it stands, would be left as it is by a step whose grid values near it are
// all zero: its last G2P and stress update changed no bit of it (still bits 0 and 1),
// its velocity and stress are zero (either sign) and, an explosive, it is unlit at time t.
inline bool particle_quiet(const StepContext* c, const unsigned char* still, int p, double t) {
  if (still[p] != 3) return false;
  // Velocity and stress all +-0: their bits less the sign bits are all clear (a NaN's are
  // not), tested at once rather than nine compares with a branch each.
  uint64_t bits = 0;
  const double* v = c->part.v + 3 * p;
  const double* s = c->part.sig + 6 * size_t(p);
  for (int k = 0; k < 3; ++k) bits |= bits_of(v[k]);
  for (int k = 0; k < 6; ++k) bits |= bits_of(s[k]);
  if ((bits << 1) != 0) return false;
  const MaterialParams& mp = c->part.mats[c->part.mat[p]];
  return !(c->part.tlight && mp.type == MAT_HIEX) || burn_fraction(mp, c->part.tlight[p], t, c->rules.burn != 0) == 0.0;
}

}  // namespace

Simulation::Simulation(Model m, int patch_cells, ParticleOrder order) : model(std::move(m)), stages_(cxx_stages()) {
  if (patch_cells < 1) throw std::invalid_argument("patch size must be at least one cell");
  // A GIMP stencil reaches one node beyond its patch's cells; the node loops find every
  // node a patch's particles touch among its own and its neighbours' nodes only when a
  // patch is at least two cells wide.
  if ((model.shape() != 0 || model.sg) && patch_cells < 2)
    throw std::invalid_argument(std::string(model.gimp ? "GIMP" : model.sg ? "sgmp" : "B-spline") +
                                " needs patches of at least two cells");
  double hi[3];
  for (int a = 0; a < 3; ++a) hi[a] = model.box_hi[a];
  // 27-node stencils and sgmp's cell centres reach one node beyond a patch's cells.
  const int halo = (model.shape() != 0 || model.sg) ? 1 : 0;
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
  // Binning of the initial state: the energy stage sums over the patch lists, and the patch
  // statistics before the first step (every step bins again).
  bin_particles();
  measure();
  initial_total_energy = kinetic + internal;
  if (regrid_every > 0) {
    regrids = 1;
    note_regrid(0);
  }
}

namespace {

// The context's grid arrays and patch buffers are those of grid g.
void point_at_grid(StepContext& c, Grid& g) {
  c.grid.gmass = g.mass.data();
  c.grid.gmom = g.mom.data();
  c.grid.gforce = g.force.data();
  c.patch.patch_start = g.patch_start.data();
  c.patch.patch_part = g.patch_part.data();
  c.patch.patch_slot = g.patch_slot.data();
  c.patch.patch_buf = g.patch_buf.data();
  c.patch.patch_box = g.patch_box.data();
}

// Room in g's patch buffers for the patches binned into c.patch.nslot slots (a quarter more, so
// that a slowly growing count does not reallocate every step).
void ensure_patch_buffer(StepContext& c, Grid& g) {
  const size_t need = size_t(c.patch.nslot) * size_t(g.patch_nodes) * kNodeFields;
  if (g.patch_buf.size() < need) {
    g.patch_buf.resize(need + need / 4);
    c.patch.patch_buf = g.patch_buf.data();
    g.patch_box.resize(6 * (g.patch_buf.size() / (size_t(g.patch_nodes) * kNodeFields)));
    c.patch.patch_box = g.patch_box.data();
  }
}

}  // namespace

void Simulation::bind() {
  Particles& P = model.particles;
  StepContext& c = ctx;
  auto or_null = [](std::vector<double>& v) { return v.empty() ? nullptr : v.data(); };
  // The particles: the model's arrays, the bin stage's cell and lx, the bodies' gravity.
  pscratch_.resize(size_t(P.np), 0);  // written by the bin stage (or the ranks) before it is read
  gravity_.assign(3 * model.bodies.size(), 0.0);
  for (size_t b = 0; b < model.bodies.size(); ++b)
    for (int a = 0; a < 3; ++a) gravity_[3 * b + a] = model.bodies[b].gravity[a];
  StepParticles& pt = c.part;
  pt.x = P.x.data();
  pt.v = P.v.data();
  pt.sig = P.sig.data();
  pt.mass = P.mass.data();
  pt.vol = P.vol.data();
  pt.epeff = P.epeff.data();
  pt.ie = P.ie.data();
  pt.temp = or_null(P.temp);
  pt.fext = or_null(P.fext);
  pt.tlight = or_null(P.tlight);
  pt.qv = or_null(P.qv);
  pt.lx = lx_.data();
  pt.mat = P.mat.data();
  pt.body = P.body.data();
  pt.cell = cell_.data();
  pt.gravity = gravity_.data();
  pt.mats = model.mats.data();
  pt.np = P.np;
  pt.nbody = int(model.bodies.size());
  pt.nmat = int(model.mats.size());
  pt.psize = model.gimp ? P.psize.data() : nullptr;
  pt.defgrad = or_null(P.defgrad);
  pt.xbin = model.tl ? P.x0.data() : P.x.data();  // TLmp: the particles stay in their reference cells
  pt.pk1 = model.tl ? P.pk1.data() : nullptr;
  // The grid's constants (its arrays: bind_grid) and the patches' size.
  c.grid.h = grid.h;
  c.grid.inv_h = 1.0 / grid.h;
  c.grid.mass_cutoff = grid.mass_cutoff;
  for (int f = 0; f < 6; ++f) c.grid.fix[f] = grid.fix[f];
  c.grid.fix_layers = model.fix_layers();
  c.patch.pscratch = pscratch_.data();
  c.patch.patch_cells = grid.patch_cells;
  c.patch.patch_halo = grid.patch_halo;  // GIMP, B-spline, sgmp: one node layer beyond the cells
  c.clock.dt = model.dt;
  c.clock.dt_int = model.dt;
  // What the deck asks of the step, and its shape-function family (transfer/transfer.hpp).
  StepMethod& me = c.method;
  me.scheme = model.scheme;
  me.has_body_force = (model.has_gravity || model.has_loads || model.damping > 0.0) ? 1 : 0;
  me.load_ramp_time = model.load_ramp_time;
  me.damping = model.damping;
  me.bulk_q1 = model.bulk_q1;
  me.bulk_q2 = model.bulk_q2;
  me.shape = model.shape();
  me.tl = model.tl ? 1 : 0;
  me.uvf = model.uvf ? 1 : 0;
  me.sg = model.sg ? 1 : 0;
  me.family = model.sg ? TRANSFER_SMOOTHED_GRADIENT : me.shape != 0 ? TRANSFER_STENCIL27 : TRANSFER_TRILINEAR;
  c.rules = model.rules;
  // Contact: set below when the deck has it.
  c.contact.body_comp = nullptr;
  c.contact.other = nullptr;
  c.contact.gnormal = nullptr;
  c.contact.cpartials = nullptr;
  c.contact.only_comp = 0;
  // sgmp: the cell centres' scratch fields (the grid window is the whole box: no regrid) and
  // the C++ kernels' per-entry weights.
  if (model.sg) {
    aux_.assign(size_t(kAuxFields) * size_t(grid.nc[0]) * size_t(grid.nc[1]) * size_t(grid.nc[2]), 0.0);
    sg_w_.assign(size_t(kSgWeights) * size_t(P.np), 0.0);
    sg_cell_.assign(8 * size_t(P.np), 0);
    sg_reach_.assign(size_t(P.np), 0);
  }
  c.sgmp.aux = model.sg ? aux_.data() : nullptr;
  c.sgmp.sg_w = model.sg ? sg_w_.data() : nullptr;
  c.sgmp.sg_cell = model.sg ? sg_cell_.data() : nullptr;
  c.sgmp.sg_reach = model.sg ? sg_reach_.data() : nullptr;
  forget_rest();  // new arrays: nothing is known still
  bind_grid();  // before the contact copy: ctx2 starts as a copy of ctx
  if (model.contact) {
    // Two contexts over the same particles: each bins, scatters and updates the particles
    // of its component on its own grid; the contact stage (in ctx) couples the two grids.
    body_comp_.assign(model.bodies.size(), 1);
    for (size_t b = 0; b < model.bodies.size(); ++b) body_comp_[b] = model.bodies[b].component;
    // The nodes' contact marks outlive a rebinding after particles changed rank (USF reads
    // them in the next step); zero when the grid is new.
    if (gnormal1_.size() != 3 * size_t(grid.nnode())) gnormal1_.assign(3 * size_t(grid.nnode()), 0.0);
    if (gnormal2_.size() != 3 * size_t(grid.nnode())) gnormal2_.assign(3 * size_t(grid.nnode()), 0.0);
    cpartials_.assign(size_t(kContactFields) * size_t(grid.npatch), 0.0);
    c.contact.body_comp = body_comp_.data();
    c.contact.contact_mu = model.contact_mu;
    c.contact.contact_normbody = model.contact_normbody;
    c.contact.cpartials = cpartials_.data();
    ctx2 = c;
    c.contact.only_comp = 1;
    c.contact.gnormal = gnormal1_.data();
    c.contact.other = &ctx2;
    ctx2.contact.only_comp = 2;
    ctx2.contact.gnormal = gnormal2_.data();
    point_at_grid(ctx2, grid2);
  }
}

void Simulation::bind_grid() {
  StepContext& c = ctx;
  point_at_grid(c, grid);
  for (int a = 0; a < 3; ++a) {
    c.grid.origin[a] = grid.origin[a];
    c.grid.nc[a] = grid.nc[a];
    c.grid.nn[a] = grid.nn[a];
    c.patch.npd[a] = grid.npd[a];
    c.grid.cell_off[a] = grid.off[a];
  }
  c.grid.nnode = grid.nnode();
  c.patch.npatch = grid.npatch;
  // The energy stage's columns: one per patch and one for the particles outside the grid.
  const size_t ncolumn_values = size_t(kReduceFields) * (size_t(grid.npatch) + 1);
  if (partials_.size() != ncolumn_values) partials_.assign(ncolumn_values, 0.0);
  c.out.partials = partials_.data();
}

void Simulation::regrid(int escaped) {
  int off[3], nc[3];
  const Particles& P = model.particles;
  WindowExtent e = window_extent(grid, P.x.data(), P.v.data(), P.np);
  if (ranks) {  // every rank's particles: the extents merged by min and max (exact)
    std::vector<double> m = {-double(e.cmin[0]), -double(e.cmin[1]), -double(e.cmin[2]), double(e.cmax[0]),
                             double(e.cmax[1]),  double(e.cmax[2]),  e.vmax2};
    ranks->max(m);
    for (int a = 0; a < 3; ++a) {
      e.cmin[a] = -int(m[size_t(a)]);
      e.cmax[a] = int(m[3 + size_t(a)]);
    }
    e.vmax2 = m[6];
  }
  window_of_extent(grid, e, regrid_every > 0 ? regrid_every : 1, model.dt, off, nc);
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

void Simulation::set_grid(const double origin[3], double h, const int deck_nc[3], int patch_cells, const int off[3],
                          const int nc[3]) {
  if (patch_cells < 1) throw std::invalid_argument("patch size must be at least one cell");
  double hi[3];
  for (int a = 0; a < 3; ++a) hi[a] = origin[a] + double(deck_nc[a]) * h;
  grid.define(origin, hi, h, patch_cells, (model.shape() != 0 || model.sg) ? 1 : 0);
  for (int a = 0; a < 3; ++a)
    if (grid.deck_nc[a] != deck_nc[a]) throw std::runtime_error("grid: cannot rebuild the stored grid");
  grid.set_window(off, nc);
  for (int f = 0; f < 6; ++f) grid.fix[f] = model.fix[f];
  grid.mass_cutoff = model.mass_cutoff;
  grid.patch_part.assign(size_t(model.particles.np), 0);
  bind();
  lists_binned_ = false;  // the new grid's lists are empty until bin_particles or a step
  reference_bin_holds_ = false;
}

void Simulation::bin_particles() {
  forget_rest();  // the particles may have been replaced (a restart)
  ctx.sgmp.sg_cached = ctx2.sgmp.sg_cached = 0;
  stages_.fn[ST_BIN](&ctx);
  if (model.contact) stages_.fn[ST_BIN](&ctx2);
  lists_binned_ = true;
  reference_bin_holds_ = model.tl && !ranks;
  stats = patch_stats(grid, ctx.patch.patch_start, model.contact ? ctx2.patch.patch_start : nullptr);
  // The patch buffers for these lists now, with the set-up, rather than in the first step:
  // their zero-filling and first touch (1.5 MB on taylor_coarse, 22 us a step averaged over
  // 200 steps at 1 thread) is no part of a step's cost.
  ensure_patch_buffers();
}

void Simulation::distribute(Ranks& r) {
  ranks = &r;
  r.distribute(*this);
}

void Simulation::particles_changed() {
  // This step's time step and clock (Simulation::step sets them before the bin stage, where
  // the particles move between ranks) outlive the rebinding.
  const double dt = ctx.clock.dt, dt_int = ctx.clock.dt_int, t = ctx.clock.time;
  // The per-particle scratch keeps its rows (the ranks may have binned them already, moving
  // them with the particles: StepContext::prebinned).
  const size_t np = size_t(model.particles.np);
  reference_bin_holds_ = false;
  lx_.resize(3 * np, 0.0);
  cell_.resize(np, -1);
  grid.patch_part.resize(np, 0);
  if (model.contact) grid2.patch_part.resize(np, 0);
  bind();
  for (StepContext* c : {&ctx, &ctx2}) {
    c->clock.dt = dt;
    c->clock.dt_int = dt_int;
    c->clock.time = t;
  }
}

void Simulation::ensure_patch_buffers() {
  ensure_patch_buffer(ctx, grid);
  if (model.contact) ensure_patch_buffer(ctx2, grid2);
}

void Simulation::step() {
  StepContext* c = &ctx;
  const double kinetic_before = kinetic;
  c->clock.dt = model.dt;
  c->clock.dt_int = steps == 0 ? 0.5 * model.dt : model.dt;  // first step: momentum with dt/2
  c->clock.time = time + model.dt;  // the end of this step (programmed burn)
  const bool contact = model.contact;
  if (contact) {
    ctx2.clock.dt = c->clock.dt;
    ctx2.clock.dt_int = c->clock.dt_int;
    ctx2.clock.time = c->clock.time;
  }
  // The scheme's row of the step table (step_order.c), walked as the Fortran driver does.
  int order[MPM3D_MAX_STEP_STAGES];
  const int nstage = mpm3d_step_order(c->method.scheme, order);
  if (nstage < 0) throw std::logic_error("unknown update scheme " + std::to_string(c->method.scheme));
  c->rest.at_rest = nullptr;  // the bin stage shares the patches by their particles
  c->patch.patch_work = nullptr;
  c->rest.still = nullptr;  // mark_rest sets it when this step keeps the still bits
  for (int k = 0; k < nstage; ++k) {
    const int s = order[k];
    if (mpm3d_stage_needs_contact(s) && !contact) continue;
    if (s == ST_RECONTACT && c->rules.contact) continue;  // rule contact=original
    if (s == ST_BIN) {
      bin_stage();
      const bool rest = rest_possible();
      if (rest != rest_on_) {  // switched on or off: nothing is known still
        forget_rest();
        rest_on_ = rest;
      }
      track_ = rest && (any_quiet_ || steps % kRestProbeSteps == 0);
      if (track_) {
        timed(ST_BIN, [&] { mark_rest(); });  // with the bin stage, as the quiet check below
      } else if (rest) {  // not kept this step: nothing is known still in the next
        std::fill(still_.begin(), still_.end(), 0);
        quiet_before_.clear();
      }
      continue;
    }
    run_stage(s);
    if (s == ST_CONTACT) {  // both grids integrated: the pair's momenta and forces corrected
      for (int a = 0; a < 3; ++a) contact_force[a] = c->out.result[5 + a];
      contact_nodes = c->contact.ncontact;
    }
  }
  if (track_)
    timed(ST_BIN, [&] {
      quiet_patches(quiet_before_);  // this step's lists, for the next
      any_quiet_ = false;  // a patch with particles, every one of them quiet
      for (int q = 0; q < c->patch.npatch && !any_quiet_; ++q)
        any_quiet_ = quiet_before_[size_t(q)] && c->patch.patch_start[q + 1] > c->patch.patch_start[q];
    });
  outside = c->out.noutside + (contact ? ctx2.out.noutside : 0);
  if (ranks) outside = int(ranks->sum(outside));
  kinetic = c->out.result[0];
  internal = c->out.result[1];
  for (int a = 0; a < 3; ++a) momentum[a] = c->out.result[2 + a];
  ++steps;
  time += model.dt;
  // The bound of the work of gravity and loads: the energy stage's sum of |f . v| with the
  // end-of-step velocities (0 without body forces), times this step's dt.
  external_work += c->out.result[8] * model.dt;
  load_work += c->out.result[9] * model.dt;
  if (model.dt_per_step) model.dt = velocity_time_step();
  if (model.dynamic_relaxation && kinetic - kinetic_before <= 0.0) {
    std::fill(model.particles.v.begin(), model.particles.v.end(), 0.0);
    kinetic = 0.0;
  }
  health_check();
}

double Simulation::velocity_time_step() {
  const double* v = model.particles.v.data();
  const long n = 3L * model.particles.np;
  // A max: the same bits for any thread count.
  double vmax = team_reduce(
      n, 0.0,
      [&](long lo, long hi, double& m) {
        double here = m;  // a local: m may alias v for all the compiler knows
        for (long i = lo; i < hi; ++i) here = std::max(here, std::fabs(v[i]));
        m = here;
      },
      [](double& a, double b) { a = std::max(a, b); });
  if (ranks) vmax = ranks->max(vmax);
  double dt = std::numeric_limits<double>::infinity();
  for (const MaterialParams& mp : model.mats) dt = std::min(dt, model.dcell / (mp.wave_speed + vmax));
  return dt * model.dtscale;
}

bool Simulation::rest_possible() const {
  // Grid values at rest are zero momenta and forces only without gravity, loads and
  // damping; one process, one grid, one current position per particle; and the still bits
  // are written by the C++ G2P and stress stages, whose skipping the other stages share.
  if (!skip_rest || model.tl || model.contact || ranks) return false;
  if (model.has_gravity || model.has_loads || model.damping > 0.0 || model.dynamic_relaxation) return false;
  const StageTable cxx = cxx_stages();
  for (int s : {ST_BIN, ST_P2G, ST_FORCES, ST_INTEGRATE, ST_G2P, ST_STRESS})
    if (stages_.fn[s] != cxx.fn[s]) return false;
  return true;
}

void Simulation::forget_rest() {
  still_.assign(0, 0);  // allocated when first kept (mark_rest)
  quiet_before_.clear();
  ctx.rest.still = nullptr;
  ctx.rest.at_rest = nullptr;
  ctx.patch.patch_work = nullptr;
  rest_on_ = false;
  track_ = any_quiet_ = false;
}

void Simulation::quiet_patches(std::vector<unsigned char>& quiet) const {
  const StepContext* c = &ctx;
  const int npatch = c->patch.npatch;
  quiet.assign(size_t(npatch), 0);
  const unsigned char* still = still_.data();
  unsigned char* out = quiet.data();
  const double t = c->clock.time;
  team_for(npatch, [&](int q) {
    bool all = true;
    for (int e = c->patch.patch_start[q]; all && e < c->patch.patch_start[q + 1]; ++e)
      all = particle_quiet(c, still, c->patch.patch_part[e], t);
    out[q] = all ? 1 : 0;
  });
}

void Simulation::mark_rest() {
  StepContext* c = &ctx;
  const int npatch = c->patch.npatch;
  if (still_.size() != size_t(model.particles.np)) still_.assign(size_t(model.particles.np), 0);
  quiet_patches(quiet_);
  // Quiet now over this step's lists and at the end of the step before over its lists: a
  // particle that moved out of a patch's reach in that step was still listed there.
  if (quiet_before_.size() != size_t(npatch)) quiet_before_.assign(size_t(npatch), 0);
  for (int q = 0; q < npatch; ++q) quiet_[size_t(q)] = quiet_[size_t(q)] & quiet_before_[size_t(q)];
  // At rest: every patch within kRestReachCells quiet, one axis at a time.
  const int r = (kRestReachCells + c->patch.patch_cells - 1) / c->patch.patch_cells;
  rest_ = quiet_;
  ring_.assign(size_t(npatch), 0);
  long stride = 1;
  for (int a = 0; a < 3; ++a) {
    const int len = c->patch.npd[a];
    for (int q = 0; q < npatch; ++q) {
      const int i = int((q / stride) % len);
      const int lo = i - r < 0 ? 0 : i - r, hi = i + r >= len ? len - 1 : i + r;
      unsigned char all = 1;
      for (int j = lo; j <= hi && all; ++j) all = rest_[size_t(q + (j - i) * stride)];
      ring_[size_t(q)] = all;
    }
    rest_.swap(ring_);
    stride *= len;
  }
  patch_work_.assign(size_t(npatch) + 1, 0);
  // The weighted sums as ints while they fit (else the threads share by particles).
  const bool weigh = long(model.particles.np) * kMovingWork <= long(std::numeric_limits<int>::max());
  long resting = 0;
  for (int q = 0; q < npatch; ++q) {
    const int n = c->patch.patch_start[q + 1] - c->patch.patch_start[q];
    if (rest_[size_t(q)]) resting += n;
    if (weigh) patch_work_[size_t(q) + 1] = patch_work_[size_t(q)] + n * (rest_[size_t(q)] ? 1 : kMovingWork);
  }
  rest_particle_steps += resting;
  c->rest.still = still_.data();
  // No particle at rest: the still bits are kept, but the stages run as without the rest
  // skip (one thread's plain scatter, no reach masks): a scene where nothing rests pays
  // only for the bits.
  c->rest.at_rest = resting > 0 ? rest_.data() : nullptr;
  c->patch.patch_work = resting > 0 && weigh ? patch_work_.data() : nullptr;
}

void Simulation::run_stage(int s) {
  timed(s, [&] { stages_.fn[s](&ctx); });
  if (model.contact && mpm3d_stage_per_component(s)) timed(s, [&] { stages_.fn[s](&ctx2); });
}

void Simulation::bin_stage() {
  StepContext* c = &ctx;
  // TLmp bins the reference positions (StepContext::xbin): with the grid and the particles
  // those of the last bin, its cells, local coordinates, lists and slots are this step's,
  // bit for bit (one process: ranks bin in their migration).
  if (reference_bin_holds_) return;  // and so do the sgmp weights cached from it
  ctx.sgmp.sg_cached = ctx2.sgmp.sg_cached = 0;  // the particles are binned again below
  // The adaptive window: a scheduled regrid before binning; a regrid and a second binning
  // when a particle inside the deck's box has left the window, so that the window never
  // freezes a particle the box would not have frozen.
  const bool scheduled = regrid_every > 0 && steps > 0 && steps % regrid_every == 0;
  if (scheduled) timed(ST_BIN, [&] { regrid(0); });
  auto migrate = [&]() {  // the ranks' binning and migration: part of the bin stage's time
    timed(ST_BIN, [&] { ranks->migrate(*this); });
  };
  if (ranks) migrate();
  run_stage(ST_BIN);
  lists_binned_ = true;
  int escaped = 0;
  if (!grid.window_is_box()) {
    if (c->out.noutside > 0) escaped = count_escaped(grid, c->part.x, c->part.cell, c->part.np);
    if (ranks) escaped = int(ranks->sum(escaped));
    if (escaped > 0) {
      timed(ST_BIN, [&] { regrid(escaped); });
      if (ranks) migrate();  // the new window's patches, drawn over the ranks again
      run_stage(ST_BIN);
    }
  }
  stats = patch_stats(grid, c->patch.patch_start, model.contact ? ctx2.patch.patch_start : nullptr);
  reference_bin_holds_ = model.tl && !ranks;
  if (ranks) ranks->add_ghost_slots(*this);  // also the patch statistics of every rank's particles
  if (scheduled || escaped > 0) note_regrid(escaped);
  ensure_patch_buffers();
}

void Simulation::measure() {
  // The sums are folded over the patch lists: they must come from a bin of these particles.
  if (!lists_binned_) throw std::logic_error("Simulation::measure: the particles are not binned");
  stages_.fn[ST_ENERGY](&ctx);
  kinetic = ctx.out.result[0];
  internal = ctx.out.result[1];
  for (int a = 0; a < 3; ++a) momentum[a] = ctx.out.result[2 + a];
}

}  // namespace mpm3d
