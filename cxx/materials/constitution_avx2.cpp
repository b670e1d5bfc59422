// The vector stress update of constitution_lanes.hpp compiled for AVX2 (cxx/CMakeLists.txt
// adds -mavx2 to this file alone; no FMA, -ffp-contract=off as everywhere). Packed
// AVX arithmetic is IEEE arithmetic lane by lane, so the bits are those of the baseline
// build; constitution.cpp calls this only on CPUs that report AVX2.
#include "materials/constitution_lanes.hpp"

namespace mpm3d {

void stress_block_avx2(const MaterialParams& m, StressBlock& b, const StressBlockArgs& a) {
  stress_block_lanes<VectorLane<kStressLanes>>(m, b, 0, a);
}

}  // namespace mpm3d
