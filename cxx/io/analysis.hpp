// Post-processing used by the tools and tests: the Taylor bar measures and reading a
// state file back.
#pragma once
#include <string>
#include <vector>

namespace mpm3d {

struct TaylorMeasures {
  double length = 0, impact_diameter = 0, width_02 = 0;  // L, D, W(0.2 L0)
};

// The project's definition (../shared/reference/README.md): axis through the mean (x, y)
// of the particles; L = max z - min z + dp; D = 2 max radius of particles with
// z < min z + dp, plus dp; W = the same within dp of min z + 0.2 L0.
TaylorMeasures taylor_measures(const std::vector<double>& x, double dp, double l0);

// Reads /particles/<name> of a state file as doubles (rows x cols flattened).
std::vector<double> read_state_dataset(const std::string& path, const std::string& name);

}  // namespace mpm3d
