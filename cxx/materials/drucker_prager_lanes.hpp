// Drucker-Prager (dpm), written for a lane type T (constitution_lanes.hpp): its return
// branches four ways, so every lane runs the scalar dp_return (constitution.cpp, where
// the formulas are) one at a time. Internal linkage (lanes.hpp).
#pragma once
#include "core/lanes.hpp"
#include "materials/constitution.hpp"
#include "materials/material.hpp"

namespace mpm3d {
namespace {  // internal linkage, see lanes.hpp

template <class T, class TL>
struct DruckerPragerLanes {
  // Drucker-Prager, one lane at a time (its returns branch in four ways).
  static T dp_return(const MaterialParams& m, T s[6], T& sm, double K, double G) {
    T deps;
    for (int i = 0; i < TL::W; ++i) {
      double si[6], smi = TL::get(sm, i);
      for (int c = 0; c < 6; ++c) si[c] = TL::get(s[c], i);
      TL::set(deps, i, mpm3d::dp_return(m, si, &smi, K, G));
      for (int c = 0; c < 6; ++c) TL::set(s[c], i, si[c]);
      TL::set(sm, i, smi);
    }
    return deps;
  }
};

}  // namespace
}  // namespace mpm3d
