// mpm3d_taylor STATE.h5 DP [L0]: the Taylor bar measures of a final state.
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "io/analysis.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: mpm3d_taylor STATE.h5 DP [L0=25.4]\n");
    return 2;
  }
  try {
    const double dp = std::atof(argv[2]);
    const double l0 = argc > 3 ? std::atof(argv[3]) : 25.4;
    const auto x = mpm3d::read_state_dataset(argv[1], "position");
    const auto t = mpm3d::taylor_measures(x, dp, l0);
    std::printf("L %.3f D %.3f W %.3f\n", t.length, t.impact_diameter, t.width_02);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mpm3d_taylor: %s\n", e.what());
    return 1;
  }
}
