#include "io/analysis.hpp"

#include <hdf5.h>

#include "io/h5_quiet.hpp"

#include <cmath>
#include <stdexcept>

namespace mpm3d {

TaylorMeasures taylor_measures(const std::vector<double>& x, double dp, double l0) {
  const size_t n = x.size() / 3;
  if (n == 0) throw std::invalid_argument("no particles");
  double cx = 0, cy = 0, zmin = INFINITY, zmax = -INFINITY;
  for (size_t p = 0; p < n; ++p) {
    cx += x[3 * p];
    cy += x[3 * p + 1];
    zmin = std::min(zmin, x[3 * p + 2]);
    zmax = std::max(zmax, x[3 * p + 2]);
  }
  cx /= double(n);
  cy /= double(n);
  const double zw = zmin + 0.2 * l0;
  double rd = 0, rw = 0;
  for (size_t p = 0; p < n; ++p) {
    const double r = std::hypot(x[3 * p] - cx, x[3 * p + 1] - cy);
    const double z = x[3 * p + 2];
    if (z < zmin + dp) rd = std::max(rd, r);
    if (std::fabs(z - zw) <= dp) rw = std::max(rw, r);
  }
  return {zmax - zmin + dp, 2.0 * rd + dp, 2.0 * rw + dp};
}

std::vector<double> read_state_dataset(const std::string& path, const std::string& name) {
  const H5ErrorSilencer quiet;  // our own messages instead; the caller's handler is restored
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw std::runtime_error("cannot open " + path);
  hid_t d = H5Dopen2(f, ("/particles/" + name).c_str(), H5P_DEFAULT);
  if (d < 0) {
    H5Fclose(f);
    throw std::runtime_error("no dataset /particles/" + name + " in " + path);
  }
  hid_t s = H5Dget_space(d);
  const hssize_t count = H5Sget_simple_extent_npoints(s);
  std::vector<double> v(size_t(count > 0 ? count : 0));
  const herr_t st = H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(s);
  H5Dclose(d);
  H5Fclose(f);
  if (st < 0) throw std::runtime_error("cannot read /particles/" + name + " from " + path);
  return v;
}

}  // namespace mpm3d
