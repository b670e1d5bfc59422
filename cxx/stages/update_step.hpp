// update_step: the stages of one explicit MPM time step.
// Every stage takes one StepContext, a plain C struct of pointers and sizes, so the
// same stage can come from C++ or from the Fortran reference (bind(C)), in any mix.
// The C++ stages are one file each (stage_bin, stage_p2g, stage_grid, stage_g2p,
// stage_stress, stage_energy.cpp); the stage table is in stages.cpp.
#pragma once
#include <cstdint>
#include <string>

#include "materials/material.hpp"
#include "stages/step_order.h"

extern "C" {

struct StepContext {
  // Particles (np): x, v (3,np); sig (6,np); lx (3,np) local cell coordinates.
  double *x, *v, *sig, *mass, *vol, *epeff, *ie;
  double *temp;     // (np) or null: only with thermal Johnson-Cook materials
  double *fext;     // (3,np) or null: only with point or body loads
  double *lx;       // (3,np) written by the bin stage
  int *mat, *body;  // 0-based
  int *cell;        // (np) base cell index written by the bin stage; -1: outside the grid
  double *gravity;  // (3,nbody) or null
  const MaterialParams *mats;
  // Grid nodes (nnode): mass, momentum (3,nnode), force (3,nnode).
  double *gmass, *gmom, *gforce;
  // Patches: start (npatch+1), particle list (np), slot (npatch), buffers.
  int *patch_start, *patch_part, *patch_slot;
  double *patch_buf;
  double *partials;  // (kReduceFields, npatch + 1) scratch of the energy stage: one column per
                     // patch, the last for the particles outside the grid
  double result[9];  // energy stage: kinetic, internal, momentum (3) in 0..4 and sum |f.v| (the
                     // external work rate of gravity and loads) in 8; contact stage: force (3) in 5..7
  double origin[3];  // lower corner of the deck's box (the lattice origin)
  double h, inv_h, dt, dt_int, mass_cutoff;
  int np, nbody, nmat, nnode;
  int nc[3], nn[3];
  int patch_cells, npd[3], npatch, nslot;
  int fix[6];
  int scheme;
  int has_body_force;  // gravity or loads present: forces carry N * (m g + f_ext)
  int noutside;        // bin stage: particles outside the grid
  // Explosives and bulk viscosity (stress stage only).
  double *tlight;      // (np) lighting time of each particle, or null: only with hiex
  double *qv;          // (np) bulk viscosity pressure of each particle, or null: only with bulk
  double time;         // time at the end of this step (the burn fraction's clock)
  double bulk_q1, bulk_q2;  // bulk viscosity coefficients (quadratic, linear); length h
  int cell_off[3];     // first cell of the grid window on the deck's lattice (adaptive grid):
                       // cell i of the window is cell cell_off + i of the deck's box
  // GIMP shape functions and multi-velocity contact (issue 5): null / 0 when the deck does
  // not ask for them.
  double *psize;             // (np) GIMP particle half-size lp, or null (trilinear)
  const int *body_comp;      // (nbody) contact component (1 or 2) of each body, or null
  struct StepContext *other; // contact: component 2's context, set in component 1's; else null
  double *gnormal;           // contact: (3,nnode) sum_p m_p grad N_i(x_p) of this component
  double *cpartials;         // contact: (kContactFields,npatch) scratch of the contact force and count
  double contact_mu;         // contact: Coulomb friction coefficient
  int shape;                 // 0 trilinear (8 nodes), 1 uGIMP, 2 B-spline (27 nodes)
  int patch_halo;            // node layers a patch buffer holds beyond its cells: 0 or 1 (27 nodes)
  int only_comp;             // 0: every particle; 1 or 2: this context's component only
  int contact_normbody;      // contact normals from component 1, 2, or 0 (both)
  int ncontact;              // contact stage: nodes corrected in this step
  // Finite-strain solids (issue 16).
  double *defgrad;           // (9,np) F - I, row-major, of each particle, or null: only with neoh
  int uvf;                   // 1: volume from det(I + L dt) (UVFp, and always for neoh)
  // Quasi-static loading (the current version's QuLo and Damp; 0: off): the point loads grow
  // linearly over load_ramp_time, and -damping m v joins each particle's body force.
  double load_ramp_time, damping;
  // Total Lagrangian MPM (the current version's TLmp): the bin stage places the particles by
  // xbin (their reference positions; else xbin = x), the force stage takes the first
  // Piola-Kirchhoff stress times the reference volume, pk1 (9,np, row-major), instead of
  // sigma V, and the stress stage integrates F from the reference velocity gradient.
  double *xbin;
  double *pk1;               // (9,np) V0 P, or null (updated Lagrangian)
  int tl;                    // 1: total Lagrangian
  int fix_layers;            // node layers the boundary conditions of a face hold: 1, or 2
                             // (the current version with 27-node stencils or sgmp)
  // Smoothed-gradient MPM (the current version's sgmp): the stages exchange through the
  // cell centres, aux (kAuxFields, ncell) their scratch fields (transfer/smoothed_gradient.cpp); else null, 0.
  double *aux;
  int sg;
  int family;          // the shape-function family (TransferFamily), chosen when the deck is bound
  // Stage-internal scratch of the C++ kernels (the Fortran mirror, step_context in
  // fortran_ref/stage_common.f90, holds them as untouched pointers).
  int *pscratch;       // (np) patch of each particle during binning
  // sgmp: each patch-list entry's auxiliary weights (kSgWeights: the P2G rule's 8, the
  // G2P rule's 8) and centres (8), written by the step's first C++ sgmp stage and read by
  // the later ones (transfer/smoothed_gradient.cpp); else null.
  double *sg_w;
  int *sg_cell;             // (np, 8) the centres of the entry's corners
  unsigned char *sg_reach;  // bits 2a, 2a+1: a corner lies in the patch below, above on axis a
  // Distributed runs (cxx/parallel/ranks.hpp; null with one rank): called between a scatter into the
  // patch buffers and their assembly (kind EXCHANGE_BUFFERS, fields first .. first+count-1),
  // so that the ghost patches' buffers hold their owners' sums, and by the energy stage
  // between its per-patch partials and their fold (EXCHANGE_PARTIALS; the contact stage's:
  // EXCHANGE_CONTACT).
  void (*exchange)(const struct StepContext* c, int kind, int first, int count);
  void *exchange_data;
  // Distributed runs: the particles in one process's storage order (order[i], i = 0..np-1,
  // ascending storage index of the one-rank run), where a rank's arrays hold them in
  // another; null: the arrays' own order. The bin stage fills the patch lists and the
  // energy stage sums the particles outside the grid in this order.
  const int *order;
  // Distributed runs: 1 when cell, lx and pscratch (the patch of every particle, of either
  // contact component) are already those of the particles' positions (the ranks binned
  // them to decide which particles move): the bin stage then only builds the lists.
  int prebinned;
  // C++ kernels' scratch (sgmp): nonzero once a C++ scatter, G2P or stress stage has written
  // sg_w and sg_cell, the weights of the particles' binned places, which the later stages
  // reuse until the next bin (2: with sg_reach, for the scatters of several threads).
  // The driver clears it whenever it bins (every step; TLmp once); the Fortran stages leave
  // it alone.
  int sg_cached;
  // sgmp, C++ kernels only: patches at rest (null when the driver does not look for them;
  // docs/ARCHITECTURE.md "Patches at rest"). sg_still (np): bit 0 set by the stress stage
  // when its update left the particle's stress state bit for bit as it was (unburnt
  // explosive: burn fraction 0), bit 1 by G2P when it left x and v so. sg_rest (npatch): 1
  // where every particle within the reach of one step's data flow is still and at rest:
  // every stage skips the patch, whose values stay those of the step before, the same bits.
  // patch_work (npatch + 1): prefix sums of the patches' work, by which thread_patches
  // shares them (null: the particle counts, patch_start).
  unsigned char* sg_still;
  const unsigned char* sg_rest;
  const int* patch_work;
};

// The shape-function families of the transfer layer (cxx/transfer/transfer.hpp).
enum TransferFamily { TRANSFER_TRILINEAR = 0, TRANSFER_STENCIL27 = 1, TRANSFER_SMOOTHED_GRADIENT = 2, TRANSFER_COUNT = 3 };

typedef void (*StageFn)(StepContext*);

// The C++ stages, by file.
void mpm3d_cxx_bin(StepContext* c);        // stage_bin: shape cache, patch lists, buffer slots
void mpm3d_cxx_p2g(StepContext* c);        // stage_p2g: mass, momentum (+ forces unless USF); BC on momentum
void mpm3d_cxx_forces(StepContext* c);     // stage_p2g: USF: internal and body forces after the stress update
void mpm3d_cxx_integrate(StepContext* c);  // stage_grid: p += f dt_int; boundary conditions
void mpm3d_cxx_g2p(StepContext* c);        // stage_g2p: v, x from the grid; MUSL: momentum remap and BC
void mpm3d_cxx_stress(StepContext* c);     // stage_stress: strain and spin increments, volume, stress
void mpm3d_cxx_energy(StepContext* c);     // stage_energy: kinetic, internal energy, momentum, sum |f.v|
void mpm3d_cxx_contact(StepContext* c);    // stage_grid: multi-velocity contact (c->other: comp. 2)
void mpm3d_cxx_recontact(StepContext* c);  // stage_grid: contact again at the marked nodes (MUSL remap, USF P2G)


// The Fortran reference stages (fortran_ref/update_step.f90, bind(C)), same contracts.
void mpm3d_f_bin(StepContext* c);
void mpm3d_f_p2g(StepContext* c);
void mpm3d_f_forces(StepContext* c);
void mpm3d_f_integrate(StepContext* c);
void mpm3d_f_g2p(StepContext* c);
void mpm3d_f_stress(StepContext* c);
void mpm3d_f_energy(StepContext* c);
void mpm3d_f_contact(StepContext* c);
void mpm3d_f_recontact(StepContext* c);

}  // extern "C"

