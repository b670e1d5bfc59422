// update_step: the stages of one explicit MPM time step.
// Every stage takes one StepContext (core/step_state.hpp), a plain C struct of pointers and
// sizes, so the same stage can come from C++ or from the Fortran reference (bind(C)), in any mix.
// The C++ stages are one file each (stage_bin, stage_p2g, stage_grid, stage_g2p,
// stage_stress, stage_energy.cpp); the stage table is in stages.cpp.
#pragma once
#include <cstdint>
#include <string>

#include "core/step_state.hpp"
#include "materials/material.hpp"
#include "stages/step_order.h"

extern "C" {

typedef void (*StageFn)(StepContext*);

// The C++ stages, by file.
void mpm3d_cxx_bin(StepContext* c);        // stage_bin: shape cache, patch lists, buffer slots
void mpm3d_cxx_p2g(StepContext* c);        // stage_p2g: mass, momentum (+ forces unless USF); BC on momentum
void mpm3d_cxx_forces(StepContext* c);     // stage_p2g: USF: internal and body forces after the stress update
void mpm3d_cxx_integrate(StepContext* c);  // stage_grid: p += f dt_int; boundary conditions
void mpm3d_cxx_g2p(StepContext* c);        // stage_g2p: v, x from the grid; MUSL: momentum remap and BC
void mpm3d_cxx_stress(StepContext* c);     // stage_stress: strain and spin increments, volume, stress
void mpm3d_cxx_energy(StepContext* c);     // stage_energy: kinetic, internal energy, momentum, sum |f.v|
void mpm3d_cxx_contact(StepContext* c);    // stage_grid: multi-velocity contact (c->contact.other: comp. 2)
// stage_grid: contact again at the marked nodes (MUSL remap, USF P2G)
void mpm3d_cxx_recontact(StepContext* c);


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

// Boundary conditions of the box faces on a nodal vector field (3,nnode): 1 fixed (all
// components zero), 2 symmetry (normal component zero). stage_grid.cpp.
void apply_bc(const StepContext* c, double* a);

}  // namespace mpm3d
