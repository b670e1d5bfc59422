// The g2p stage: particle velocities and positions from the grid, through the deck's
// shape-function family (transfer/transfer.hpp), and with MUSL the remap of the particle
// momenta to the nodes and their boundary conditions.
#include "stages/update_step.hpp"
#include "transfer/transfer.hpp"
#include "transfer/transfer_common.hpp"

using namespace mpm3d;

// v_p += dt_int sum_i N_ip f_i / m_i, x_p += dt sum_i N_ip p_i / m_i over the nodes above
// the mass cut-off; MUSL: p_i = sum_p m_p v_p N_ip again (patch buffers, assembly) and the
// boundary conditions on the momenta.
extern "C" void mpm3d_cxx_g2p(StepContext* c) {
  const bool remap = c->method.scheme == SCHEME_MUSL;
  transfer_of(c).g2p(c, remap);
  if (remap) apply_bc(c, c->grid.gmom);
}