namespace mpm3d {

extern const char* const kStageNames[ST_COUNT];
constexpr int kAuxFields = 34;  // doubles per cell in StepContext::aux (sgmp)
constexpr int kSgWeights = 16;  // doubles per patch-list entry in StepContext::sg_w (sgmp)
// Fields of the energy stage's columns: kinetic, internal energy, momentum (3), sum |f.v|.
constexpr int kReduceFields = 6;
// StepContext::exchange's kind: what the stage is about to assemble or fold.
enum ExchangeKind { EXCHANGE_BUFFERS = 0, EXCHANGE_PARTIALS = 1, EXCHANGE_CONTACT = 2 };
// Fields of the contact stage's columns: the force on component 1 (3), corrected nodes.
constexpr int kContactFields = 4;

// The stage table: which implementation each stage uses (cxx/stages/stages.cpp).
struct StageTable {
  StageFn fn[ST_COUNT];
};
StageTable cxx_stages();
// True when the Fortran reference kernels are linked in (MPM3D_HAVE_FORTRAN).
bool have_fortran_stages();
StageTable fortran_stages();  // throws std::runtime_error without them
// Applies "--kernel cxx|fortran" or "--kernels stage=lang,..." to a table; throws
// std::invalid_argument naming the bad stage or language.
void select_stages(StageTable& t, const std::string& spec, bool per_stage);

}  // namespace mpm3d
