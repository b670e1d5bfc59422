#include "grid.hpp"

#include <cmath>
#include <stdexcept>

namespace mpm3d {

void Grid::setup(const double lo[3], const double hi[3], double cell, int patch_cells_, int halo) {
  h = cell;
  patch_cells = patch_cells_;
  patch_halo = halo;
  for (int a = 0; a < 3; ++a) {
    origin[a] = lo[a];
    const double n = std::floor((hi[a] - lo[a]) / cell + 0.5);
    if (!(n >= 1.0) || n > 1.0e6) throw std::runtime_error("grid: bad cell count");
    nc[a] = static_cast<int>(n);
    nn[a] = nc[a] + 1;
    npd[a] = (nc[a] + patch_cells - 1) / patch_cells;
  }
  npatch = npd[0] * npd[1] * npd[2];
  const int q = patch_cells + 1 + 2 * halo;
  patch_nodes = q * q * q;
  const size_t nnodes = size_t(nnode());
  mass.assign(nnodes, 0.0);
  mom.assign(3 * nnodes, 0.0);
  force.assign(3 * nnodes, 0.0);
  patch_start.assign(size_t(npatch) + 1, 0);
  patch_slot.assign(size_t(npatch), -1);
  nslot = 0;
  patch_buf.clear();
}

}  // namespace mpm3d
