// The constitutive loop of the stress stage for the families that give one particle's
// velocity gradient at a time (stencil27.cpp, smoothed_gradient.cpp): runs of particles of
// one material, kStressLanes at a time, through stress_block (constitution.hpp). The
// trilinear family runs the same update in lanes (stress_list, transfer_lanes.hpp).
#pragma once
#include <algorithm>

#include "materials/constitution.hpp"
#include "transfer/transfer_common.hpp"
#include "transfer/transfer_lanes.hpp"

namespace mpm3d {
namespace {

// The constitutive update of the particles list[i] (i where list is null), i in
// [first, first + count): velocity gradients one particle at a time (gradient(dec, i, p, L)), the update
// of kStressLanes consecutive particles of one material at a time (stress_block; a shorter
// run lane by lane, which gives the same bits).
template <class Gradient>
void stress_run(StepContext* c, const CellDecoder& dec, const StressBlockArgs& args, const int* list, int first,
                int count, Gradient& gradient) {
  const bool filter = c->contact.only_comp > 0;
  StressBlock b;
  int part[kStressLanes];
  int n = 0, mat = -1;
  auto flush = [&]() {
    const MaterialParams& mp = c->part.mats[mat];
    if (n == kStressLanes)
      stress_block(mp, b, args);
    else
      for (int i = 0; i < n; ++i) stress_block_lane(mp, b, i, args);
    if (c->rest.still) mark_stress_still(c, mp, part, n, b);
    for (int i = 0; i < n; ++i) stress_block_store(c, part[i], i, b);
    n = 0;
  };
  for (int i = first; i < first + count; ++i) {
    const int p = list ? list[i] : i;
    if (c->part.cell[p] < 0) continue;
    if (filter && other_component(c, p)) continue;
    if (n > 0 && c->part.mat[p] != mat) flush();
    mat = c->part.mat[p];
    double L[9];
    gradient(dec, i, p, L);
    for (int r = 0; r < 9; ++r) b.L[r][n] = L[r];
    stress_block_load(c, c->part.mats[mat], p, n, b);
    part[n++] = p;
    if (n == kStressLanes) flush();
  }
  if (n > 0) flush();
}

// The particle loop of the 27-node stencils: fixed chunks [first, end) of the particles,
// each with its own gradient functor make_gradient(nullptr, end); with patches at rest the
// lists of the others, make_gradient(list, end) for entries [first, end).
template <class MakeGradient>
void stress_particles(StepContext* c, MakeGradient&& make_gradient) {
  const CellDecoder dec(c);
  const StressBlockArgs args = stress_args(c);
  if (c->rest.at_rest) {  // the lists of the patches not at rest (for_stress_lists)
    const int* list = c->patch.patch_part;
    for_stress_lists(c, [&](int first, int count) {
      auto gradient = make_gradient(list, first + count);
      stress_run(c, dec, args, list, first, count, gradient);
    });
    return;
  }
  constexpr int kChunk = 256;
  const int nchunk = (c->part.np + kChunk - 1) / kChunk;
  team_for(nchunk, [&](int ch) {
    const int first = ch * kChunk, end = std::min(c->part.np, first + kChunk);
    auto gradient = make_gradient(nullptr, end);
    stress_run(c, dec, args, nullptr, first, end - first, gradient);
  });
}

}  // namespace
}  // namespace mpm3d
