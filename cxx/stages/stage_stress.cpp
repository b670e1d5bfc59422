// The stress stage: node velocities, then through the deck's shape-function family
// (transfer/transfer.hpp) each particle's velocity gradient and the constitutive update of
// strain and spin increments, volume, stress and internal energy (stress_block,
// constitution.cpp).
#include "core/patch_loops.hpp"
#include "stages/update_step.hpp"
#include "transfer/transfer.hpp"
#include "transfer/transfer_common.hpp"

namespace mpm3d {
namespace {

// Node velocities v_i = p_i / m_i at the nodes above the mass cut-off, once per node (the
// same division as per particle, so the same bits). They are kept in the force array,
// which no stage reads again before the next p2g or forces stage overwrites it (USF:
// stress runs before forces).
double* node_velocities(StepContext* c) {
  const double cutoff = c->grid.mass_cutoff;
  double* gvel = c->grid.gforce;
  for_patches(c, [&](int q) {
    if (patch_at_rest(c, q)) return;
    const OwnedNodes o = owned_nodes(c, q);
    if (!o.active) return;
    for_owned_nodes(c, o, [&](int n) {
      const double m = c->grid.gmass[n];
      if (!(m > cutoff)) return;
      for (int a = 0; a < 3; ++a) gvel[3 * n + a] = c->grid.gmom[3 * n + a] / m;
    });
  });
  return gvel;
}

}  // namespace
}  // namespace mpm3d

using namespace mpm3d;

// Node velocities; per particle L = sum_i v_i (x) G_ip over the nodes above the mass
// cut-off (the family's gradients), then the constitutive update: strain and spin
// increments, volume, Jaumann rotation, stress return, EOS, bulk viscosity, internal energy.
extern "C" void mpm3d_cxx_stress(StepContext* c) { transfer_of(c).stress(c, node_velocities(c)); }
