/* The stages of one explicit step and their order for each update scheme: the one table
   that the C++ driver (Simulation::step), the Fortran reference driver (mpm3d_ref.f90,
   through bind(C)) and the mixed --kernels runs all walk. Adding a scheme is one new row
   in step_order.c (and its kernels). Plain C, so that both languages link it. */
#ifndef MPM3D_STEP_ORDER_H
#define MPM3D_STEP_ORDER_H

#ifdef __cplusplus
extern "C" {
#endif

/* Update schemes (the deck's 'musl', 'usl', 'usf'); stage_common.f90 repeats the values. */
enum UpdateScheme { SCHEME_MUSL = 0, SCHEME_USL = 1, SCHEME_USF = 2 };

/* Stage identifiers; fortran_ref/update_step.f90 repeats the values (ST_*), and the
   layout check (fref_layout) compares them. */
enum Stage {
  ST_BIN,        /* particles to cells and patches */
  ST_P2G,        /* mass and momentum (+ forces unless USF) to the grid */
  ST_FORCES,     /* USF: internal and body forces after the stress update */
  ST_INTEGRATE,  /* nodal momenta from the forces; boundary conditions */
  ST_G2P,        /* particle velocities and positions; MUSL: momentum remap */
  ST_STRESS,     /* strain and spin increments, volume, stress */
  ST_ENERGY,     /* kinetic and internal energy, momentum */
  ST_CONTACT,    /* multi-velocity contact of the two components */
  ST_RECONTACT,  /* contact again at the nodes marked by the last contact */
  ST_COUNT
};

/* The longest row of the table. */
#define MPM3D_MAX_STEP_STAGES 16

/* Copies the stages of one step of `scheme` (SCHEME_MUSL, SCHEME_USL or SCHEME_USF) into order[0 .. n-1] and returns n; -1 for an unknown scheme. */
int mpm3d_step_order(int scheme, int order[MPM3D_MAX_STEP_STAGES]);

/* 1 when the stage runs only in a deck with contact (cont), else 0. */
int mpm3d_stage_needs_contact(int stage);

/* 1 when the stage runs on each contact component's context in turn, 0 when it runs once
   on component 1's: the contact pair (it reaches component 2 through `other`) and the
   energy (it sums every particle, whatever the component). */
int mpm3d_stage_per_component(int stage);

#ifdef __cplusplus
}
#endif
#endif
