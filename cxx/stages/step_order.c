/* The step order of each update scheme (step_order.h). Contact and recontact appear in
   every row where a deck with contact needs them and are skipped without contact. */
#include "stages/step_order.h"

#include <string.h>

/* USF: stress from the P2G velocities, then the forces. With contact, the P2G momenta of
   the nodes in contact at the end of the previous step are corrected again before the
   strain rates read them (their velocities moved the particles). */
static const int kUsf[] = {ST_BIN,    ST_P2G,       ST_RECONTACT, ST_STRESS, ST_FORCES,
                           ST_INTEGRATE, ST_CONTACT, ST_G2P,       ST_ENERGY};
/* USL: stress from the updated grid velocities. */
static const int kUsl[] = {ST_BIN, ST_P2G, ST_INTEGRATE, ST_CONTACT, ST_G2P, ST_STRESS, ST_ENERGY};
/* MUSL: stress from the remapped momenta (G2P remaps them); with contact, the remapped
   momenta of the nodes in contact are corrected again before the stress stage reads them. */
static const int kMusl[] = {ST_BIN, ST_P2G,       ST_INTEGRATE, ST_CONTACT,
                            ST_G2P, ST_RECONTACT, ST_STRESS,    ST_ENERGY};

int mpm3d_step_order(int scheme, int order[MPM3D_MAX_STEP_STAGES]) {
  const int* row;
  int n;
  switch (scheme) {
    case SCHEME_MUSL: row = kMusl; n = (int)(sizeof(kMusl) / sizeof(kMusl[0])); break;
    case SCHEME_USL: row = kUsl; n = (int)(sizeof(kUsl) / sizeof(kUsl[0])); break;
    case SCHEME_USF: row = kUsf; n = (int)(sizeof(kUsf) / sizeof(kUsf[0])); break;
    default: return -1;
  }
  memcpy(order, row, (size_t)n * sizeof(int));
  return n;
}

int mpm3d_stage_needs_contact(int stage) { return stage == ST_CONTACT || stage == ST_RECONTACT; }

int mpm3d_stage_per_component(int stage) {
  return !(stage == ST_CONTACT || stage == ST_RECONTACT || stage == ST_ENERGY);
}
