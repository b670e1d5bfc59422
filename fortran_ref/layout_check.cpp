// Checks that the Fortran bind(C) types step_context and material_params have the layout
// of struct StepContext and struct MaterialParams (cxx/update_step.hpp, cxx/material.hpp).
#include <cstddef>
#include <cstdio>

#include "update_step.hpp"

// The Fortran mirror stops after cell_off: later fields are C++-internal scratch.

extern "C" void mpm3d_f_context_layout(size_t out[11]);

int main() {
  size_t f[11];
  mpm3d_f_context_layout(f);
  const size_t c[11] = {sizeof(StepContext),
                       offsetof(StepContext, result),
                       offsetof(StepContext, np),
                       offsetof(StepContext, fix),
                       offsetof(StepContext, reduce_block),
                       sizeof(MaterialParams),
                       offsetof(MaterialParams, eos_e0),
                       offsetof(MaterialParams, eos_type),
                       offsetof(StepContext, bulk_q2),
                       offsetof(MaterialParams, dp_tension),
                       offsetof(StepContext, cell_off)};
  const char* what[11] = {"sizeof(StepContext)", "offsetof(result)", "offsetof(np)", "offsetof(fix)",
                         "offsetof(reduce_block)", "sizeof(MaterialParams)", "offsetof(eos_e0)",
                         "offsetof(eos_type)", "offsetof(bulk_q2)", "offsetof(dp_tension)", "offsetof(cell_off)"};
  int bad = 0;
  for (int i = 0; i < 11; ++i) {
    // sizeof(StepContext) may exceed the Fortran size by the C++ scratch fields only.
    const bool ok = i == 0 ? (f[0] <= c[0] && f[0] >= offsetof(StepContext, cell_off) + 3 * sizeof(int))
                           : c[i] == f[i];
    std::printf("%-24s C %4zu  Fortran %4zu%s\n", what[i], c[i], f[i], ok ? "" : "  MISMATCH");
    if (!ok) bad = 1;
  }
  return bad;
}
