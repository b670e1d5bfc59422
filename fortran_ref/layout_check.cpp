// Checks that the Fortran bind(C) types step_context and material_params have the layout
// of struct StepContext and struct MaterialParams (cxx/stages/update_step.hpp, cxx/materials/material.hpp),
// and that the Fortran stage and scheme identifiers are those of cxx/step_order.h.
#include <cstddef>
#include <cstdio>

#include "stages/update_step.hpp"

// The Fortran mirror covers the whole struct (the C++ kernels' scratch pointers as
// placeholders), so that the Fortran stages reach the ranks' hooks at its end.
// noutside is the last int before the pointer tlight: the padding before tlight would hide
// one int missing from the ints there, so its own offset is checked.

extern "C" void mpm3d_f_context_layout(size_t out[26]);
extern "C" void mpm3d_f_step_constants(int out[17]);

int main() {
  size_t f[26];
  mpm3d_f_context_layout(f);
  const size_t c[26] = {sizeof(StepContext),
                       offsetof(StepContext, result),
                       offsetof(StepContext, np),
                       offsetof(StepContext, fix),
                       offsetof(StepContext, noutside),
                       sizeof(MaterialParams),
                       offsetof(MaterialParams, eos_e0),
                       offsetof(MaterialParams, eos_type),
                       offsetof(StepContext, bulk_q2),
                       offsetof(MaterialParams, dp_tension),
                       offsetof(StepContext, cell_off),
                       offsetof(StepContext, psize),
                       offsetof(StepContext, ncontact),
                       offsetof(StepContext, defgrad),
                       offsetof(StepContext, uvf),
                       offsetof(StepContext, damping),
                       offsetof(StepContext, tl),
                       offsetof(StepContext, fix_layers),
                       offsetof(StepContext, aux),
                       offsetof(StepContext, sg),
                       offsetof(StepContext, exchange),
                       offsetof(StepContext, order),
                       offsetof(StepContext, prebinned),
                       offsetof(StepContext, sg_cached),
                       offsetof(StepContext, patch_work),
                       offsetof(StepContext, family)};
  const char* what[26] = {"sizeof(StepContext)", "offsetof(result)", "offsetof(np)", "offsetof(fix)",
                         "offsetof(noutside)", "sizeof(MaterialParams)", "offsetof(eos_e0)",
                         "offsetof(eos_type)", "offsetof(bulk_q2)", "offsetof(dp_tension)", "offsetof(cell_off)",
                         "offsetof(psize)", "offsetof(ncontact)",
                         "offsetof(defgrad)", "offsetof(uvf)", "offsetof(damping)", "offsetof(tl)",
                         "offsetof(fix_layers)", "offsetof(aux)", "offsetof(sg)",
                         "offsetof(exchange)", "offsetof(order)", "offsetof(prebinned)",
                         "offsetof(sg_cached)", "offsetof(patch_work)", "offsetof(family)"};
  int bad = 0;
  for (int i = 0; i < 26; ++i) {
    const bool ok = c[i] == f[i];
    std::printf("%-24s C %4zu  Fortran %4zu%s\n", what[i], c[i], f[i], ok ? "" : "  MISMATCH");
    if (!ok) bad = 1;
  }
  int fk[17];
  mpm3d_f_step_constants(fk);
  const int ck[17] = {ST_BIN,       ST_P2G,    ST_FORCES,   ST_INTEGRATE, ST_G2P,     ST_STRESS, ST_ENERGY,
                      ST_CONTACT,   ST_RECONTACT, ST_COUNT, SCHEME_MUSL,  SCHEME_USL, SCHEME_USF,
                      MPM3D_MAX_STEP_STAGES, TRANSFER_TRILINEAR, TRANSFER_STENCIL27,
                      TRANSFER_SMOOTHED_GRADIENT};
  for (int i = 0; i < 17; ++i)
    if (fk[i] != ck[i]) {
      std::printf("step constant %d: C %d  Fortran %d  MISMATCH\n", i, ck[i], fk[i]);
      bad = 1;
    }
  if (!bad) std::printf("stage, scheme and transfer family identifiers: the same\n");
  return bad;
}
