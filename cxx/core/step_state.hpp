// The step state: the one struct every step stage takes (stages/update_step.hpp), whether
// the stage comes from C++ or from the Fortran reference (bind(C)), in any mix. It sits in
// the lowest layer because the transfer families, the stages, the deck binding, the solver
// and the ranks all stand on it (docs/ARCHITECTURE.md, "Layers").
#pragma once
#include <cstdint>

extern "C" {

struct MaterialParams;  // materials/material.hpp (the stages that read it include it)

// The step state, in named groups, one C-interoperable layout (the Fortran reference's
// step_context in fortran_ref/stage_common.f90 mirrors it; fref_layout checks every member's
// offset). Arrays are the model's own, not copies; a null pointer or a 0 says the deck does
// not use the feature. The C++ kernels' scratch (pscratch, sg_w, sg_cell, sg_reach,
// sg_cached, patches at rest) is held by the Fortran mirror as untouched members.
// The particles (np) and their materials and bodies.
struct StepParticles {
  double *x, *v, *sig, *mass, *vol, *epeff, *ie;  // x, v (3,np); sig (6,np); mass, vol, epeff, ie (np)
  double *temp;  // (np) or null: only with thermal Johnson-Cook materials
  double *fext;  // (3,np) or null: only with point or body loads
  double *lx;  // (3,np) local cell coordinates, written by the bin stage
  int *mat, *body;  // (np) 0-based
  int *cell;  // (np) base cell index written by the bin stage; -1: outside the grid
  double *gravity;  // (3,nbody) or null
  const MaterialParams *mats;  // (nmat)
  double *tlight;  // (np) lighting time of each particle, or null: only with hiex
  double *qv;  // (np) bulk viscosity pressure of each particle, or null: only with bulk
  double *psize;  // (np) GIMP particle half-size lp, or null
  double *defgrad;  // (9,np) F - I, row-major, or null: only with neoh
  double *xbin;  // (3,np) the positions the bin stage places: x, or the reference ones (TLmp)
  double *pk1;  // (9,np) V0 P, row-major (TLmp), or null (updated Lagrangian)
  int np, nbody, nmat;
};

// The background grid's window and its node arrays (nnode).
struct StepGrid {
  double *gmass, *gmom, *gforce;  // mass, momentum (3,nnode), force (3,nnode)
  double origin[3];  // lower corner of the deck's box (the lattice origin)
  double h, inv_h, mass_cutoff;
  int nnode;
  int nc[3], nn[3];  // cells and nodes per axis of the window
  int cell_off[3];  // first cell of the window on the deck's lattice (adaptive grid)
  int fix[6];  // boundary condition of each box face: 0 free, 1 fixed, 2 symmetry
  int fix_layers;  // node layers a held face holds: 1, or 2 (current version, 27 nodes or sgmp)
};

// The patch decomposition: lists, buffers and their sizes.
struct StepPatches {
  int *patch_start, *patch_part, *patch_slot;  // start (npatch+1), particle list (np), slot (npatch)
  double *patch_buf;  // the non-empty patches' buffers (kNodeFields per node)
  int *pscratch;  // C++ kernels' scratch: (np) patch of each particle during binning
  const int *patch_work;  // (npatch + 1) prefix sums of the patches' work for thread_patches, or null
  // C++ kernels' scratch: (6, slots) the nodes [lo, hi) per axis, buffer-local, that the
  // 27-node scatters touched in each buffer (assemble skips the rest; stencil27.cpp)
  int *patch_box;
  int patch_cells;  // cells per patch edge
  int npd[3];  // patches per axis
  int npatch, nslot, patch_halo;  // patch_halo: node layers a buffer holds beyond its cells
};

// The step's time.
struct StepClock {
  double dt, dt_int, time;  // time: at the end of this step (the burn fraction's clock)
};

// What the deck asks of the step.
struct StepMethod {
  double bulk_q1, bulk_q2;  // bulk viscosity coefficients (quadratic, linear); length h
  double load_ramp_time, damping;  // QuLo: the point loads ramp over this time; Damp: -damping m v (0: off)
  int scheme;  // SCHEME_MUSL, SCHEME_USL or SCHEME_USF
  int has_body_force;  // gravity or loads present: forces carry N * (m g + f_ext)
  int uvf;  // 1: volume from det(I + L dt) (UVFp, and always for neoh)
  int tl;  // 1: total Lagrangian (TLmp)
  int shape;  // 0 trilinear (8 nodes), 1 uGIMP, 2 B-spline (27 nodes)
  int sg;  // 1: smoothed-gradient MPM (sgmp)
  int family;  // the shape-function family (TransferFamily), chosen when the deck is bound
};

// What the energy, bin and contact stages report.
struct StepResults {
  // (kReduceFields, npatch + 1) the energy stage's columns, the last for the particles outside the grid
  double *partials;
  // energy: kinetic, internal, momentum (3) in 0..4, sum |f.v| in 8, sum f.v (loads as
  // P2G applies them, without damping) in 9; contact: force in 5..7
  double result[10];
  int noutside;  // bin stage: particles outside the grid
};

// Multi-velocity contact; null / 0 without it.
struct StepContact {
  const int *body_comp;  // (nbody) contact component (1 or 2) of each body, or null
  struct StepContext *other;  // component 2's context, set in component 1's; else null
  double *gnormal;  // (3,nnode) sum_p m_p grad N_i(x_p) of this component
  double *cpartials;  // (kContactFields, npatch) scratch of the contact force and count
  double contact_mu;  // Coulomb friction coefficient
  int only_comp;  // 0: every particle; 1 or 2: this context's component only
  int contact_normbody;  // normals from component 1, 2, or 0 (both)
  int ncontact;  // contact stage: nodes corrected in this step
};

// Smoothed-gradient MPM's state (transfer/smoothed_gradient.cpp); null / 0 otherwise.
struct StepSgmp {
  double *aux;  // (kAuxFields, ncell) the cell centres' fields
  double *sg_w;  // C++ kernels: each patch-list entry's weights (kSgWeights)
  int *sg_cell;  // C++ kernels: (np, 8) the centres of the entry's corners
  uint16_t *sg_reach;  // C++ kernels: bits 2a, 2a+1: a corner lies in the patch below, above on axis a
                       // (16 bits: a char store may alias every field, which made the
                       // weights loop reload them; 0.98 of the 2-thread sgmp time)
  int sg_cached;  // C++ kernels: nonzero once sg_w and sg_cell hold this bin's weights (2: with sg_reach)
};

// Distributed runs (cxx/solver/ranks.hpp, implemented in cxx/parallel/); null / 0 with one rank.
struct StepRanks {
  // called between a scatter and its assembly, and before the energy and contact columns are folded
  void (*exchange)(const struct StepContext* c, int kind, int first, int count);
  void *exchange_data;
  const int *order;  // (np) the particles in one process's storage order, or null
  int prebinned;  // 1: cell, lx and pscratch already hold the particles' binning
};

// C++ kernels: patches at rest (docs/ARCHITECTURE.md); null when not looked for.
struct StepRest {
  unsigned char *still;  // (np) bit 0: the stress update changed nothing; bit 1: G2P changed nothing
  const unsigned char *at_rest;  // (npatch) 1 where every stage skips the patch
};

// Where we deliberately differ from the original programs: one named rule each, chosen once
// when the deck is bound (core/rules.hpp: names, values, presets; docs/FROM_MPM3D_F90.md).
// 0 is always our own value, the default; each member is read where its rule acts and
// nowhere else. The deck-level rules (program .. bulk_book, deck_reals) act in the reader
// and the solver; the others in the stages.
struct StepRules {
  int program;        // 0 the book program's conventions, 1 the current program's
  int time_step;      // 0 the initial dt kept (book), 1 recomputed every step (current)
  int bulk_book;      // book program: 0 'bulk' applied, 1 read and ignored (the book program)
  int bulk_switch;    // bulk viscosity where 0 the volume shrinks, 1 the mean stress is compressive too
                      // (the new one in models without an EOS, the old one with)
  int bulk_linear;    // 0 every material, linear term with its wave speed; 1 the current program's
                      // (none with a linear or JWL EOS, so none on hiex; linear term on elas, neoh, null only)
  int burn;           // programmed burn: 0 ramp over 1.5 cells, 1 step at the lighting time
  int dp_return;      // Drucker-Prager: 0 returns end on the yield surface, 1 the original's branches
  int deck_reals;     // 0 deck reals read in double precision, 1 rounded to single as the original
  int tl_shape;       // TLmp: 0 shape functions at the reference position, 1 at the cell's centre
                      // with the current volume in the work of P on dF (the current program)
  int sg_lower;       // sgmp auxiliary cell next to a lower face: 0 the nearest centre, 1 truncated toward 0
  int sg_beyond;      // sgmp weights of centres beyond a one-layer grid: 0 to the nearest centre, 1 dropped
  int fluid_viscous;  // viscous null: 0 stress 2 mu dev(D), 1 2 mu D (the original's integer 1/3)
  int bulk_work;      // work of the bulk viscosity q: 0 by the mean of the old and new q, 1 by the
                      // new q over the whole step (the current program; twice for john)
  int pressure_q;     // output variable pres (curves, frames): 0 the stress's pressure, q included,
                      // 1 without q (the current program writes its mean stress apart from q)
  int clay_return;    // clay: 0 the return solved to consistency (Newton), 1 the newest program's one
                      // linearised step, scaled to the yield stress at the new epeff
  int null_eos;       // null with an EOS: 0 the EOS as the deck gives it, 1 its first coefficient (c0,
                      // C0, A; Mie-Gruneisen's rho0 c0^2) replaced by the null's wave speed (current program)
  int start_temp;     // particles' starting temperature: 0 the card's room temperature, 1 293 whatever the
                      // card says (both original programs)
  int contact;        // contact: 0 ours (recontact stage; force corrections d / dt_int), 1 the originals'
                      // (no recontact; d / dt, so the first step's half dt moves the particles by d / 2)
};

struct StepContext {
  struct StepParticles part;
  struct StepGrid grid;
  struct StepPatches patch;
  struct StepClock clock;
  struct StepMethod method;
  struct StepResults out;
  struct StepContact contact;
  struct StepSgmp sgmp;
  struct StepRanks ranks;
  struct StepRest rest;
  struct StepRules rules;
};

// The shape-function families of the transfer layer (cxx/transfer/transfer.hpp).
enum TransferFamily {
  TRANSFER_TRILINEAR = 0,
  TRANSFER_STENCIL27 = 1,
  TRANSFER_SMOOTHED_GRADIENT = 2,
  TRANSFER_COUNT = 3
};

}  // extern "C"

namespace mpm3d {

constexpr int kAuxFields = 34;  // doubles per cell in StepContext::aux (sgmp)
constexpr int kSgWeights = 16;  // doubles per patch-list entry in StepContext::sg_w (sgmp)
// Fields of the energy stage's columns: kinetic, internal energy, momentum (3), sum |f.v|.
constexpr int kReduceFields = 7;
// StepContext::exchange's kind: what the stage is about to assemble or fold.
enum ExchangeKind { EXCHANGE_BUFFERS = 0, EXCHANGE_PARTIALS = 1, EXCHANGE_CONTACT = 2 };
// Fields of the contact stage's columns: the force on component 1 (3), corrected nodes.
constexpr int kContactFields = 4;

}  // namespace mpm3d
