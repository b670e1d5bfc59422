// The transfer layer: one unit per shape-function family, each behind the same per-patch
// interface, chosen once when the deck is bound (StepContext::family, set by
// Simulation::bind). The stages (cxx/stages/) keep only the algorithm: P2G scatters and
// assembles through the family, then applies the boundary conditions; G2P updates the
// particles through it; the stress stage computes the node velocities and hands them to
// the family, whose velocity gradients feed one constitutive loop (stress_loop.hpp, or the
// lanes' stress_list).
//   trilinear.cpp          8-node trilinear, in vector lanes (transfer_lanes.hpp)
//   stencil27.cpp          the 27-node stencils of uGIMP and the quadratic B-spline
//   smoothed_gradient.cpp  sgmp: every exchange through the cell centres
// A new point-shape function of the 27-node kind is a shape in core/grid.hpp and a branch
// of gimp_stencil (core/patch_index.hpp). A new family is one file here, one row of
// enum TransferFamily (core/step_state.hpp, with its Fortran twin in stage_common.f90)
// and of transfer_of's table, its choice in Simulation::bind, and in Fortran its calls in
// the stage files and its choice in mpm3d_ref.f90.
#pragma once
#include "core/step_state.hpp"

namespace mpm3d {

struct Transfer {
  // Scatter of the particles into their patches' buffers and the canonical assembly into
  // the nodes (assemble, transfer_common.hpp): mass and momentum (with_mass_mom) and/or forces (with_forces).
  void (*p2g)(StepContext* c, bool with_mass_mom, bool with_forces);
  // Particle velocities and positions from the grid; with remap (MUSL) the nodes' momenta
  // from the updated velocities again (before their boundary conditions).
  void (*g2p)(StepContext* c, bool remap);
  // Every particle's velocity gradient from the node velocities gvel, then its
  // constitutive update.
  void (*stress)(StepContext* c, const double* gvel);
  // Contact: sum_p m_p grad N_i(x_p) of the context's particles into fields 4-6 of the patch
  // buffers, assembled by the contact stage with the boxes this returns (null: whole buffers).
  const int* (*mass_gradient)(StepContext* c);
};

extern const Transfer kTrilinearTransfer;         // trilinear.cpp
extern const Transfer kStencil27Transfer;         // stencil27.cpp
extern const Transfer kSmoothedGradientTransfer;  // smoothed_gradient.cpp

// The trilinear mass gradients, also sgmp's contact normals (trilinear.cpp).
const int* mass_gradient_trilinear(StepContext* c);

// The family of a bound context.
inline const Transfer& transfer_of(const StepContext* c) {
  static const Transfer* const table[TRANSFER_COUNT] = {&kTrilinearTransfer, &kStencil27Transfer,
                                                        &kSmoothedGradientTransfer};
  return *table[c->method.family];
}

}  // namespace mpm3d
