// The p2g and forces stages: the scatter of mass, momentum and forces into the nodes, through
// the deck's shape-function family (transfer/transfer.hpp), and the boundary conditions.
#include "stages/update_step.hpp"
#include "transfer/transfer.hpp"
#include "transfer/transfer_common.hpp"

using namespace mpm3d;

// m_i = sum_p m_p N_ip, p_i = sum_p m_p v_p N_ip and, unless USF (forces after the stress
// update), f_i = sum_p (-V_p sigma_p G_ip + N_ip (m_p g + f_ext,p)); then the boundary
// conditions on the momenta.
extern "C" void mpm3d_cxx_p2g(StepContext* c) {
  transfer_of(c).p2g(c, true, c->method.scheme != SCHEME_USF);
  apply_bc(c, c->grid.gmom);
}

// USF: f_i with the updated stresses.
extern "C" void mpm3d_cxx_forces(StepContext* c) { transfer_of(c).p2g(c, false, true); }
